// `sonarmap map` on shared logs cut short (a full disk, a pulled cable, a stopped recorder): exit 0,
// a map of the beams before the cut, and the summary says where and why the reader stopped
// (docs/reliability.md). Skipped without ../shared/data.
#include <fstream>
#include <iterator>
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using cliCutLogs = CliTest;

/// The first `bytes` bytes of the shared log `name`, written under root as `as`; empty when the
/// shared data is absent.
std::string cutCopy(const fs::path& root, const std::string& name, std::size_t bytes, const std::string& as) {
  const fs::path source = fs::path(SONARMAP_SHARED_DATA) / name;
  if (!fs::exists(source)) return {};
  std::ifstream in(source, std::ios::binary);
  std::string data(bytes, '\0');
  in.read(data.data(), static_cast<std::streamsize>(bytes));
  writeFile(root / as, data);
  return (root / as).string();
}

struct Cut {
  const char* name;
  std::size_t bytes;
  const char* file;
  const char* said;  ///< what the summary's "skipped 1 by the reader: ..." says
};

TEST_F(cliCutLogs, ACutLogMapsTheBeamsBeforeTheCutAndSaysWhereItWasCut) {
  for (const Cut& cut : {
           Cut{"micron_pool_ros1.bag", 3900000, "pool.bag",
               "skipped 1 by the reader: byte 3188792: the file ends 711159 bytes into the chunk's 759240 bytes of data "
               "(cut short); its records read to byte 3899481, the last 519 bytes skipped"},
           Cut{"seanet_sector_target.V4LOG", 300000, "sector.V4LOG",
               "skipped 1 by the reader: byte 299483: length of record 346 is 688 but the file ends 517 bytes after the "
               "record's start (cut short)"},
           Cut{"cras_micron_tank_static.mat", 800000, "tank.mat",
               "byte 128: data element declares 1613726 bytes, 799864 left (cut short): the first 2768 of the 5604 "
               "elements of 'parsedData' read, the rest skipped"},
           Cut{"ping360_basin.bin", 200000, "basin.bin",
               "record 204 at byte 199260: data of 1224 bytes, the file ends 708 bytes after their start"}}) {
    const std::string path = cutCopy(root_, cut.name, cut.bytes, cut.file);
    if (path.empty()) GTEST_SKIP() << "no shared data at " << SONARMAP_SHARED_DATA;
    const ProgramRun result = run({"map", path, "-o", (out_ / "map.bt").string(), "-q"});
    EXPECT_EQ(result.exit_code, 0) << cut.name << ": " << result.err;
    EXPECT_NE(result.out.find(cut.said), std::string::npos) << cut.name << ": " << result.out;
    EXPECT_TRUE(fs::exists(out_ / "map.bt")) << cut.name;
    fs::remove(out_ / "map.bt");
  }
}

TEST_F(cliCutLogs, InfoSaysABagWasReadByScanningItsChunks) {
  std::string path = cutCopy(root_, "micron_pool_ros1.bag", 3900000, "pool.bag");
  if (path.empty()) GTEST_SKIP() << "no shared data at " << SONARMAP_SHARED_DATA;
  // as a stopped `rosbag record` leaves it: the header's index position (after "index_pos=") 0
  std::string bytes = readFile(path);
  bytes.replace(bytes.find("index_pos=") + 10, 8, std::string(8, '\0'));
  writeFile(path, bytes);
  const ProgramRun result = run({"info", path, "--json"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("the ROS bag is unindexed (its header's index position is 0, as a stopped `rosbag record` "
                            "leaves it): read by scanning its chunks from the start"),
            std::string::npos) << result.out;
}

}  // namespace
}  // namespace sonarmap::test
