// libFuzzer harness: raw Tritech SeaNet wire capture bytes → parseSeaNetCapture.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/seanet_capture.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::parseSeaNetCapture({data, size}, "fuzz.seanet"); });
}
