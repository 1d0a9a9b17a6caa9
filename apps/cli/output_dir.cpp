#include "output_dir.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {

namespace fs = std::filesystem;

OutputDir::OutputDir(const std::string& path) : path_(path) {
  std::error_code ec;
  if (fs::exists(path_, ec) && !fs::is_directory(path_, ec)) {
    throw FileError("output folder '" + path + "' exists and is not a folder");
  }
  for (fs::path level = fs::absolute(path_); !level.empty() && !fs::exists(level, ec); level = level.parent_path()) {
    created_.insert(created_.begin(), level);
  }
  if (!fs::create_directories(path_, ec) && ec) {
    removeCreated();
    throw FileError("cannot create output folder '" + path + "': " + ec.message());
  }
}

OutputDir::~OutputDir() {
  if (!keep_) removeCreated();
}

void OutputDir::removeCreated() const {
  std::error_code ec;  // fs::remove leaves a folder that is not empty and reports it in ec
  for (auto level = created_.rbegin(); level != created_.rend(); ++level) fs::remove(*level, ec);
}

std::string OutputDir::file(const std::string& name) const { return (path_ / name).string(); }

namespace {

/// A fresh folder under the system's temporary folder, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string name = (fs::temp_directory_path() / "sonarmap_scratch_XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) {
      throw FileError("cannot create a scratch folder '" + name + "': " + std::strerror(errno));
    }
    path_ = name;
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

}  // namespace

void stageFromPathWriter(FileTransaction& outputs, const std::string& target,
                         const std::function<void(const std::string& path)>& write) {
  const ScratchDir scratch;
  const fs::path file = scratch.path() / fs::path(target).filename();
  write(file.string());
  std::ifstream in(file, std::ios::binary);
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw FileError("cannot read back the scratch file '" + file.string() + "'");
  outputs.stageBytes(target, bytes);
}

}  // namespace sonarmap::cli
