#include "sonarmap/io/atomic_file.hpp"

#include <atomic>
#include <fstream>
#include <random>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

std::filesystem::path temporaryBeside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::random_device entropy;
  std::string name = ".";  // appended piecewise: GCC 12 warns falsely on "." + std::string
  name += target.filename().string();
  name += ".tmp";
  name += std::to_string(entropy() % 1000000U);
  name += "_";
  name += std::to_string(counter++);
  return target.parent_path() / name;
}

void removeQuietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

}  // namespace

FileTransaction::~FileTransaction() {
  for (const Staged& file : staged_) removeQuietly(file.temporary);
}

void FileTransaction::stage(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path target(path);
  if (target.filename().empty()) throw FileError("cannot write '" + path + "': not a file name");
  const std::filesystem::path temporary = temporaryBeside(target);
  try {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError("cannot write '" + path + "': cannot create a file in its folder");
    write(out);
    out.flush();
    if (!out) throw FileError("cannot write '" + path + "': writing failed (disk full?)");
  } catch (...) {
    removeQuietly(temporary);
    throw;
  }
  staged_.push_back({temporary, target});
}

void FileTransaction::stageBytes(const std::string& path, std::span<const unsigned char> bytes) {
  stage(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

void FileTransaction::commit() {
  while (!staged_.empty()) {
    const Staged file = staged_.front();
    std::error_code error;
    std::filesystem::rename(file.temporary, file.target, error);
    if (error) throw FileError("cannot write '" + file.target.string() + "': " + error.message());
    staged_.erase(staged_.begin());
  }
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  FileTransaction transaction;
  transaction.stage(path, write);
  transaction.commit();
}

void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes) {
  FileTransaction transaction;
  transaction.stageBytes(path, bytes);
  transaction.commit();
}

}  // namespace sonarmap
