// .ot full trees: round trips, our writer read by OctoMap 1.9 (liboctomap-dev, test-only),
// OctoMap's writer read (and rewritten byte for byte) by us, malformed files.
#include <gtest/gtest.h>

#include <octomap/AbstractOcTree.h>
#include <octomap/OcTree.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include "common/temp_dir.hpp"
#include "sonarmap/io/octomap_full.hpp"
#include "sonarmap/io/octomap_header.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

/// A tree with free space, obstacles, values between the clamps and a pruned block.
OcTree16 sampleTree(const OctreeOptions& options = {}) {
  OcTree16 tree(0.05, options);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  for (int i = 0; i < 3000; ++i) tree.integrate(*tree.coder().keyOf({coord(rng), coord(rng), 0.3 * coord(rng)}), i % 3 == 0);
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) tree.integrate(*tree.coder().keyOf({3.0 + 0.05 * x, 0.05 * y, 0.05 * z}), true);
  return tree;
}

/// Pre-order list of (log-odds bits, child bits): equal lists mean identical trees.
void dump(const OcTree16& tree, NodeRef ref, std::vector<std::pair<std::uint32_t, unsigned>>& out) {
  const OcTreeNode& node = tree.node(ref);
  unsigned bits = 0;
  for (unsigned i = 0; i < 8; ++i) bits |= tree.node(tree.childRef(node, i)).exists() ? 1U << i : 0U;
  EXPECT_EQ(bits, tree.childMask(node));
  out.emplace_back(std::bit_cast<std::uint32_t>(node.log_odds), bits);
  for (unsigned i = 0; i < 8; ++i)
    if ((bits >> i) & 1U) dump(tree, tree.childRef(node, i), out);
}
std::vector<std::pair<std::uint32_t, unsigned>> dump(const OcTree16& tree) {
  std::vector<std::pair<std::uint32_t, unsigned>> out;
  if (!tree.empty()) dump(tree, kRootRef, out);
  return out;
}

std::string fullBytes(const OcTree16& tree) {
  std::ostringstream out;
  writeFull(tree, out);
  return out.str();
}

OcTree16 parse(const std::string& bytes) {
  std::istringstream in(bytes);
  return readFull(in, {}, "test.ot");
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t dataStart(const std::string& bytes) { return bytes.find("\ndata\n") + 6; }

void expectFileError(const std::string& bytes, const std::string& message_part) {
  try {
    parse(bytes);
    ADD_FAILURE() << "no FileError; expected one mentioning '" << message_part << "'";
  } catch (const FileError& error) {
    EXPECT_NE(std::string(error.what()).find(message_part), std::string::npos) << error.what();
  }
}

octomap::OcTreeKey toOctomap(const Key16& key) { return octomap::OcTreeKey(key[0], key[1], key[2]); }

TEST(ioOctomapFull, RoundTripKeepsStructureAndValuesExactly) {
  for (const bool prune : {true, false}) {
    OctreeOptions options;
    options.prune = prune;
    const OcTree16 tree = sampleTree(options);
    const auto before = dump(tree);
    const std::string bytes = fullBytes(tree);
    EXPECT_EQ(dump(tree), before) << "writing is const";
    const OcTree16 back = parse(bytes);
    EXPECT_EQ(dump(back), before) << "prune " << prune;
    EXPECT_EQ(back.resolution_m(), 0.05);
    EXPECT_EQ(fullBytes(back), bytes);
  }
  const OcTree16 empty = parse(fullBytes(OcTree16(0.1)));
  EXPECT_TRUE(empty.empty());
}

TEST(ioOctomapFull, LayoutIsHeaderPlusFiveBytesPerNode) {
  // formats.md: geb079 as .ot is a 135-byte header plus 532,566 × 5 bytes.
  std::ostringstream header;
  writeOctomapHeader(header, kFullFileFirstLine, {"OcTree", 532566, 0.08});
  EXPECT_EQ(header.str().size(), 135U);
  const OcTree16 tree = sampleTree();
  const std::string bytes = fullBytes(tree);
  EXPECT_EQ(bytes.rfind("# Octomap OcTree file\n", 0), 0U);
  EXPECT_NE(bytes.find("\nid OcTree\nsize " + std::to_string(tree.counts().nodes) + "\nres 0.05\ndata\n"), std::string::npos);
  EXPECT_EQ(bytes.size() - dataStart(bytes), 5 * tree.counts().nodes);
}

TEST(ioOctomapFull, OctoMapReadsOurFileWithIdenticalNodes) {
  const TempDir dir;
  const OcTree16 tree = sampleTree();
  writeFullFile(tree, dir.file("ours.ot"));
  std::unique_ptr<octomap::AbstractOcTree> read(octomap::AbstractOcTree::read(dir.file("ours.ot")));
  auto* theirs = dynamic_cast<octomap::OcTree*>(read.get());
  ASSERT_NE(theirs, nullptr);
  EXPECT_DOUBLE_EQ(theirs->getResolution(), 0.05);
  EXPECT_EQ(theirs->size(), tree.counts().nodes);
  std::size_t leaves = 0;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    ++leaves;
    octomap::OcTreeNode* node = theirs->search(toOctomap(leaf.key), static_cast<unsigned>(leaf.depth));
    ASSERT_NE(node, nullptr);
    EXPECT_FALSE(theirs->nodeHasChildren(node));
    EXPECT_EQ(node->getLogOdds(), leaf.log_odds);  // exact
  });
  EXPECT_EQ(theirs->getNumLeafNodes(), leaves);
  for (auto it = theirs->begin_tree(); it != theirs->end_tree(); ++it) {  // inner nodes too
    const octomap::OcTreeKey k = it.getKey();
    EXPECT_EQ(tree.search(Key16{{k[0], k[1], k[2]}}, static_cast<int>(it.getDepth())), it->getLogOdds());
  }
}

TEST(ioOctomapFull, WeReadOctoMapsFileAndRewriteItByteForByte) {
  const TempDir dir;
  octomap::OcTree theirs(0.05);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> coord(-1.0F, 1.0F);
  for (int i = 0; i < 2000; ++i) theirs.updateNode(octomap::point3d(coord(rng), coord(rng), 0.2F * coord(rng)), i % 4 == 0);
  for (int x = 0; x < 8; ++x)  // a pruned block
    for (int y = 0; y < 8; ++y) theirs.updateNode(octomap::point3d(2.0F + 0.05F * x, 0.05F * y, 0.0F), true);
  ASSERT_TRUE(theirs.write(dir.file("theirs.ot")));

  const OcTree16 ours = readFullFile(dir.file("theirs.ot"));
  EXPECT_EQ(ours.counts().nodes, theirs.size());
  EXPECT_EQ(ours.counts().leaves, theirs.getNumLeafNodes());
  std::size_t checked = 0;
  for (auto it = theirs.begin_tree(); it != theirs.end_tree(); ++it, ++checked) {
    const octomap::OcTreeKey k = it.getKey();
    const auto value = ours.search(Key16{{k[0], k[1], k[2]}}, static_cast<int>(it.getDepth()));
    ASSERT_TRUE(value.has_value());
    EXPECT_EQ(*value, it->getLogOdds());  // leaves and (max) inner nodes exact
  }
  EXPECT_EQ(checked, theirs.size());
  std::ostringstream rewritten;
  writeFull(ours, rewritten);
  EXPECT_EQ(rewritten.str(), fileBytes(dir.file("theirs.ot")));
}

TEST(ioOctomapFull, TruncatedAtEveryOffsetThrowsFileError) {
  OcTree16 tree(0.1);
  tree.integrate(*tree.coder().keyOf({0.15, -0.3, 0.0}), true);
  tree.integrate(*tree.coder().keyOf({0.25, -0.3, 0.0}), false);
  const std::string bytes = fullBytes(tree);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    EXPECT_THROW(parse(bytes.substr(0, size)), FileError) << "truncated to " << size << " bytes";
  }
  expectFileError(bytes.substr(0, bytes.size() - 3), "test.ot: byte " + std::to_string(bytes.size() - 3) + ": file ends after");
}

TEST(ioOctomapFull, RandomCorruptionOfTheDataThrowsOnlyLibraryErrors) {
  OcTree16 tree(0.1);
  for (int i = 0; i < 10; ++i) tree.integrate(*tree.coder().keyOf({0.1 * i, 0.05 * i, 0.0}), i % 2 == 0);
  const std::string good = fullBytes(tree);
  const std::size_t data = dataStart(good);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = good;
    for (int flips = 1 + trial % 4; flips > 0; --flips) bytes[data + rng() % (bytes.size() - data)] = static_cast<char>(rng());
    try {
      parse(bytes);
    } catch (const Error&) {  // FileError; anything else (or a crash) fails the test
    }
  }
}

TEST(ioOctomapFull, MalformedFilesThrowFileError) {
  const OcTree16 tree = sampleTree();
  const std::string bytes = fullBytes(tree);
  const std::size_t data = dataStart(bytes);
  const std::string size_line = "size " + std::to_string(tree.counts().nodes);
  auto withSize = [&](const std::string& size) {
    std::string changed = bytes;
    changed.replace(changed.find(size_line), size_line.size(), "size " + size);
    return changed;
  };
  expectFileError("", "not an OctoMap file");
  expectFileError("# Octomap OcTree binary file\nid OcTree\nsize 1\nres 0.1\ndata\n", "not an OctoMap file");
  expectFileError("# Octomap OcTree file\nid ColorOcTree\nsize 1\nres 0.1\ndata\n", "is not OcTree");
  expectFileError(withSize("1000000000"), "expected 5000000000");  // huge size: no huge buffer
  expectFileError(withSize("18446744073709551615"), "size");
  expectFileError(withSize(std::to_string(tree.counts().nodes - 1)), "continues past");
  expectFileError(withSize(std::to_string(tree.counts().nodes + 1)) + "12345", "tree ends after");
  std::string nan = bytes;
  const float quiet_nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[data + 5], &quiet_nan, 4);  // the root's first child
  expectFileError(nan, "byte " + std::to_string(data + 5) + ": log-odds of a node is nan");
  std::string inf = bytes;
  const float infinity = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[data], &infinity, 4);
  expectFileError(inf, "log-odds of a node is inf");
  // A chain of 18 nodes, each with child 0: the node at depth 16 cannot have children.
  std::string deep = "# Octomap OcTree file\nid OcTree\nsize 18\nres 0.1\ndata\n";
  for (int depth = 0; depth < 18; ++depth) deep += std::string(4, '\0') + std::string(1, depth < 17 ? '\1' : '\0');
  expectFileError(deep, "node at depth 16 (the finest level) has children");
  EXPECT_THROW(readFullFile("/nonexistent/x.ot"), FileError);
}

}  // namespace
}  // namespace sonarmap
