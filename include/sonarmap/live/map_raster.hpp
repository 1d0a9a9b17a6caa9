#pragma once
/// @file map_raster.hpp
/// The map at one height as the live page draws it: a top view, north up, of a square window of
/// the map frame around the vehicle, one pixel per voxel (or per block of voxels when the window
/// holds more than a cap of pixels), and its PNG bytes.
///
/// Frames: the map frame of navigation.hpp (NWU: x north, y west, z up, metres). North up puts map
/// +x at the top of the picture and map −y (east) at its right.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sonarmap/mapping/provisional_beams.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// The part of the map to draw.
struct RasterWindow {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  ///< map x, y of the window's centre, metres
  double half_width_m = 50.0;  ///< half the window's edge, metres (> 0)
  double z_m = 0.0;            ///< map z of the voxel layer to cut (the layer holding it), metres
  /// Most pixels along one edge (≥ 16): a window of more voxels is drawn with blocks of k × k voxels
  /// per pixel, k the smallest integer that fits, starting at multiples of k voxels from the map's
  /// origin. 2560: a 50 m head's automatic window (LiveViewOptions) at 5 cm voxels is drawn whole.
  int max_side_px = 2560;
};

/// A top view of one voxel layer, north up.
struct MapRaster {
  /// CV_8U: occupied 0, free 255, unknown 128. Row 0 is the north edge, column 0 the west edge.
  /// A pixel of k × k voxels shows the highest class among them (occupied > free > unknown).
  /// Cropped to the known pixels plus a border of one unknown pixel; 1 × 1 unknown when the window
  /// holds no known voxel.
  cv::Mat image;
  double north_m = 0.0;   ///< map x of the top edge of row 0, metres
  double west_m = 0.0;    ///< map y of the left edge of column 0, metres
  double cell_m = 0.0;    ///< edge of a pixel, metres: the map's resolution × voxels_per_pixel
  int voxels_per_pixel = 1;
  double z_m = 0.0;       ///< the height asked for (RasterWindow::z_m), metres
  std::size_t occupied_px = 0;
  std::size_t free_px = 0;
};

/// The voxel layer holding `window.z_m`, within the window (clipped to the map's extent).
/// Cost: the leaves of the octree meeting the window's box one voxel high (forEachLeafInBox), plus
/// the pixels; measured in tests/live/test_map_raster.cpp.
/// @throws OutOfMapError when z_m lies outside the map; ValueError when the window's values are not
///         finite, half_width_m ≤ 0 or max_side_px < 16.
MapRaster rasterizeMap(const OcTree16& map, const RasterWindow& window);

/// The page's map tiles: a fixed grid of square pictures in the map frame, so that a beam redraws
/// the few tiles it touched and the page fetches only those. Pixels are blocks of
/// voxels_per_pixel × voxels_per_pixel voxels counted from the map's origin (as rasterizeMap's);
/// tile (i, j) holds map x in [i·edge_m, (i+1)·edge_m) and y in [j·edge_m, (j+1)·edge_m), edge_m =
/// tile_px · voxels_per_pixel · resolution_m; its row 0 is its north edge, column 0 its west edge.
struct TileGrid {
  double resolution_m = 0.1;  ///< the map's voxel edge, metres (> 0)
  int voxels_per_pixel = 1;   ///< ≥ 1
  int tile_px = 128;          ///< pixels along a tile's edge, ≥ 1
  double cell_m() const { return resolution_m * voxels_per_pixel; }
  double edge_m() const { return cell_m() * tile_px; }
  /// The tile holding map coordinate `coord_m` (x for i, y for j), metres.
  long tileOf(double coord_m) const;
  friend bool operator==(const TileGrid&, const TileGrid&) = default;
};

/// One tile of the page's map as it is sent, immutable once made (LiveView's raster thread).
struct MapTile {
  long i = 0, j = 0;          ///< its place in the grid (TileGrid)
  std::uint64_t version = 0;  ///< the map picture (RasterInfo::version) that last changed it
  cv::Mat image;              ///< TileRaster::image
  std::size_t occupied_px = 0, free_px = 0;
  std::string png_base64;     ///< its PNG (encodePng), base64 (RFC 4648)
  std::size_t png_bytes = 0;
};

/// One tile of the layer holding `z_m`.
struct TileRaster {
  cv::Mat image;  ///< CV_8U tile_px × tile_px: occupied 0, free 255, unknown 128 (MapRaster's classes)
  std::size_t occupied_px = 0, free_px = 0;
};

/// Tile (i, j) of `grid` in the voxel layer of `map` holding `z_m`: the cells rasterizeMap draws
/// there (the part outside the map's extent unknown), with the voxels `shown` in place of map's
/// (ShownMapVisitor: the map as shown during a live run, read without copying it).
/// @throws ValueError when map's resolution differs from grid.resolution_m, voxels_per_pixel or
///         tile_px < 1, or z_m is not finite; OutOfMapError when z_m lies outside the map.
TileRaster rasterizeTile(const OcTree16& map, std::span<const ShownVoxel> shown, const TileGrid& grid, long i, long j,
                         double z_m);

/// The centres (x, y), map frame, metres, of the pixels of `raster` showing `value` (0 occupied,
/// 255 free): what the page draws, for comparing with cellsInSlice (map_slice.hpp) in tests.
std::vector<Eigen::Vector2d> rasterCells(const MapRaster& raster, std::uint8_t value);

}  // namespace sonarmap
