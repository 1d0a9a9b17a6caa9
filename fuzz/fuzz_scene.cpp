// libFuzzer harness: simulator scene file (ground truth) bytes → readScene.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/sim/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto in = sonarmap::fuzz::inputStream(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readScene(in, "fuzz.scene"); });
}
