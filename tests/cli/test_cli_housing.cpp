// The head's own housing on the shared real logs (../shared/data/README.md; skipped without them):
// the automatic minimum range cuts the bright band the housing and the transducer's ring-down make
// in every beam, `map`'s summary gives the minimum ranges the sweeps used, lowest .. highest, and
// what rises out of the near field's reverberation is mapped, not the edge of its cut.

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
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

// The basin's 10 m turns: the near field's reverberation (saturated to 1.5–2 m in every beam, bright
// to 2.5–5 m where the floor enters the aperture) is not a wall, and the wall that rises out of its
// tail (bearings 65–100°, 2.5–6 m) and the posts behind it (110–118°, 4.3–7 m) are
// (../shared/data/README.md). The occupied voxels at 3.0–4.6 m from the head were 58 % of the map:
// each sweep's cut of the near field, at 3.0–4.3 m, made a ring of obstacles at its edge.
TEST_F(cliHousing, Ping360BasinNearFieldIsNotARing) {
  if (!mapShared("ping360_basin.bin")) GTEST_SKIP() << "shared data absent: ping360_basin.bin";
  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary((out_ / "map.bt").string()));
  std::size_t occupied = 0, ring = 0, beyond_east = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double cells = std::round(it.getSize() / tree.getResolution());
    const auto voxels = static_cast<std::size_t>(cells * cells * cells);
    const octomap::point3d p = it.getCoordinate();  // ENU: x east, y north
    const double range_m = std::hypot(p.x(), p.y());
    const double bearing_deg = std::fmod(std::atan2(p.x(), p.y()) * 180.0 / std::numbers::pi + 360.0, 360.0);
    occupied += voxels;
    if (range_m >= 3.0 && range_m <= 4.6) ring += voxels;
    if (range_m > 4.6 && bearing_deg >= 45.0 && bearing_deg <= 130.0) beyond_east += voxels;
  }
  ASSERT_GT(occupied, 0u);
  EXPECT_LE(static_cast<double>(ring) / static_cast<double>(occupied), 0.25) << ring << " of " << occupied;
  EXPECT_GE(beyond_east, 100u);
}

// --max-near-field is the farthest end of the automatic minimum range: the basin's median band rule
// reaches 3.0–4.3 m, and the option left it there ("min range 0.60 .. 4.26 m" with 1 m).
TEST_F(cliHousing, MaxNearFieldBoundsTheAutomaticMinimumRange) {
  const fs::path path = fs::path(SONARMAP_SHARED_DATA) / "ping360_basin.bin";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: ping360_basin.bin";
  const ProgramRun run1 = run({"map", "-q", path.string(), "-o", (out_ / "map.bt").string(), "--max-near-field", "1"});
  ASSERT_EQ(run1.exit_code, 0) << run1.err;
  const MinRange range = summaryMinRange(run1.out);
  ASSERT_FALSE(std::isnan(range.highest_m)) << run1.out;
  EXPECT_LE(range.highest_m, 1.0 + 1e-9) << run1.out;
}

// --min-range is the nearest echo used, also where the self-reflection band reaches farther (the
// band was zeroed up to its end whatever the option: "min range 0.30 .. 4.26 m" with 0.3).
TEST_F(cliHousing, MinRangeIsTheNearestEchoUsed) {
  const fs::path path = fs::path(SONARMAP_SHARED_DATA) / "ping360_basin.bin";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: ping360_basin.bin";
  const ProgramRun run1 = run({"map", "-q", path.string(), "-o", (out_ / "map.bt").string(), "--min-range", "0.3"});
  ASSERT_EQ(run1.exit_code, 0) << run1.err;
  const MinRange range = summaryMinRange(run1.out);
  EXPECT_NEAR(range.lowest_m, 0.3, 1e-9) << run1.out;
  EXPECT_NEAR(range.highest_m, 0.3, 1e-9) << run1.out;
}

// Echoes hidden by a minimum range are reported with where they were, over the sweeps that hid them:
// the nearest band's end below the farthest minimum range (a warning quoted one sweep's figures for
// echoes counted over all of them: "between the band's end (3.65 m) and the minimum range (3.65 m)").
TEST_F(cliHousing, HiddenEchoesWarningStatesWhereTheyLie) {
  const fs::path path = fs::path(SONARMAP_SHARED_DATA) / "ping360_basin.bin";
  if (!fs::exists(path)) GTEST_SKIP() << "shared data absent: ping360_basin.bin";
  const ProgramRun run1 = run({"map", path.string(), "-o", (out_ / "map.bt").string(), "--min-range", "3"});
  ASSERT_EQ(run1.exit_code, 0) << run1.err;
  const std::size_t at = run1.err.find("minimum range (");
  ASSERT_NE(at, std::string::npos) << run1.err;
  double from_m = NAN, to_m = NAN;
  ASSERT_EQ(std::sscanf(run1.err.c_str() + at, "minimum range (%lf .. %lf m", &from_m, &to_m), 2) << run1.err;
  EXPECT_LT(from_m, to_m) << run1.err;
  EXPECT_NEAR(to_m, 3.0, 0.01) << run1.err;
}

}  // namespace
}  // namespace sonarmap::test
