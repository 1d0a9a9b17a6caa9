#include "output_dir.hpp"


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

}  // namespace sonarmap::cli
