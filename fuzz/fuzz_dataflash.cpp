// libFuzzer harness: ArduPilot dataflash log bytes (a BlueROV2's .BIN) → parseDataflashNavigation
// (FMT records, records of the types they define, the joined track and the GPS clock).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sonarmap::fuzz::expectReadOrError(
      [&] { (void)sonarmap::parseDataflashNavigation(std::span<const std::uint8_t>(data, size), "fuzz.BIN"); });
}
