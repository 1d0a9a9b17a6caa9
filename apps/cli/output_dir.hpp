#pragma once
// Output folders of the commands that write several files (`simulate`, `demo`): created when
// missing, removed again when the run fails.

#include <filesystem>
#include <string>
#include <vector>

namespace sonarmap::cli {

/// An output folder, created (with its missing parents) by the constructor. Unless keep() is
/// called, the destructor removes the folders it created, if they are still empty: a failed run
/// leaves nothing behind, and a folder that existed before is never touched.
class OutputDir {
 public:
  /// @throws FileError when `path` exists and is not a folder, or cannot be created.
  explicit OutputDir(const std::string& path);
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  ~OutputDir();

  /// The path of `name` inside the folder.
  std::string file(const std::string& name) const;
  /// The run succeeded: keep the folder.
  void keep() { keep_ = true; }

 private:
  void removeCreated() const;

  std::filesystem::path path_;
  std::vector<std::filesystem::path> created_;  ///< deepest last
  bool keep_ = false;
};

}  // namespace sonarmap::cli
