#pragma once
/// @file map_figures.hpp
/// Readable figures of an occupancy map (figure.hpp): the 2D slice, the 3D top and side views, and
/// the distance of the occupied voxels to the ground truth. Each is composeFigure()'s BGR image,
/// CV_8UC3, at least kMinFigureLongSide_px on its long side, with the title line given and a legend.
/// The map figures (slice, band, top and side views) take the map in ENU (map_frame.hpp's
/// mapInFrame(map, MapFrame::kEnu)) and draw it as a chart: east to the right, north up (z up in
/// the side view), axes labelled "east (m)", "north (m)", "up z (m)"; their tracks are ENU too.
/// surfaceErrorFigure draws the frame of its map and report (x right; y or z up), axes "x (m)".
/// Tracks are positions in metres (e.g. the sonar's positions along a run:
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

/// The slice at height `z_m` (renderSliceView) of an ENU map: occupied voxels near-black
/// (kOccupiedBgr), free light grey (kFreeBgr), unknown white, axes east (m) and north (m); the
/// track's (east, north).
/// @throws OutOfMapError when z_m is outside the map.
cv::Mat sliceFigure(const OcTree16& map, double z_m, const std::string& title,
                    const std::vector<Eigen::Vector3d>& track_m = {});

/// As sliceFigure for the band of heights z_min_m … z_max_m projected from above (renderBandView:
/// a column is occupied when any voxel of it in the band is).
/// @throws OutOfMapError when a bound is outside the map; ValueError when z_min_m > z_max_m.
cv::Mat bandFigure(const OcTree16& map, double z_min_m, double z_max_m, const std::string& title,
                   const std::vector<Eigen::Vector3d>& track_m = {});

/// The top view (renderTopView) of an ENU map: each column's highest occupied voxel coloured by its
/// height (viridis, colour bar "up z (m)"), free columns light grey, unknown white; the track's
/// (east, north).
cv::Mat topViewFigure(const OcTree16& map, const std::string& title, const std::vector<Eigen::Vector3d>& track_m = {});

/// The side view (renderSideView) of an ENU map, looking north (along +y): the occupied voxel
/// nearest the viewer coloured by its north (colour bar "north (m)"); axes east (m) and up z (m);
/// the track's (east, z).
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
