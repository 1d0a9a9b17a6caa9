#pragma once
/// @file map_slice.hpp
/// Horizontal slices of a map (the 2D map of paper §6 lies in the sonar's plane) and projections
/// of a band of heights (a 3D map's occupied band, seen from above).

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// Centres (x, y) in metres, map frame, of the finest voxels in the slice containing height
/// `z_m` whose occupancy is `wanted`. Pruned leaves contribute each of their finest voxels.
/// @throws OutOfMapError when z_m is outside the map.
std::vector<Eigen::Vector2d> cellsInSlice(const OcTree16& map, double z_m, Occupancy wanted);

/// A slice's top view and where it lies.
struct SliceView {
  cv::Mat image;         ///< CV_8U, renderSlice's picture
  double left_m = 0.0;   ///< x of the left edge of column 0, metres, map frame
  double bottom_m = 0.0; ///< y of the lower edge of the last row, metres, map frame
  double pixel_m = 0.0;  ///< edge of a pixel: the map's resolution, metres
};

/// renderSlice's image with its position in the map frame (for axes in metres, figure.hpp).
/// @throws OutOfMapError when z_m is outside the map.
SliceView renderSliceView(const OcTree16& map, double z_m);

/// The band of heights from the voxel holding `z_min_m` to the one holding `z_max_m` projected
/// along z: a pixel is occupied (0) when any voxel of its column in the band is, else free (255)
/// when any is, else unknown (128). Same layout as renderSliceView, which is the band of one
/// voxel (z_min_m = z_max_m).
/// @throws OutOfMapError when z_min_m or z_max_m is outside the map; ValueError when z_min_m > z_max_m.
SliceView renderBandView(const OcTree16& map, double z_min_m, double z_max_m);

/// Top view of the slice at `z_m`, one pixel per voxel: occupied 0 (black), free 255 (white),
/// unknown 128 (grey). +x to the right, +y up. The image spans the known voxels of the slice
/// plus a one-voxel border; an empty slice gives a 1 × 1 grey image. CV_8U, rows × cols.
/// @throws OutOfMapError when z_m is outside the map.
cv::Mat renderSlice(const OcTree16& map, double z_m);

}  // namespace sonarmap
