#pragma once
/// @file map_figures.hpp
/// Readable figures of an occupancy map (figure.hpp): the 2D slice, the 3D top and side views, and
/// the distance of the occupied voxels to the ground truth. Each is composeFigure()'s BGR image,
/// CV_8UC3, at least kMinFigureLongSide_px on its long side, with axes in metres of the map frame
/// (x to the right; y up in the top views, z up in the side view), the title line given, and a
/// legend. Tracks are map-frame positions in metres (e.g. the sonar's positions along a run:
/// sonarToMap(fix, mounting).translation() of each navigation fix) drawn as a red line
/// (kTrackBgr) with a circle at their start; a single position (a static sonar) is a red dot
/// labelled "sonar"; an empty track draws nothing.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// The slice at height `z_m` (renderSliceView): occupied voxels near-black (kOccupiedBgr), free
/// light grey (kFreeBgr), unknown white, axes x (m) and y (m); the track's (x, y).
/// @throws OutOfMapError when z_m is outside the map.
cv::Mat sliceFigure(const OcTree16& map, double z_m, const std::string& title,
                    const std::vector<Eigen::Vector3d>& track_m = {});

/// The top view (renderTopView): each column's highest occupied voxel coloured by its height
/// (viridis, colour bar "z (m)"), free columns light grey, unknown white; the track's (x, y).
cv::Mat topViewFigure(const OcTree16& map, const std::string& title, const std::vector<Eigen::Vector3d>& track_m = {});

/// The side view (renderSideView), looking along +y: the occupied voxel nearest the viewer
/// coloured by its y (colour bar "y (m)"); axes x (m) and z (m); the track's (x, z).
cv::Mat sideViewFigure(const OcTree16& map, const std::string& title, const std::vector<Eigen::Vector3d>& track_m = {});

/// Where the map is wrong: the top view, each (x, y) column holding an occupied voxel of the
/// evaluated region coloured by the largest distance to the truth among them
/// (GroundTruthReport::occupied_errors; COLORMAP_TURBO from 0 m, dark blue, to max(2 T,
/// surface_error_p90_m), dark red, larger distances in dark red and the bar's top labelled ">="),
/// other known columns light grey, unknown white. When the evaluated slab spans more than one
/// layer (z_max_m > z_min_m), the side view along +y, each (x, z) pixel coloured alike, is stacked
/// under it. The titles are `title` + ", top view" / ", side view along +y". `sensors_m`, e.g.
/// eval's --sensor-pose positions, are drawn as the track ("sonar positions").
cv::Mat surfaceErrorFigure(const OcTree16& map, const GroundTruthReport& report, const std::string& title,
                           const std::vector<Eigen::Vector3d>& sensors_m = {});

}  // namespace sonarmap
