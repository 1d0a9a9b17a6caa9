#include "sonarmap/mapping/map_slice.hpp"

#include <algorithm>
#include <limits>

#include <opencv2/core.hpp>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// Calls visit(x0, y0, edge, occupancy) for every leaf meeting the band of voxels holding heights
/// z_min_m … z_max_m; x0/y0 are key indices of the leaf's lower corner and edge its width in voxels.
template <class Visit>
void forEachLeafInBand(const OcTree16& map, double z_min_m, double z_max_m, Visit&& visit) {
  if (z_min_m > z_max_m) throw ValueError("a height band needs z_min_m <= z_max_m");
  const long z_lo = map.coder().keyOfChecked({0.0, 0.0, z_min_m})[2];
  const long z_hi = map.coder().keyOfChecked({0.0, 0.0, z_max_m})[2];
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const long edge = static_cast<long>(leaf.edgeVoxels());
    const long z0 = static_cast<long>(leaf.key[2]);
    if (z0 > z_hi || z0 + edge - 1 < z_lo) return;
    visit(static_cast<long>(leaf.key[0]), static_cast<long>(leaf.key[1]), edge, map.model().classify(leaf.log_odds));
  });
}

}  // namespace

std::vector<Eigen::Vector2d> cellsInSlice(const OcTree16& map, double z_m, Occupancy wanted) {
  std::vector<Eigen::Vector2d> cells;
  const auto& coder = map.coder();
  forEachLeafInBand(map, z_m, z_m, [&](long x0, long y0, long edge, Occupancy occupancy) {
    if (occupancy != wanted) return;
    for (long x = x0; x < x0 + edge; ++x)
      for (long y = y0; y < y0 + edge; ++y)
        cells.emplace_back(coder.centerOf(static_cast<Key16::Index>(x)), coder.centerOf(static_cast<Key16::Index>(y)));
  });
  return cells;
}

cv::Mat renderSlice(const OcTree16& map, double z_m) { return renderSliceView(map, z_m).image; }

SliceView renderSliceView(const OcTree16& map, double z_m) { return renderBandView(map, z_m, z_m); }

SliceView renderBandView(const OcTree16& map, double z_min_m, double z_max_m) {
  long min_x = std::numeric_limits<long>::max(), min_y = min_x, max_x = std::numeric_limits<long>::min(), max_y = max_x;
  forEachLeafInBand(map, z_min_m, z_max_m, [&](long x0, long y0, long edge, Occupancy) {
    min_x = std::min(min_x, x0);
    min_y = std::min(min_y, y0);
    max_x = std::max(max_x, x0 + edge - 1);
    max_y = std::max(max_y, y0 + edge - 1);
  });
  const double res = map.resolution_m();
  if (min_x > max_x) return {cv::Mat(1, 1, CV_8U, cv::Scalar(128)), -res / 2.0, -res / 2.0, res};
  const int cols = static_cast<int>(max_x - min_x + 3);
  const int rows = static_cast<int>(max_y - min_y + 3);
  // Rank of each pixel: 0 unknown, 1 free, 2 occupied; a column shows the highest rank in the band.
  cv::Mat rank(rows, cols, CV_8U, cv::Scalar(0));
  forEachLeafInBand(map, z_min_m, z_max_m, [&](long x0, long y0, long edge, Occupancy occupancy) {
    const unsigned char value = occupancy == Occupancy::kOccupied ? 2 : (occupancy == Occupancy::kFree ? 1 : 0);
    const int left = static_cast<int>(x0 - min_x + 1);
    const int top = rows - 1 - static_cast<int>(y0 + edge - 1 - min_y + 1);  // +y up
    cv::Mat cells = rank(cv::Rect(left, top, static_cast<int>(edge), static_cast<int>(edge)));
    cv::max(cells, cv::Scalar(value), cells);
  });
  cv::Mat image(rows, cols, CV_8U, cv::Scalar(128));
  image.setTo(255, rank == 1);
  image.setTo(0, rank == 2);
  // Column 0 and the last row are the border voxel before min_x and min_y.
  const auto& coder = map.coder();
  return {image, coder.centerOf(static_cast<Key16::Index>(min_x)) - 1.5 * res,
          coder.centerOf(static_cast<Key16::Index>(min_y)) - 1.5 * res, res};
}

}  // namespace sonarmap
