// .bt files: our writer read by OctoMap 1.9 (liboctomap-dev, test-only), OctoMap's writer read by
// us, round trips, malformed files and atomic writes.
#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/octomap_binary.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path dir = fs::temp_directory_path() / ("sonarmap_bt_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

/// A tree with free space, obstacles and pruned regions.
OcTree16 sampleTree() {
  OcTree16 tree(0.05);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  for (int i = 0; i < 3000; ++i) {
    const auto key = tree.coder().keyOf({coord(rng), coord(rng), 0.3 * coord(rng)});
    tree.integrate(*key, i % 3 == 0);
  }
  for (int x = 0; x < 16; ++x)  // a solid block that prunes
    for (int y = 0; y < 16; ++y)
      for (int z = 0; z < 16; ++z) tree.integrate(*tree.coder().keyOf({3.0 + 0.05 * x, 0.05 * y, 0.05 * z}), true);
  return tree;
}

octomap::OcTreeKey toOctomap(const Key16& key) { return octomap::OcTreeKey(key[0], key[1], key[2]); }

TEST(ioOctomapBinary, OctoMapReadsOurFileAndFindsOurLeaves) {
  const OcTree16 tree = sampleTree();
  const fs::path path = tempDir() / "ours.bt";
  writeBinaryFile(tree, path.string());

  octomap::OcTree theirs(0.1);
  ASSERT_TRUE(theirs.readBinary(path.string()));
  EXPECT_DOUBLE_EQ(theirs.getResolution(), 0.05);
  EXPECT_EQ(theirs.size(), tree.counts().nodes);
  std::size_t leaves = 0, mismatches = 0;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    ++leaves;
    octomap::OcTreeNode* node = theirs.search(toOctomap(leaf.key), static_cast<unsigned>(leaf.depth));
    if (node == nullptr || theirs.nodeHasChildren(node) ||
        theirs.isNodeOccupied(node) != tree.model().isOccupied(leaf.log_odds)) {
      ++mismatches;
    }
  });
  EXPECT_GT(leaves, 1000U);
  EXPECT_EQ(mismatches, 0U);
  EXPECT_EQ(theirs.getNumLeafNodes(), leaves);
  const NodeCounts counts = tree.counts();
  EXPECT_EQ(counts.leaves, leaves);
  EXPECT_EQ(counts.inner + counts.leaves, counts.nodes);
}

TEST(ioOctomapBinary, WeReadOctoMapsFile) {
  octomap::OcTree theirs(0.05);
  for (int i = -20; i < 20; ++i) {
    theirs.updateNode(octomap::point3d(0.05f * i, 0.3f, 0.0f), true);
    theirs.updateNode(octomap::point3d(0.05f * i, 0.0f, 0.0f), false);
  }
  const fs::path path = tempDir() / "theirs.bt";
  ASSERT_TRUE(theirs.writeBinary(path.string()));  // thresholds and prunes their tree first

  const OcTree16 ours = readBinaryFile(path.string());
  EXPECT_EQ(ours.counts().nodes, theirs.size());
  std::size_t checked = 0;
  for (auto it = theirs.begin_leafs(); it != theirs.end_leafs(); ++it) {
    const octomap::OcTreeKey k = it.getKey();
    const auto value = ours.search(Key16{{k[0], k[1], k[2]}}, static_cast<int>(it.getDepth()));
    ASSERT_TRUE(value.has_value());
    EXPECT_EQ(ours.model().isOccupied(*value), theirs.isNodeOccupied(*it));
    ++checked;
  }
  EXPECT_EQ(checked, theirs.getNumLeafNodes());
  EXPECT_GT(checked, 20U);
}

TEST(ioOctomapBinary, RoundTripKeepsLeavesAndDoesNotChangeTheTree) {
  const OcTree16 tree = sampleTree();
  const NodeCounts before = tree.counts();
  std::stringstream stream;
  writeBinary(tree, stream);
  EXPECT_EQ(tree.counts().nodes, before.nodes);  // writing is const: nothing pruned or thresholded
  const OcTree16 back = readBinary(stream);
  EXPECT_EQ(back.counts().nodes, before.nodes);
  EXPECT_EQ(back.counts().leaves, before.leaves);
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    const auto value = back.search(leaf.key, leaf.depth);
    ASSERT_TRUE(value.has_value());
    EXPECT_EQ(back.model().classify(*value), tree.model().classify(leaf.log_odds));
  });
}

TEST(ioOctomapBinary, HeaderHasOctoMapsExactLines) {
  OcTree16 tree(0.02);
  tree.integrate(*tree.coder().keyOf({0.1, 0.1, 0.0}), true);
  std::stringstream stream;
  writeBinary(tree, stream);
  const std::string text = stream.str();
  EXPECT_EQ(text.rfind("# Octomap OcTree binary file\n", 0), 0U);
  EXPECT_NE(text.find("\nid OcTree\nsize 17\nres 0.02\ndata\n"), std::string::npos);
  EXPECT_EQ(text.size() - (text.find("data\n") + 5), 2U * 16U);  // 16 inner nodes, 2 bytes each
}

TEST(ioOctomapBinary, AnEmptyTreeIsSizeZeroWithNoDataAndOctoMapReadsIt) {
  const OcTree16 tree(0.05);
  EXPECT_EQ(tree.counts().nodes, 0U);
  std::stringstream stream;
  writeBinary(tree, stream);
  const std::string text = stream.str();
  EXPECT_NE(text.find("\nsize 0\nres 0.05\ndata\n"), std::string::npos);
  EXPECT_EQ(text.size(), text.find("data\n") + 5);
  EXPECT_TRUE(readBinary(stream).empty());
  std::istringstream theirs_in(text);
  octomap::OcTree theirs(0.1);
  ASSERT_TRUE(theirs.readBinary(theirs_in));
  EXPECT_EQ(theirs.size(), 0U);
}

TEST(ioOctomapBinary, MalformedFilesThrowFileError) {
  const OcTree16 tree = sampleTree();
  std::stringstream good;
  writeBinary(tree, good);
  const std::string text = good.str();
  auto parse = [](const std::string& content) {
    std::istringstream in(content);
    return readBinary(in, {}, "broken.bt");
  };
  EXPECT_THROW(parse(""), FileError);
  EXPECT_THROW(parse("# Octomap OcTree file\nid OcTree\nsize 1\nres 0.1\ndata\n"), FileError);  // .ot magic
  EXPECT_THROW(parse(text.substr(0, text.size() / 2)), FileError);                              // truncated
  EXPECT_THROW(parse(text.substr(0, text.find("data"))), FileError);                            // no data line
  std::string wrong_size = text;
  wrong_size.replace(wrong_size.find("size ") + 5, 1, "9");
  EXPECT_THROW(parse(wrong_size), FileError);
  std::string bad_res = text;
  bad_res.replace(bad_res.find("res 0.05"), 8, "res -1.0");
  EXPECT_THROW(parse(bad_res), ValueError);
  EXPECT_THROW(readBinaryFile((tempDir() / "missing.bt").string()), FileError);
}

TEST(ioAtomicFile, FailedWriteLeavesExistingFileUntouched) {
  const fs::path dir = tempDir() / "atomic";
  fs::create_directories(dir);
  const fs::path path = dir / "keep.bt";
  writeFileAtomically(path.string(), [](std::ostream& out) { out << "old content"; });
  EXPECT_THROW(writeFileAtomically(path.string(),
                                   [](std::ostream& out) {
                                     out << "half of a new";
                                     throw FileError("failed half way");
                                   }),
               FileError);
  std::ifstream in(path);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "old content");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(path.parent_path())) ++files;
  EXPECT_EQ(files, 1U) << "the temporary file was removed";
  EXPECT_THROW(writeBinaryFile(OcTree16(0.1), "/nonexistent-dir/x.bt"), FileError);
}

}  // namespace
}  // namespace sonarmap
