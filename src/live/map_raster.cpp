#include "sonarmap/live/map_raster.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/octree/box_copy.hpp"

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

/// Class rank per pixel of the voxels x_lo … x_hi, y_lo … y_hi (key indices, inclusive; those
/// outside the map are unknown) in blocks of per_px × per_px voxels from (x_lo, y_lo), blocks_x =
/// (x_hi − x_lo) / per_px + 1 rows and as many columns along y, already north up: row = blocks_x − 1 − block x, column = blocks_y − 1 − block y; and
/// the box of the known pixels (bottom < 0: none).
struct RankImage {
  cv::Mat rank;
  int top = 0, bottom = -1, left = 0, right = -1;
};

RankImage rankBlocks(const OcTree16& map, Index z_key, long x_lo, long y_lo, long x_hi, long y_hi, long per_px) {
  const int blocks_x = static_cast<int>((x_hi - x_lo) / per_px + 1);
  const int blocks_y = static_cast<int>((y_hi - y_lo) / per_px + 1);
  RankImage out;
  out.rank = cv::Mat(blocks_x, blocks_y, CV_8U, cv::Scalar(0));
  out.top = blocks_x;
  out.left = blocks_y;
  const long kLastIndex = 2L * static_cast<long>(Coder::offset()) - 1;
  const long kx_lo = std::max(x_lo, 0L), kx_hi = std::min(x_hi, kLastIndex);
  const long ky_lo = std::max(y_lo, 0L), ky_hi = std::min(y_hi, kLastIndex);
  if (kx_lo > kx_hi || ky_lo > ky_hi) return out;
  const OcTree16::KeyType min_key{{static_cast<Index>(kx_lo), static_cast<Index>(ky_lo), z_key}};
  const OcTree16::KeyType max_key{{static_cast<Index>(kx_hi), static_cast<Index>(ky_hi), z_key}};
  const LogOddsModel& model = map.model();
  map.forEachLeafInBox(min_key, max_key, [&](const LeafView<16>& leaf) {
    const Occupancy occupancy = model.classify(leaf.log_odds);
    const std::uint8_t value = occupancy == Occupancy::kOccupied ? 2 : (occupancy == Occupancy::kFree ? 1 : 0);
    if (value == 0) return;
    const long edge = static_cast<long>(leaf.edgeVoxels());
    const long xa = std::max<long>(leaf.key[0], kx_lo), xb = std::min<long>(leaf.key[0] + edge - 1, kx_hi);
    const long ya = std::max<long>(leaf.key[1], ky_lo), yb = std::min<long>(leaf.key[1] + edge - 1, ky_hi);
    if (xa > xb || ya > yb) return;
    const int row_first = blocks_x - 1 - static_cast<int>((xb - x_lo) / per_px);
    const int row_last = blocks_x - 1 - static_cast<int>((xa - x_lo) / per_px);
    const int col_first = blocks_y - 1 - static_cast<int>((yb - y_lo) / per_px);
    const int col_last = blocks_y - 1 - static_cast<int>((ya - y_lo) / per_px);
    out.top = std::min(out.top, row_first);
    out.bottom = std::max(out.bottom, row_last);
    out.left = std::min(out.left, col_first);
    out.right = std::max(out.right, col_last);
    for (int row = row_first; row <= row_last; ++row) {
      std::uint8_t* line = out.rank.ptr<std::uint8_t>(row);
      for (int col = col_first; col <= col_last; ++col) line[col] = std::max(line[col], value);
    }
  });
  return out;
}

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

  const RankImage ranks = rankBlocks(map, *z_key, x_lo, y_lo, x_hi, y_hi, per_px);
  const cv::Mat& rank = ranks.rank;
  int top = ranks.top, bottom = ranks.bottom, left = ranks.left, right = ranks.right;

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

long TileGrid::tileOf(double coord_m) const { return static_cast<long>(std::floor(coord_m / edge_m())); }

TileRaster rasterizeTile(const OcTree16& map, std::span<const ShownVoxel> shown, const TileGrid& grid, long i, long j,
                         double z_m) {
  if (grid.voxels_per_pixel < 1 || grid.tile_px < 1) throw ValueError("map tile: voxels_per_pixel and tile_px must be >= 1");
  if (map.resolution_m() != grid.resolution_m) {
    throw ValueError("map tile: the map's resolution " + std::to_string(map.resolution_m()) + " m is not the grid's " +
                     std::to_string(grid.resolution_m) + " m");
  }
  if (!std::isfinite(z_m)) throw ValueError("map tile: the height must be finite");
  const std::optional<Index> z_key = map.coder().indexOf(z_m);
  if (!z_key) throw OutOfMapError("map tile: height " + std::to_string(z_m) + " m is outside the map");
  const long per_px = grid.voxels_per_pixel;
  const long voxels = per_px * grid.tile_px;
  const long origin = static_cast<long>(Coder::offset());
  const long x_lo = origin + i * voxels, y_lo = origin + j * voxels;
  const long x_hi = x_lo + voxels - 1, y_hi = y_lo + voxels - 1;
  const auto inTile = [&](const ShownVoxel& v) {
    return v.key[2] == *z_key && v.key[0] >= x_lo && v.key[0] <= x_hi && v.key[1] >= y_lo && v.key[1] <= y_hi;
  };
  RankImage ranks;
  if (per_px == 1 || std::none_of(shown.begin(), shown.end(), inTile)) {
    ranks = rankBlocks(map, *z_key, x_lo, y_lo, x_hi, y_hi, per_px);
    // One voxel per pixel: a shown voxel is its pixel.
    for (const ShownVoxel& voxel : shown) {
      if (!inTile(voxel)) continue;
      const Occupancy occupancy = map.model().classify(voxel.log_odds);
      ranks.rank.at<std::uint8_t>(static_cast<int>(x_hi - voxel.key[0]), static_cast<int>(y_hi - voxel.key[1])) =
          occupancy == Occupancy::kOccupied ? 2 : (occupancy == Occupancy::kFree ? 1 : 0);
    }
  } else {
    // Blocks of voxels: the tile's layer copied with the shown voxels set, then drawn.
    const auto clip = [](long index) { return static_cast<Index>(std::clamp(index, 0L, 2L * static_cast<long>(Coder::offset()) - 1)); };
    OcTree16 part = copyLeavesInBox(map, OcTree16::KeyType{{clip(x_lo), clip(y_lo), *z_key}},
                                    OcTree16::KeyType{{clip(x_hi), clip(y_hi), *z_key}});
    for (const ShownVoxel& voxel : shown) {
      if (inTile(voxel)) part.updateNode(voxel.key, voxel.log_odds - part.search(voxel.key).value_or(0.0F), true);
    }
    part.updateInnerOccupancy();
    ranks = rankBlocks(part, *z_key, x_lo, y_lo, x_hi, y_hi, per_px);
  }
  TileRaster tile;
  tile.image.create(grid.tile_px, grid.tile_px, CV_8U);
  for (int row = 0; row < grid.tile_px; ++row) {
    const std::uint8_t* from = ranks.rank.ptr<std::uint8_t>(row);
    std::uint8_t* to = tile.image.ptr<std::uint8_t>(row);
    for (int col = 0; col < grid.tile_px; ++col) {
      tile.occupied_px += from[col] == 2;
      tile.free_px += from[col] == 1;
      to[col] = kGrey[from[col]];
    }
  }
  return tile;
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
