// End-to-end tests of the progress bars: the long commands (map, cloud, simulate, eval)
// draw one on a terminal and end with their summary line; -q or a stderr that is not a terminal
// draws none. The tool runs on a pseudo-terminal (forkpty), stdout and stderr both on it.
#include <gtest/gtest.h>

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <vector>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

/// Runs the tool with `args` in `dir` on a pseudo-terminal; everything it printed, and its exit code.
std::pair<std::string, int> runOnTerminal(const Names& args, const fs::path& dir) {
  std::vector<std::string> words{SONARMAP_CLI};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  int master = -1;
  const pid_t child = forkpty(&master, nullptr, nullptr, nullptr);
  if (child < 0) return {"forkpty failed", -1};
  if (child == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string output;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n > 0) {
      output.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO once the child has closed the terminal
    }
  }
  close(master);
  int status = 0;
  waitpid(child, &status, 0);
  return {output, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

using cliProgress = CliTest;

TEST_F(cliProgress, LongCommandsDrawABarOnATerminalAndEndWithTheirSummary) {
  writeFile(root_ / "cloud.xyz", "1 0 0\n0 1 0\n0 0 1\n");
  struct Case {
    Names args;
    const char* bar;      ///< the bar's label
    const char* summary;  ///< a piece of the summary line
  };
  const std::vector<Case> cases{
      {{"simulate", "tank", "-o", "sim", "--turns", "2"}, "simulating [", "micron: 400 beams in 2 turns"},
      {{"map", "sim/beams.csv", "-o", "map.bt"}, "mapping [", "-> map.bt"},
      {{"eval", "map.bt", "--truth", "tank"}, "scoring [", "scored "},
      {{"cloud", "cloud.xyz", "-o", "cloud.bt"}, "inserting [", "3 points in 1 scans"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args[0]);
    const auto [output, code] = runOnTerminal(c.args, root_);
    ASSERT_EQ(code, 0) << output;
    const std::size_t bar = output.find(std::string("\r") + c.bar);
    EXPECT_NE(bar, std::string::npos) << output;
    const std::size_t summary = output.find(c.summary);
    EXPECT_NE(summary, std::string::npos) << output;
    EXPECT_LT(bar, summary) << "the bar runs before the summary";
    EXPECT_NE(output.find("\r\033[K", bar), std::string::npos) << "the bar's line is cleared";
    // -q: the summary alone.
    Names quiet = c.args;
    quiet.push_back("-q");
    const auto [quiet_output, quiet_code] = runOnTerminal(quiet, root_);
    ASSERT_EQ(quiet_code, 0) << quiet_output;
    EXPECT_EQ(quiet_output.find(c.bar), std::string::npos) << quiet_output;
    EXPECT_NE(quiet_output.find(c.summary), std::string::npos) << quiet_output;
  }
}

}  // namespace
}  // namespace sonarmap::test
