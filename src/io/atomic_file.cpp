#include "sonarmap/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <fstream>
#include <system_error>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

/// What commit() did to one target, so that it can be undone.
struct Placed {
  fs::path target;
  fs::path backup;  ///< the target's old content; empty when the target did not exist
};

std::string cannotWrite(const fs::path& target, const std::string& why) {
  return "cannot write '" + target.string() + "': " + why;
}

/// ".NAME.sonarmap-PID-N" + `kind` beside `target`: hidden, unique within this process.
fs::path besideName(const fs::path& target, const char* kind) {
  static std::atomic<unsigned long> counter{0};
  constexpr std::size_t kMaxStem = 200;  // room for the suffix within the usual 255-byte file names
  std::string name = ".";                // appended piecewise: GCC 12 warns falsely on "." + std::string
  name += target.filename().string().substr(0, kMaxStem);
  name += ".sonarmap-";
  name += std::to_string(::getpid());
  name += "-";
  name += std::to_string(counter++);
  name += kind;
  return target.parent_path() / name;
}

/// Calls `create` with fresh names beside `target` until one is free (a name already taken is
/// never overwritten). @returns the name created. @throws FileError naming `target` on other errors.
template <class Create>
fs::path createBeside(const fs::path& target, const char* kind, const std::string& what, Create create) {
  constexpr int kAttempts = 100;
  std::error_code error;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    fs::path name = besideName(target, kind);
    error = create(name);
    if (!error) return name;
    if (error != std::errc::file_exists) break;
  }
  throw FileError(cannotWrite(target, "cannot create " + what + " in its folder: " + error.message()));
}

/// A new, empty temporary file beside `target`.
fs::path createTemporary(const fs::path& target) {
  return createBeside(target, ".tmp", "a temporary file", [](const fs::path& name) {
    const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return std::error_code(errno, std::generic_category());
    ::close(fd);
    return std::error_code();
  });
}

/// A backup of the existing `target` beside it: a hard link, or a copy where links are not supported.
fs::path createBackup(const fs::path& target) {
  return createBeside(target, ".bak", "a backup of the existing file", [&](const fs::path& name) {
    std::error_code error;
    fs::create_hard_link(target, name, error);
    if (error && error != std::errc::file_exists) {
      error.clear();
      fs::copy_file(target, name, fs::copy_options::none, error);
    }
    return error;
  });
}

void removeQuietly(const fs::path& path) {
  std::error_code ignored;
  if (!path.empty()) fs::remove(path, ignored);
}

void writeTemporary(const fs::path& temporary, const fs::path& target,
                    const std::function<void(std::ostream&)>& write) {
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) throw FileError(cannotWrite(target, "cannot open a temporary file in its folder"));
  write(out);
  out.close();
  if (!out) throw FileError(cannotWrite(target, "writing failed (disk full?)"));
}

/// Renames `temporary` over `target`, keeping a backup of an existing target (a folder in the way
/// is left to make the rename fail). @throws FileError naming `target`; then no backup remains.
Placed place(const fs::path& temporary, const fs::path& target) {
  std::error_code error;
  const fs::file_type type = fs::symlink_status(target, error).type();
  const bool keep_old = type != fs::file_type::not_found && type != fs::file_type::directory;
  Placed placed{target, keep_old ? createBackup(target) : fs::path()};
  fs::rename(temporary, target, error);
  if (error) {
    removeQuietly(placed.backup);
    throw FileError(cannotWrite(target, error.message()));
  }
  return placed;
}

/// Undoes `placed`, last first: backups renamed back over their targets, new targets removed.
/// @returns "" when everything was undone, else what could not be (a backup that stays is named).
std::string rollBack(const std::vector<Placed>& placed) {
  std::string failures;
  for (auto file = placed.rbegin(); file != placed.rend(); ++file) {
    std::error_code error;
    if (file->backup.empty()) {
      fs::remove(file->target, error);
    } else {
      fs::rename(file->backup, file->target, error);
    }
    if (!error) continue;
    failures += "; could not restore '" + file->target.string() + "' (" + error.message();
    failures += file->backup.empty() ? ")" : ", its old content is in '" + file->backup.string() + "')";
  }
  return failures;
}

}  // namespace

FileTransaction::~FileTransaction() { discard(); }

void FileTransaction::discard() {
  for (const Staged& file : staged_) removeQuietly(file.temporary);
  staged_.clear();
}

void FileTransaction::stage(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const fs::path target(path);
  if (target.filename().empty()) throw FileError(cannotWrite(target, "not a file name"));
  const fs::path temporary = createTemporary(target);
  try {
    writeTemporary(temporary, target, write);
    staged_.push_back({temporary, target});
  } catch (...) {
    removeQuietly(temporary);
    throw;
  }
}

void FileTransaction::stageBytes(const std::string& path, std::span<const unsigned char> bytes) {
  stage(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

void FileTransaction::commit() {
  std::vector<Placed> placed;
  try {
    placed.reserve(staged_.size());
    for (const Staged& file : staged_) placed.push_back(place(file.temporary, file.target));
  } catch (const std::exception& error) {
    const std::string not_restored = rollBack(placed);
    discard();
    throw FileError(error.what() + not_restored);
  }
  for (const Placed& file : placed) removeQuietly(file.backup);
  staged_.clear();
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  FileTransaction transaction;
  transaction.stage(path, write);
  transaction.commit();
}

void checkWritable(const std::string& path) {
  const fs::path target(path);
  if (target.filename().empty()) throw FileError(cannotWrite(target, "not a file name"));
  removeQuietly(createTemporary(target));
}

void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes) {
  FileTransaction transaction;
  transaction.stageBytes(path, bytes);
  transaction.commit();
}

}  // namespace sonarmap
