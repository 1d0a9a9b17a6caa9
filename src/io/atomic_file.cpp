#include "sonarmap/io/atomic_file.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <random>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

std::filesystem::path temporaryBeside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::random_device entropy;
  const std::string suffix = ".tmp" + std::to_string(entropy() % 1000000U) + "_" + std::to_string(counter++);
  return target.parent_path() / ("." + target.filename().string() + suffix);
}

/// Removes the temporary file unless released.
struct TemporaryFile {
  std::filesystem::path path;
  bool keep = false;
  ~TemporaryFile() {
    if (!keep) {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
  }
};

}  // namespace

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path target(path);
  if (target.filename().empty()) throw FileError("cannot write '" + path + "': not a file name");
  TemporaryFile temporary{temporaryBeside(target)};
  {
    std::ofstream out(temporary.path, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError("cannot write '" + path + "': cannot create a file in its folder");
    write(out);
    out.flush();
    if (!out) throw FileError("cannot write '" + path + "': writing failed (disk full?)");
  }
  std::error_code error;
  std::filesystem::rename(temporary.path, target, error);
  if (error) throw FileError("cannot write '" + path + "': " + error.message());
  temporary.keep = true;
}

void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace sonarmap
