// The head's own housing on the shared real logs (../shared/data/README.md; skipped without them):
// the automatic minimum range cuts the bright band the housing and the transducer's ring-down make
// in every beam, and `map`'s summary gives the minimum ranges the sweeps used, lowest .. highest.

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

/// The lowest and highest minimum range of a summary line ("min range 0.31 m" or
/// "min range 0.31 .. 0.62 m"); NaN when the line has none.
struct MinRange {
  double lowest_m = std::nan("");
  double highest_m = std::nan("");
};

MinRange summaryMinRange(const std::string& out) {
  MinRange range;
  const std::size_t at = out.find("min range ");
  if (at == std::string::npos) return range;
  const std::string rest = out.substr(at + 10);
  if (std::sscanf(rest.c_str(), "%lf .. %lf m", &range.lowest_m, &range.highest_m) == 1) range.highest_m = range.lowest_m;
  return range;
}

/// Occupied finest voxels of a written map whose centre lies within `distance_m` of the head (the
/// map's origin: these logs have no navigation), and the nearest occupied centre's distance.
struct NearHead {
  std::size_t voxels = 0;
  double nearest_m = INFINITY;
};

NearHead occupiedNearHead(const fs::path& bt, double distance_m) {
  octomap::OcTree tree(0.1);
  EXPECT_TRUE(tree.readBinary(bt.string()));
  NearHead near;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double d = it.getCoordinate().norm();
    near.nearest_m = std::min(near.nearest_m, d);
    if (d < distance_m) {
      const double cells = std::round(it.getSize() / tree.getResolution());
      near.voxels += static_cast<std::size_t>(cells * cells * cells);
    }
  }
  return near;
}

class cliHousing : public CliTest {
 protected:
  /// Maps a shared log with the defaults into out/map.bt; false (and skips) when it is absent.
  bool mapShared(const char* name) {
    const fs::path path = fs::path(SONARMAP_SHARED_DATA) / name;
    if (!fs::exists(path)) return false;
    result_ = run({"map", "-q", path.string(), "-o", (out_ / "map.bt").string()});
    EXPECT_EQ(result_.exit_code, 0) << result_.err;
    return true;
  }
  ProgramRun result_;
};

// The pool bag's Micron shows its housing and ring-down as a band of 40–90 counts over black water
// in every beam out to about 1 m: too faint for the median's band rule, it was mapped as a ring of
// obstacles around the head (55 occupied voxels within 0.5 m, "min range 0.00 m").
TEST_F(cliHousing, PoolBagHousingIsNotMapped) {
  if (!mapShared("micron_pool_ros1.bag")) GTEST_SKIP() << "shared data absent: micron_pool_ros1.bag";
  const MinRange range = summaryMinRange(result_.out);
  EXPECT_GT(range.lowest_m, 0.3) << result_.out;
  EXPECT_LE(range.lowest_m, range.highest_m) << result_.out;
  EXPECT_LE(occupiedNearHead(out_ / "map.bt", 0.5).voxels, 2u);
}

// The Ping360 basin log changes range (2, 10 and 20 m) and each sweep calibrates its own minimum
// range: the summary's lowest is a bound on every occupied voxel's distance from the head.
TEST_F(cliHousing, Ping360BasinHasNothingNearerThanTheLowestMinRange) {
  if (!mapShared("ping360_basin.bin")) GTEST_SKIP() << "shared data absent: ping360_basin.bin";
  const MinRange range = summaryMinRange(result_.out);
  ASSERT_FALSE(std::isnan(range.lowest_m)) << result_.out;
  EXPECT_LE(range.lowest_m, range.highest_m) << result_.out;
  // A voxel is occupied when a beam's echo falls in it: its centre may lie half a diagonal nearer.
  const double half_diagonal_m = 0.5 * std::sqrt(3.0) * 0.05;
  EXPECT_GE(occupiedNearHead(out_ / "map.bt", 0.0).nearest_m, range.lowest_m - half_diagonal_m) << result_.out;
}

}  // namespace
}  // namespace sonarmap::test
