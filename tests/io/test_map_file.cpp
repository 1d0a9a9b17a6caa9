// Map files chosen by extension: .bt (maximum likelihood) or .ot (exact log-odds).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/temp_dir.hpp"
#include "sonarmap/io/map_file.hpp"

namespace sonarmap {
namespace {

namespace fs = std::filesystem;

OcTree16 smallTree() {
  OcTree16 tree(0.1);
  for (int i = 0; i < 20; ++i) tree.integrate(*tree.coder().keyOf({0.1 * i, 0.0, 0.0}), i % 2 == 0);
  tree.integrate(*tree.coder().keyOf({0.0, 1.0, 0.0}), true);
  return tree;
}

std::string firstLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(ioMapFile, ExtensionChoosesTheFormat) {
  EXPECT_EQ(mapFormatOf("a/map.bt"), MapFormat::kBinary);
  EXPECT_EQ(mapFormatOf("map.OT"), MapFormat::kFull);
  EXPECT_THROW(mapFormatOf("map.txt"), FileError);
  EXPECT_THROW(mapFormatOf("map"), FileError);
  EXPECT_THROW(mapFormatOf("bt"), FileError);
}

TEST(ioMapFile, WritesAndReadsBothFormats) {
  const test::TempDir dir;
  const OcTree16 tree = smallTree();
  writeMapFile(tree, dir.file("map.bt"));
  writeMapFile(tree, dir.file("map.Ot"));
  EXPECT_EQ(firstLine(dir.file("map.bt")), "# Octomap OcTree binary file");
  EXPECT_EQ(firstLine(dir.file("map.Ot")), "# Octomap OcTree file");

  const OcTree16 full = readMapFile(dir.file("map.Ot"));
  const OcTree16 binary = readMapFile(dir.file("map.bt"));
  EXPECT_EQ(full.counts().nodes, tree.counts().nodes);
  EXPECT_EQ(binary.counts().nodes, tree.counts().nodes);
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    EXPECT_EQ(full.search(leaf.key, leaf.depth), leaf.log_odds);  // .ot: exact
    const auto ml = binary.search(leaf.key, leaf.depth);           // .bt: occupied/free only
    ASSERT_TRUE(ml.has_value());
    EXPECT_EQ(binary.model().isOccupied(*ml), tree.model().isOccupied(leaf.log_odds));
  });
}

TEST(ioMapFile, UnknownExtensionWritesNothing) {
  const test::TempDir dir;
  EXPECT_THROW(writeMapFile(smallTree(), dir.file("map.png")), FileError);
  EXPECT_TRUE(fs::is_empty(dir.path()));
  std::ofstream(dir.file("map.txt")) << "not a map";
  EXPECT_THROW(readMapFile(dir.file("map.txt")), FileError);
  std::ofstream(dir.file("wrong.ot")) << "# Octomap OcTree binary file\n";  // .bt content, .ot name
  EXPECT_THROW(readMapFile(dir.file("wrong.ot")), FileError);
}

}  // namespace
}  // namespace sonarmap
