#include "sonarmap/live/map_raster.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using Coder = KeyCoder<16>;
using Index = Coder::Index;

/// Key index of `coord_m`, clamped to the map's extent.
long clampedIndex(const Coder& coder, double coord_m) {
  const double offset = Coder::offset();
  const double cell = std::clamp(std::floor(coord_m / coder.resolution_m()), -offset, offset - 1.0);
  return static_cast<long>(cell + offset);
}

/// Grey level of a class rank: 0 unknown, 1 free, 2 occupied.
constexpr std::uint8_t kGrey[3] = {128, 255, 0};

}  // namespace

MapRaster rasterizeMap(const OcTree16& map, const RasterWindow& window) {
  if (!window.centre_m.allFinite() || !std::isfinite(window.half_width_m) || !std::isfinite(window.z_m)) {
    throw ValueError("map raster: the window's centre, half width and height must be finite");
  }
  if (!(window.half_width_m > 0.0)) throw ValueError("map raster: the window's half width must be > 0 m");
  if (window.max_side_px < 16) throw ValueError("map raster: max_side_px must be >= 16");
  const Coder& coder = map.coder();
  const double res = coder.resolution_m();
  const std::optional<Index> z_key = coder.indexOf(window.z_m);
  if (!z_key) {
    throw OutOfMapError("map raster: height " + std::to_string(window.z_m) + " m is outside the map at resolution " +
                        std::to_string(res) + " m");
  }
  long x_lo = clampedIndex(coder, window.centre_m.x() - window.half_width_m);
  const long x_hi = clampedIndex(coder, window.centre_m.x() + window.half_width_m);
  long y_lo = clampedIndex(coder, window.centre_m.y() - window.half_width_m);
  const long y_hi = clampedIndex(coder, window.centre_m.y() + window.half_width_m);
  const long span = std::max(x_hi - x_lo, y_hi - y_lo) + 1;
  const long per_px = std::max(1L, (span + window.max_side_px - 1) / window.max_side_px);
  // Blocks start at multiples of per_px voxels from the map's origin: successive rasters of a
  // moving window put the same voxels in the same pixel, and pixel edges fall on multiples of cell_m.
  const long origin = static_cast<long>(Coder::offset());
  x_lo -= ((x_lo - origin) % per_px + per_px) % per_px;
  y_lo -= ((y_lo - origin) % per_px + per_px) % per_px;
  const int blocks_x = static_cast<int>((x_hi - x_lo) / per_px + 1);
  const int blocks_y = static_cast<int>((y_hi - y_lo) / per_px + 1);

  // Class rank per pixel, already north up: row = blocks_x − 1 − block x, column = blocks_y − 1 − block y.
  cv::Mat rank(blocks_x, blocks_y, CV_8U, cv::Scalar(0));
  const OcTree16::KeyType min_key{{static_cast<Index>(x_lo), static_cast<Index>(y_lo), *z_key}};
  const OcTree16::KeyType max_key{{static_cast<Index>(x_hi), static_cast<Index>(y_hi), *z_key}};
  const LogOddsModel& model = map.model();
  int top = blocks_x, bottom = -1, left = blocks_y, right = -1;  // the known pixels' box
  map.forEachLeafInBox(min_key, max_key, [&](const LeafView<16>& leaf) {
    const Occupancy occupancy = model.classify(leaf.log_odds);
    const std::uint8_t value = occupancy == Occupancy::kOccupied ? 2 : (occupancy == Occupancy::kFree ? 1 : 0);
    if (value == 0) return;
    const long edge = static_cast<long>(leaf.edgeVoxels());
    const long xa = std::max<long>(leaf.key[0], x_lo), xb = std::min<long>(leaf.key[0] + edge - 1, x_hi);
    const long ya = std::max<long>(leaf.key[1], y_lo), yb = std::min<long>(leaf.key[1] + edge - 1, y_hi);
    if (xa > xb || ya > yb) return;
    const int row_first = blocks_x - 1 - static_cast<int>((xb - x_lo) / per_px);
    const int row_last = blocks_x - 1 - static_cast<int>((xa - x_lo) / per_px);
    const int col_first = blocks_y - 1 - static_cast<int>((yb - y_lo) / per_px);
    const int col_last = blocks_y - 1 - static_cast<int>((ya - y_lo) / per_px);
    top = std::min(top, row_first);
    bottom = std::max(bottom, row_last);
    left = std::min(left, col_first);
    right = std::max(right, col_last);
    for (int row = row_first; row <= row_last; ++row) {
      std::uint8_t* line = rank.ptr<std::uint8_t>(row);
      for (int col = col_first; col <= col_last; ++col) line[col] = std::max(line[col], value);
    }
  });

  MapRaster raster;
  raster.cell_m = res * static_cast<double>(per_px);
  raster.voxels_per_pixel = static_cast<int>(per_px);
  raster.z_m = window.z_m;
  if (bottom < 0) {
    raster.image = cv::Mat(1, 1, CV_8U, cv::Scalar(kGrey[0]));
    raster.north_m = window.centre_m.x() + raster.cell_m / 2.0;
    raster.west_m = window.centre_m.y() + raster.cell_m / 2.0;
    return raster;
  }
  // One unknown pixel around the known ones.
  top = std::max(top - 1, 0);
  left = std::max(left - 1, 0);
  bottom = std::min(bottom + 1, blocks_x - 1);
  right = std::min(right + 1, blocks_y - 1);
  raster.image.create(bottom - top + 1, right - left + 1, CV_8U);
  for (int row = top; row <= bottom; ++row) {
    const std::uint8_t* from = rank.ptr<std::uint8_t>(row);
    std::uint8_t* to = raster.image.ptr<std::uint8_t>(row - top);
    for (int col = left; col <= right; ++col) {
      const std::uint8_t value = from[col];
      raster.occupied_px += value == 2;
      raster.free_px += value == 1;
      to[col - left] = kGrey[value];
    }
  }
  const long block_x = blocks_x - 1 - top;   // block of row 0
  const long block_y = blocks_y - 1 - left;  // block of column 0
  raster.north_m = (Coder::cellOf(static_cast<Index>(x_lo)) + static_cast<double>((block_x + 1) * per_px)) * res;
  raster.west_m = (Coder::cellOf(static_cast<Index>(y_lo)) + static_cast<double>((block_y + 1) * per_px)) * res;
  return raster;
}

std::vector<Eigen::Vector2d> rasterCells(const MapRaster& raster, std::uint8_t value) {
  std::vector<Eigen::Vector2d> cells;
  for (int row = 0; row < raster.image.rows; ++row) {
    const std::uint8_t* line = raster.image.ptr<std::uint8_t>(row);
    for (int col = 0; col < raster.image.cols; ++col) {
      if (line[col] != value) continue;
      cells.emplace_back(raster.north_m - (row + 0.5) * raster.cell_m, raster.west_m - (col + 0.5) * raster.cell_m);
    }
  }
  return cells;
}

}  // namespace sonarmap
