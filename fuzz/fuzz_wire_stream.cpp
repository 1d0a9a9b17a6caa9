// libFuzzer harness: WireStreamDecoder fed the input in random chunks must give what the whole
// input gives at once (beams, skipped count, skip lines). Byte 0 picks the protocol (even: SeaNet,
// odd: Ping360 raw stream) and seeds the chunk sizes; the rest is the stream. A difference traps.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/formats/wire_stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using sonarmap::Beam;
  if (size == 0) return 0;
  const sonarmap::LogFormat format = data[0] % 2 == 0 ? sonarmap::LogFormat::kSeaNet : sonarmap::LogFormat::kPing360;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);
  const sonarmap::SonarLog whole = sonarmap::WireStreamDecoder(format, {}, "fuzz").decodeAll(stream);

  sonarmap::WireStreamDecoder decoder(format, {}, "fuzz");
  std::vector<Beam> beams;
  std::vector<std::string> reasons;
  std::uint32_t state = data[0] * 2654435761U + 1U;
  for (std::size_t at = 0; at < stream.size();) {
    state = state * 1664525U + 1013904223U;
    const std::size_t chunk = std::min<std::size_t>(stream.size() - at, 1 + (state >> 24) % 97);
    for (Beam& beam : decoder.feed(stream.subspan(at, chunk))) beams.push_back(std::move(beam));
    for (std::string& reason : decoder.takeSkipReasons()) reasons.push_back(std::move(reason));
    at += chunk;
  }
  for (Beam& beam : decoder.finish()) beams.push_back(std::move(beam));
  for (std::string& reason : decoder.takeSkipReasons()) reasons.push_back(std::move(reason));

  bool same = beams.size() == whole.beams.size() && decoder.skippedItems() == whole.skipped_beams &&
              reasons == whole.skip_reasons;
  for (std::size_t i = 0; same && i < beams.size(); ++i) {
    same = beams[i].bearing_rad == whole.beams[i].bearing_rad && beams[i].intensities == whole.beams[i].intensities &&
           beams[i].bin_length_m == whole.beams[i].bin_length_m;
  }
  if (!same) std::abort();
  return 0;
}
