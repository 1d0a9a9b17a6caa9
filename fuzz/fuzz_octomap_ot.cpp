// libFuzzer harness: OctoMap full tree (.ot) bytes → readFull, then a walk over every leaf of
// what was read (a tree that reads must also be usable).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/io/octomap_full.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto in = sonarmap::fuzz::inputStream(data, size);
  return sonarmap::fuzz::expectReadOrError([&] {
    const sonarmap::OcTree16 tree = sonarmap::readFull(in, {}, "fuzz.ot");
    (void)tree.counts();
  });
}
