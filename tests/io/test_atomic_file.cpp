// FileTransaction and the atomic writers: a transaction puts all its files in place or none. A
// commit whose third rename fails rolls the first two back byte for byte; a writer throwing half
// way leaves nothing; no temporary or backup file survives any path.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;
using Names = std::vector<std::string>;

std::string contentOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const fs::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
}

/// Every entry of `dir`, hidden ones (temporary files, backups) included, sorted.
Names entriesOf(const fs::path& dir) {
  Names names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::function<void(std::ostream&)> text(const std::string& content) {
  return [content](std::ostream& out) { out << content; };
}

/// The message of the FileError `action` throws; fails the test when it throws none.
template <class Action>
std::string fileErrorOf(Action action) {
  try {
    action();
  } catch (const FileError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no FileError thrown";
  return {};
}

/// A folder with an existing a.bt ("old a"), no b.png, and c.csv that is a non-empty folder: a
/// transaction staging a, b and c renames a and b, then fails on c.
class ioFileTransaction : public ::testing::Test {
 protected:
  void SetUp() override {
    put(a_, "old a\n");
    fs::create_directory(c_);
    put(c_ / "keep.txt", "user file in the way\n");
  }
  void stageAll(FileTransaction& transaction) const {
    transaction.stage(a_.string(), text("new a\n"));
    transaction.stageBytes(b_.string(), std::vector<unsigned char>{'n', 'e', 'w', ' ', 'b'});
    transaction.stage(c_.string(), text("new c\n"));
  }
  void expectOldState() const {
    EXPECT_EQ(contentOf(a_), "old a\n") << "a.bt was not restored";
    EXPECT_FALSE(fs::exists(b_)) << "b.png did not exist before and must not now";
    EXPECT_EQ(contentOf(c_ / "keep.txt"), "user file in the way\n");
    EXPECT_EQ(entriesOf(dir_.path()), (Names{"a.bt", "c.csv"})) << "no temporary or backup file may remain";
  }

  test::TempDir dir_;
  fs::path a_ = dir_.path() / "a.bt";
  fs::path b_ = dir_.path() / "b.png";
  fs::path c_ = dir_.path() / "c.csv";
};

TEST_F(ioFileTransaction, ThirdRenameFailingRollsBackTheFirstTwo) {
  FileTransaction transaction;
  stageAll(transaction);
  const std::string message = fileErrorOf([&] { transaction.commit(); });
  EXPECT_NE(message.find("'" + c_.string() + "'"), std::string::npos) << message;
  EXPECT_EQ(message.find("could not restore"), std::string::npos) << message;
  expectOldState();
}

TEST_F(ioFileTransaction, FolderRemovedAfterStagingRollsBackTheOthers) {
  const fs::path gone = dir_.path() / "gone";
  fs::create_directory(gone);
  fs::remove_all(c_);
  c_ = gone / "c.csv";
  FileTransaction transaction;
  stageAll(transaction);
  fs::remove_all(gone);  // takes c's temporary file with it: its rename fails
  const std::string message = fileErrorOf([&] { transaction.commit(); });
  EXPECT_NE(message.find("'" + c_.string() + "'"), std::string::npos) << message;
  EXPECT_EQ(contentOf(a_), "old a\n");
  EXPECT_EQ(entriesOf(dir_.path()), Names{"a.bt"});
}

TEST_F(ioFileTransaction, SameTargetStagedTwiceIsRestoredToItsFirstContent) {
  FileTransaction transaction;
  transaction.stage(a_.string(), text("first\n"));
  transaction.stage(b_.string(), text("first b\n"));
  transaction.stage(a_.string(), text("second\n"));
  transaction.stage(b_.string(), text("second b\n"));
  transaction.stage(c_.string(), text("new c\n"));
  fileErrorOf([&] { transaction.commit(); });
  expectOldState();
}

TEST_F(ioFileTransaction, WriterThrowingHalfWayLeavesNothing) {
  {
    FileTransaction transaction;
    transaction.stage(b_.string(), text("new b\n"));
    EXPECT_THROW(transaction.stage(a_.string(),
                                   [](std::ostream& out) {
                                     out << "half of a new";
                                     throw ValueError("a value the writer rejects");
                                   }),
                 ValueError);
    EXPECT_EQ(entriesOf(dir_.path()).size(), 3U) << "a, c and b's temporary file only";
  }
  expectOldState();
}

TEST_F(ioFileTransaction, SuccessReplacesEveryTargetAndRemovesBackups) {
  fs::remove_all(c_);
  {
    FileTransaction transaction;
    stageAll(transaction);
    EXPECT_EQ(contentOf(a_), "old a\n") << "no target changes before commit()";
    transaction.commit();
  }
  EXPECT_EQ(contentOf(a_), "new a\n");
  EXPECT_EQ(contentOf(b_), "new b");
  EXPECT_EQ(contentOf(c_), "new c\n");
  EXPECT_EQ(entriesOf(dir_.path()), (Names{"a.bt", "b.png", "c.csv"}));
}

TEST_F(ioFileTransaction, DestructorWithoutCommitRemovesTemporaries) {
  {
    FileTransaction transaction;
    stageAll(transaction);
    const Names staged = entriesOf(dir_.path());
    ASSERT_EQ(staged.size(), 5U) << "a, c and three temporary files";
    for (const std::string& name : staged) {
      if (name != "a.bt" && name != "c.csv") {
        EXPECT_EQ(name.front(), '.') << name << " should be hidden";
      }
    }
  }
  expectOldState();
}

TEST_F(ioFileTransaction, UserFilesNamedLikeTemporariesAreNeverTouched) {
  // Leftovers of an earlier run (or a user's files) with the first names this process tries: ctest
  // runs each test in its own process, so the name counter starts at 0 (temporary 0-2 taken, then
  // 3; backup 4-5 taken, then 6).
  Names decoys;
  const std::string stem = ".a.bt.sonarmap-" + std::to_string(::getpid()) + "-";
  for (int n = 0; n < 3; ++n) decoys.push_back(stem + std::to_string(n) + ".tmp");
  for (int n = 0; n < 6; ++n) decoys.push_back(stem + std::to_string(n) + ".bak");
  for (const std::string& decoy : decoys) put(dir_.path() / decoy, "decoy\n");
  writeFileAtomically(a_.string(), text("new a\n"));
  EXPECT_EQ(contentOf(a_), "new a\n");
  for (const std::string& decoy : decoys) EXPECT_EQ(contentOf(dir_.path() / decoy), "decoy\n") << decoy;
  Names expected = decoys;
  expected.insert(expected.end(), {"a.bt", "c.csv"});
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(entriesOf(dir_.path()), expected) << "no temporary or backup file of ours may remain";
}

TEST(ioAtomicFile, MissingFolderThrowsNamingTheFileAndCreatesNothing) {
  const test::TempDir dir;
  const fs::path path = dir.path() / "missing" / "x.csv";
  const std::string message = fileErrorOf([&] { writeFileAtomically(path.string(), text("x\n")); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_EQ(entriesOf(dir.path()), Names{});
  EXPECT_THROW(writeBytesAtomically((dir.path() / "").string(), {}), FileError) << "not a file name";
}

}  // namespace
}  // namespace sonarmap
