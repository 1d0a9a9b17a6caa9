// libFuzzer harness: NavCsvStream (sonarmap live --nav-stream) fed the input in pseudo-random
// chunks of 1–97 bytes (byte 0 seeds the sizes). It never throws: every fix it gives is finite and
// later than the one before, and any way of cutting the bytes gives the same fixes and skip count.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "sonarmap/nav/navigation.hpp"

namespace {
std::vector<sonarmap::NavSample> chunked(std::span<const std::uint8_t> stream, std::uint32_t state, std::size_t& skipped) {
  sonarmap::NavCsvStream rows("fuzz");
  std::vector<sonarmap::NavSample> fixes;
  for (std::size_t at = 0; at < stream.size();) {
    state = state * 1664525U + 1013904223U;
    const std::size_t chunk = std::min<std::size_t>(stream.size() - at, 1 + (state >> 24) % 97);
    for (const sonarmap::NavSample& fix : rows.feed(stream.subspan(at, chunk))) fixes.push_back(fix);
    at += chunk;
  }
  skipped = rows.skippedRows();
  return fixes;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  std::size_t skipped_a = 0, skipped_b = 0;
  const std::vector<sonarmap::NavSample> a = chunked(stream, data[0] * 2654435761U + 1U, skipped_a);
  const std::vector<sonarmap::NavSample> b = chunked(stream, 7U, skipped_b);
  if (a.size() != b.size() || skipped_a != skipped_b) std::abort();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i].time_s) || a[i].time_s != b[i].time_s || a[i].position_ned_m != b[i].position_ned_m) std::abort();
    if (i > 0 && !(a[i].time_s > a[i - 1].time_s)) std::abort();
  }
  return 0;
}
