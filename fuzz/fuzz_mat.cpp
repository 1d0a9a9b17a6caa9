// libFuzzer harness: CRAS Micron MAT-file bytes (through a temporary file: libmatio reads paths)
// → readCrasMat (libmatio, or the walk of mat_cut.cpp for a file cut short).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/mat_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".mat");
  const std::string& path = file.write(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readCrasMat(path); });
}
