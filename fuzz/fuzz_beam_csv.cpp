// libFuzzer harness: beam CSV bytes (through a temporary file) → readBeamCsv.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/beam_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".csv");
  const std::string& path = file.write(data, size);
  sonarmap::fuzz::expectReadOrError([&] { sonarmap::fuzz::readTwice(*sonarmap::openBeamCsv(path)); });
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readBeamCsv(path); });
}
