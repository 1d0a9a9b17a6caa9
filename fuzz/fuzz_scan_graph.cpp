// libFuzzer harness: OctoMap scan graph (.graph) bytes → readScanGraph.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/io/scan_graph.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto in = sonarmap::fuzz::inputStream(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readScanGraph(in, "fuzz.graph"); });
}
