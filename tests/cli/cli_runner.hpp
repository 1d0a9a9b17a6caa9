#pragma once
/// @file cli_runner.hpp
/// Helpers for end-to-end tests of a command-line program: run it as a child process (fork/exec
/// through posix_spawn, no shell) with stdin from /dev/null and stdout/stderr redirected to files,
/// so stderr is never a terminal; plus fresh temporary directories and small file helpers.

#include <filesystem>
#include <string>
#include <vector>

namespace sonarmap::test {

/// What one run of a program did.
struct ProgramRun {
  int exit_code = -1;  ///< exit status; -1 when the child did not exit normally
  int signal = 0;      ///< signal that killed the child, 0 when it exited
  std::string out;     ///< all bytes written on stdout
  std::string err;     ///< all bytes written on stderr
};

/// Runs `program` with `args` as argv[1..] and waits for it. The captured streams are written to
/// `capture_dir`/stdout.txt and stderr.txt (overwritten), then read back.
/// @throws std::runtime_error when the program cannot be spawned or waited for.
ProgramRun runProgram(const std::string& program, const std::vector<std::string>& args,
                      const std::filesystem::path& capture_dir);

/// A fresh, empty directory under the system temporary folder, named after `label`.
/// @throws std::runtime_error when it cannot be created.
std::filesystem::path makeTempDir(const std::string& label);

/// The whole content of `path` (binary). @throws std::runtime_error when it cannot be opened.
std::string readFile(const std::filesystem::path& path);

/// Writes `content` to `path` (binary, truncating). @throws std::runtime_error on failure.
void writeFile(const std::filesystem::path& path, const std::string& content);

/// The names of the entries of `dir`, sorted; empty when `dir` does not exist.
std::vector<std::string> listDir(const std::filesystem::path& dir);

}  // namespace sonarmap::test
