// libFuzzer harness: gzip-compressed point-scan CSV bytes (a temporary `.csv.gz` file) →
// readPointScansCsv through openTextInput's inflating stream.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "sonarmap/slam/point_scans.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static sonarmap::fuzz::InputFile file(".csv.gz");
  const std::string& path = file.write(data, size);
  return sonarmap::fuzz::expectReadOrError([&] { sonarmap::readPointScansCsv(path); });
}
