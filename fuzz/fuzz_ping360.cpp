// libFuzzer harness: Ping360 bytes (Ping Viewer log or raw ping-protocol stream) → parsePing360.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/formats/ping360_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::parsePing360({data, size}, "fuzz.bin"); });
}
