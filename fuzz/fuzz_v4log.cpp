// libFuzzer harness: Tritech SeaNet .V4LOG bytes → parseSeaNetV4Log.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/v4log_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sonarmap::fuzz::expectReadOrError(
      [&] { sonarmap::parseSeaNetV4Log({data, size}, "fuzz.V4LOG"); });
}
