#pragma once
/// @file atomic_file.hpp
/// Writing files so that a reader never sees half of one: the content goes to a temporary file
/// beside the target, is flushed, and is renamed over the target only when complete. On any
/// failure the temporary files are removed and existing targets are left untouched.

#include <filesystem>
#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace sonarmap {

/// Several output files that appear together or not at all. stage() writes each to a temporary
/// file beside its target; commit() renames them all onto their targets. Destroyed without a
/// commit (an error part-way), it removes its temporary files and no target is touched.
class FileTransaction {
 public:
  FileTransaction() = default;
  FileTransaction(const FileTransaction&) = delete;
  FileTransaction& operator=(const FileTransaction&) = delete;
  ~FileTransaction();

  /// Writes what `write` puts into the stream (binary) to a temporary file for `path`.
  /// @throws FileError when the temporary file cannot be created, written or flushed (its folder
  ///         does not exist, the disk is full…); exceptions from `write` propagate.
  void stage(const std::string& path, const std::function<void(std::ostream&)>& write);

  /// Stages `bytes` for `path`. @throws FileError as stage().
  void stageBytes(const std::string& path, std::span<const unsigned char> bytes);

  /// Renames every staged file onto its target, in staging order.
  /// @throws FileError when a rename fails; the files renamed before it stay in place.
  void commit();

 private:
  struct Staged {
    std::filesystem::path temporary;
    std::filesystem::path target;
  };
  std::vector<Staged> staged_;
};

/// Writes `path` atomically with what `write` puts into the stream (binary mode).
/// @throws FileError as FileTransaction::stage() and commit().
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Writes `bytes` to `path` atomically. @throws FileError as writeFileAtomically.
void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes);

}  // namespace sonarmap
