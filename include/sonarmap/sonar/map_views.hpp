#pragma once
/// @file map_views.hpp
/// Pictures of a 3D map: a top view coloured by height and a side view, each with its
/// colour scale, and the map's height extent. Each finest voxel is one pixel, or a square of whole
/// pixels when the view is magnified; pruned leaves count as each of their finest voxels. The 2D
/// slice of the sonar's plane is map_slice.hpp's renderSlice.
///
/// Colours (BGR, CV_8UC3): occupied voxels through OpenCV's COLORMAP_VIRIDIS (dark violet at the
/// low end of the scale, yellow at the high end), pixels with free voxels but no occupied one light
/// grey (kFreeGrey), pixels with nothing known white; a mid-grey frame (kFrameGrey) on the
/// one-voxel border around the known voxels. A legend panel to the right of the view shows the
/// colour bar with the scale's ends in metres, or "none" when no voxel is occupied.

#include <cstddef>
#include <optional>

#include <opencv2/core.hpp>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Lowest and highest centre z of the occupied finest voxels, metres, map frame.
struct HeightExtent {
  double min_m = 0.0;
  double max_m = 0.0;
};

/// The height extent of the occupied voxels; nullopt when none is occupied.
std::optional<HeightExtent> occupiedHeightExtent(const OcTree16& map);

/// A rendered view and the colour scale its occupied pixels were drawn with.
struct MapView {
  cv::Mat image;                    ///< CV_8UC3 (BGR): the view, then the legend panel on its right
  int view_cols = 0;                ///< width of the view itself in pixels (the legend panel follows it)
  int view_rows = 0;                ///< height of the view itself in pixels (the image may be taller)
  int pixels_per_voxel = 1;         ///< edge of a voxel's square in the view, pixels
  double scale_min_m = 0.0;         ///< value drawn at the scale's low end, metres
  double scale_max_m = 0.0;         ///< value drawn at the scale's high end (== min when one value)
  std::size_t occupied_pixels = 0;  ///< pixels of the view showing an occupied voxel
  double left_m = 0.0;    ///< map coordinate (x) of the view's left edge, metres (its border included)
  double bottom_m = 0.0;  ///< map coordinate of its lower edge (y top view, z side view), metres
  double voxel_m = 0.0;   ///< the map's resolution: a voxel's edge, metres (pixels_per_voxel pixels)
};

/// Light grey of the pixels with free voxels and no occupied one; 255 (white) is unknown.
inline constexpr unsigned char kFreeGrey = 200;
/// Mid grey of the frame on the view's one-voxel border.
inline constexpr unsigned char kFrameGrey = 128;
/// Width of the legend panel, pixels; the image is at least kLegendMinRows tall.
inline constexpr int kLegendCols = 76;
inline constexpr int kLegendMinRows = 100;
/// The largest magnification of a view: pixels per voxel edge.
inline constexpr int kMaxPixelsPerVoxel = 8;

/// The BGR colour of `value_m` on a scale from `min_m` to `max_m` (COLORMAP_VIRIDIS; the middle
/// colour when min_m == max_m).
cv::Vec3b scaleColour(double value_m, double min_m, double max_m);

/// Top view, looking down (−z): +x to the right, +y up. Each (x, y) column shows its highest
/// occupied voxel coloured by that voxel's centre z; the scale spans the columns' highest
/// occupied z (its ends: scale_min_m, scale_max_m), the legend is titled "z (m)". The view spans
/// the known voxels' x and y plus a one-voxel border (1 × 1 plus the border for an empty map).
/// @param max_side_px  > 0: the view is magnified by the largest whole factor, at most
///                     kMaxPixelsPerVoxel, that keeps its larger side within max_side_px (at least
///                     1); 0: one pixel per voxel.
MapView renderTopView(const OcTree16& map, int max_side_px = 0);

/// Side view, looking along +y (from −y): +x to the right, +z up. Each (x, z) pixel shows the
/// occupied voxel nearest the viewer (lowest y) coloured by its centre y; the scale spans those
/// y, the legend is titled "y (m)". Walls' heights and the seabed's slope show. The view spans the
/// known voxels' x and z plus a one-voxel border. `max_side_px` as renderTopView's.
MapView renderSideView(const OcTree16& map, int max_side_px = 0);

}  // namespace sonarmap
