// libFuzzer harness: MAVLink telemetry log bytes (a BlueROV2's .tlog) → parseMavlinkTlogNavigation
// (frames, checksums, the boot clock put on UTC, the joined track).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sonarmap::fuzz::expectReadOrError(
      [&] { (void)sonarmap::parseMavlinkTlogNavigation(std::span<const std::uint8_t>(data, size), "fuzz.tlog"); });
}
