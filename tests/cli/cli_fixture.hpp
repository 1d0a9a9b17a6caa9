#pragma once
// The fixture of the CLI tests: a temporary folder per test and the checks every error shares.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace sonarmap::test {

namespace fs = std::filesystem;
using Names = std::vector<std::string>;

/// Lines of `text`, without their '\n'; a last line without '\n' counts too.
inline Names linesOf(const std::string& text) {
  Names lines;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

/// Each test gets its own temporary root: outputs go to root/out (listed by the tests), the
/// captured streams and hand-made inputs stay in root. Removed on success, kept on failure.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string label = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(label.begin(), label.end(), '/', '_');
    root_ = makeTempDir(label);
    out_ = root_ / "out";
    fs::create_directory(out_);
  }
  void TearDown() override {
    if (HasFailure()) {
      std::cerr << "kept for inspection: " << root_ << '\n';
    } else {
      std::error_code ec;
      fs::remove_all(root_, ec);
    }
  }

  ProgramRun run(const Names& args) const { return runProgram(SONARMAP_CLI, args, root_); }

  /// Exit `code`, nothing on stdout, exactly one "sonarmap: error:" line on stderr.
  static void expectError(const ProgramRun& result, int code) {
    EXPECT_EQ(result.signal, 0);
    EXPECT_EQ(result.exit_code, code) << "stderr: " << result.err;
    EXPECT_EQ(result.out, "");
    const Names lines = linesOf(result.err);
    ASSERT_EQ(lines.size(), 1u) << "stderr: " << result.err;
    EXPECT_EQ(lines[0].rfind("sonarmap: error:", 0), 0u) << lines[0];
    EXPECT_EQ(result.err.back(), '\n');
  }

  fs::path root_;
  fs::path out_;
};

}  // namespace sonarmap::test
