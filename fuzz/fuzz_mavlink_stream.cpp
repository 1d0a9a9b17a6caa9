// libFuzzer harness: a MAVLink stream (sonarmap live --nav-stream from an autopilot) fed in
// pseudo-random chunks of 1–300 bytes (byte 0 seeds the sizes) to MavlinkFrameParser,
// MavlinkNavigation and NavigationStream. None throws: any two ways of cutting the bytes give the
// same frames and counts, every byte is a frame's, noise or held; every fix is finite and later than
// the one before.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/mavlink_navigation.hpp"
#include "sonarmap/formats/navigation_stream.hpp"

namespace {

using sonarmap::MavlinkFrame;
using sonarmap::NavSample;

std::vector<std::span<const std::uint8_t>> chunks(std::span<const std::uint8_t> stream, std::uint32_t state) {
  std::vector<std::span<const std::uint8_t>> out;
  for (std::size_t at = 0; at < stream.size();) {
    state = state * 1664525U + 1013904223U;
    const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + (state >> 20) % 300);
    out.push_back(stream.subspan(at, n));
    at += n;
  }
  return out;
}

std::size_t frameBytes(const MavlinkFrame& f) {
  return (f.version == 2 ? 10 : 6) + f.payload_length + 2 + (f.is_signed ? sonarmap::kMavlinkSignatureBytes : 0);
}

void requireIncreasing(const std::vector<NavSample>& fixes, double& last_s) {
  for (const NavSample& f : fixes) {
    if (!sonarmap::isFinite(f) || !(f.time_s > last_s)) std::abort();
    last_s = f.time_s;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  const auto a = chunks(stream, data[0] * 2654435761U + 1U);
  const auto b = chunks(stream, 7U);

  sonarmap::MavlinkFrameParser pa, pb;
  std::vector<MavlinkFrame> fa, fb;
  for (const auto chunk : a) pa.feed(chunk, fa);
  for (const auto chunk : b) pb.feed(chunk, fb);
  if (fa.size() != fb.size()) std::abort();
  std::size_t frame_bytes = 0;
  for (std::size_t i = 0; i < fa.size(); ++i) {
    if (fa[i].message_id != fb[i].message_id || fa[i].payload != fb[i].payload || fa[i].checked != fb[i].checked) std::abort();
    frame_bytes += frameBytes(fa[i]);
  }
  const sonarmap::MavlinkStreamCounts& ca = pa.counts();
  if (ca.noise_bytes != pb.counts().noise_bytes || ca.bad_frames != pb.counts().bad_frames) std::abort();
  if (frame_bytes + ca.noise_bytes + pa.heldBytes() != ca.bytes) std::abort();

  // Arrivals from the chunk index with a jitter, so clock offsets go up and down.
  sonarmap::MavlinkNavigation nav("fuzz", {.pressure = {}, .max_hold_s = 0.5});
  sonarmap::NavigationStream either("fuzz");
  double last_nav_s = -INFINITY, last_either_s = -INFINITY;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double arrival_s = 0.01 * static_cast<double>(i) + 0.003 * static_cast<double>((i * 7) % 5);
    requireIncreasing(nav.feed(a[i], arrival_s), last_nav_s);
    requireIncreasing(either.feed(a[i], arrival_s), last_either_s);
  }
  requireIncreasing(nav.finish(), last_nav_s);
  requireIncreasing(either.finish(), last_either_s);
  (void)nav.description();
  (void)either.description();
  (void)nav.takeNotes();
  (void)either.takeNotes();
  return 0;
}
