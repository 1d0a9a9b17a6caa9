#pragma once
/// @file fuzz_input.hpp
/// What every libFuzzer harness of sonarmap shares: the contract that a reader either returns or
/// throws a sonarmap::Error (any other exception escapes and libFuzzer reports it as a crash), and
/// a temporary file for the readers that take a path (libmatio needs a real file).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap::fuzz {

/// Runs `read()`; a sonarmap::Error is the expected answer to bad input and is swallowed. Anything
/// else (std::bad_alloc, std::out_of_range, a crash, a sanitizer report) is a finding.
template <class Read>
int expectReadOrError(Read&& read) {
  try {
    read();
  } catch (const Error&) {
  }
  return 0;
}

/// Reads every beam of `source` in two passes, as `map` reads a log beam by beam.
inline void readTwice(BeamSource& source) {
  for (int pass = 0; pass < 2; ++pass) {
    source.rewind();
    while (source.next()) {
    }
  }
}

/// The input as a stream of bytes (binary-safe).
inline std::istringstream inputStream(const std::uint8_t* data, std::size_t size) {
  return std::istringstream(std::string(reinterpret_cast<const char*>(data), size), std::ios::binary);
}

/// The input written to one temporary file per process (named with the pid and `extension`),
/// rewritten for every input and removed at exit.
class InputFile {
 public:
  explicit InputFile(std::string_view extension)
      : path_(std::filesystem::temp_directory_path() /
              ("sonarmap-fuzz-" + std::to_string(::getpid()) + std::string(extension))) {}
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  ~InputFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }

  /// Writes the input and returns the file's path.
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream(path_, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                  static_cast<std::streamsize>(size));
    name_ = path_.string();
    return name_;
  }

 private:
  std::filesystem::path path_;
  std::string name_;
};

}  // namespace sonarmap::fuzz
