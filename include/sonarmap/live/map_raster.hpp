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
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

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

/// The centres (x, y), map frame, metres, of the pixels of `raster` showing `value` (0 occupied,
/// 255 free): what the page draws, for comparing with cellsInSlice (map_slice.hpp) in tests.
std::vector<Eigen::Vector2d> rasterCells(const MapRaster& raster, std::uint8_t value);

}  // namespace sonarmap
