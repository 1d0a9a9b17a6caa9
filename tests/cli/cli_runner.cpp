/// @file cli_runner.cpp
/// Child processes and temporary directories for the CLI tests (see cli_runner.hpp).

#include "cli_runner.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

extern char** environ;

namespace sonarmap::test {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void throwErrno(const std::string& what, int error) {
  throw std::runtime_error(what + ": " + std::strerror(error));
}

/// posix_spawn file actions that own their resources.
class FileActions {
 public:
  FileActions() {
    if (const int rc = posix_spawn_file_actions_init(&actions_); rc != 0) throwErrno("posix_spawn_file_actions_init", rc);
  }
  ~FileActions() { posix_spawn_file_actions_destroy(&actions_); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;

  void open(int fd, const std::string& path, int flags) {
    if (const int rc = posix_spawn_file_actions_addopen(&actions_, fd, path.c_str(), flags, 0644); rc != 0) {
      throwErrno("posix_spawn_file_actions_addopen " + path, rc);
    }
  }
  const posix_spawn_file_actions_t* get() const { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_;
};

}  // namespace

ProgramRun runProgram(const std::string& program, const std::vector<std::string>& args, const fs::path& capture_dir) {
  const fs::path out_path = capture_dir / "stdout.txt";
  const fs::path err_path = capture_dir / "stderr.txt";
  FileActions actions;
  actions.open(STDIN_FILENO, "/dev/null", O_RDONLY);
  actions.open(STDOUT_FILENO, out_path.string(), O_WRONLY | O_CREAT | O_TRUNC);
  actions.open(STDERR_FILENO, err_path.string(), O_WRONLY | O_CREAT | O_TRUNC);

  std::vector<std::string> storage;
  storage.reserve(args.size() + 1);
  storage.push_back(program);
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : storage) argv.push_back(arg.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  if (const int rc = posix_spawn(&pid, program.c_str(), actions.get(), nullptr, argv.data(), environ); rc != 0) {
    throwErrno("posix_spawn " + program, rc);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throwErrno("waitpid", errno);
  }
  ProgramRun run;
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  run.out = readFile(out_path);
  run.err = readFile(err_path);
  return run;
}

fs::path makeTempDir(const std::string& label) {
  std::string name = (fs::temp_directory_path() / ("sonarmap_cli_" + label + "_XXXXXX")).string();
  if (::mkdtemp(name.data()) == nullptr) throwErrno("mkdtemp " + name, errno);
  return name;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << content;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::vector<std::string> listDir(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace sonarmap::test
