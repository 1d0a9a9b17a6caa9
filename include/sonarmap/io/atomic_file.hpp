#pragma once
/// @file atomic_file.hpp
/// Writing files so that a reader never sees half of one and a failed run changes nothing: the
/// content goes to a temporary file beside the target, is flushed and closed, and is renamed over
/// the target only when complete. Several files commit together (FileTransaction): all are put in
/// place or, when one fails, the others are rolled back to what they were.
///
/// Temporary files and backups live beside their target (same folder, hence same filesystem, so a
/// rename is atomic) under hidden names no user file has: ".NAME.sonarmap-PID-N.tmp" and
/// ".NAME.sonarmap-PID-N.bak", created exclusively (an existing file of that name is never reused
/// or overwritten). Every one is removed on every path that returns or throws.

#include <filesystem>
#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace sonarmap {

/// Several output files that appear together or not at all. stage() writes each to a temporary
/// file beside its target; commit() puts them all in place, or none. Destroyed without a commit
/// (an error part-way), it removes its temporary files and no target is touched.
class FileTransaction {
 public:
  FileTransaction() = default;
  FileTransaction(const FileTransaction&) = delete;
  FileTransaction& operator=(const FileTransaction&) = delete;
  ~FileTransaction();

  /// Writes what `write` puts into the stream (binary) to a new temporary file beside `path`;
  /// `path` itself is not touched until commit().
  /// @throws FileError naming `path` when `path` has no file name or the temporary file cannot be
  ///         created, written or closed (its folder does not exist, the disk is full…).
  ///         Exceptions from `write` propagate. In every case the temporary file is removed.
  void stage(const std::string& path, const std::function<void(std::ostream&)>& write);

  /// Stages `bytes` for `path`. @throws FileError as stage().
  void stageBytes(const std::string& path, std::span<const unsigned char> bytes);

  /// Puts every staged file in place, in staging order: an existing target (not a folder) is first
  /// kept as a backup beside it (a hard link; a copy where the filesystem has none), then the
  /// temporary file is renamed over it, so the target always exists with its old or its new content.
  /// On success the backups are removed. When any step fails, the files already put in place are
  /// rolled back in reverse order (backups renamed back over their targets, targets that did not
  /// exist before removed), every temporary file and backup is removed, and FileError is thrown.
  ///
  /// Cannot guarantee: that a crash (power loss, SIGKILL) between two renames leaves all or none —
  /// then some targets hold new content and the hidden .tmp/.bak files stay behind; that the files
  /// reached the disk (no fsync); that a rollback step itself succeeds (the folder was removed
  /// meanwhile…): such a backup is kept and the message says where. A target that is a symbolic
  /// link is replaced by a regular file, and the new files get default permissions, not the old ones.
  /// @throws FileError naming the file that could not be put in place and why (a folder is in the
  ///         way, its folder is gone…), followed by any file the rollback could not restore.
  void commit();

 private:
  struct Staged {
    std::filesystem::path temporary;
    std::filesystem::path target;
  };
  /// Removes the temporary files still staged and forgets them.
  void discard();

  std::vector<Staged> staged_;
};

/// Writes `path` atomically with what `write` puts into the stream (binary mode).
/// @throws FileError as FileTransaction::stage() and commit().
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Writes `bytes` to `path` atomically. @throws FileError as writeFileAtomically.
void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes);

/// Checks now that `path` could be written later: a temporary file is created beside it and
/// removed, as FileTransaction::stage() creates one (for a run that writes its output only at the
/// end, so that a folder that does not exist or cannot be written is said before any work).
/// `path` itself is not touched.
/// @throws FileError as FileTransaction::stage() when the temporary file cannot be created.
void checkWritable(const std::string& path);

}  // namespace sonarmap
