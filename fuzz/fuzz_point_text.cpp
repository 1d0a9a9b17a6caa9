// libFuzzer harness: `x y z` text cloud bytes → readPointText.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/io/point_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto in = sonarmap::fuzz::inputStream(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readPointText(in, "fuzz.xyz"); });
}
