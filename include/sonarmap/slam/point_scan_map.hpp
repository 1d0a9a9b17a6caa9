#pragma once
/// @file point_scan_map.hpp
/// Formed scans (scan_forming.hpp, point_scans.hpp) placed with their poses: the points in NED's
/// plane for a picture, and an occupancy map of them, so that a corrected track can be seen in the
/// places it was corrected by (the marina's quays drawn once, not twice). What `sonarmap localize
/// --png` and `--map` write.

#include <vector>

#include <Eigen/Core>

#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/slam/pose2.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap {

/// Each scan's points (its reference frame) placed with its pose (poses[k]: scan k's reference
/// pose in NED's plane, SlamResult::scan_poses or SonarScan::dead_reckoning), NED's plane (x north,
/// y east), metres. Scans beyond `poses` are left out.
std::vector<Eigen::Vector2d> placedScanPoints(const std::vector<SonarScan>& scans, const std::vector<Pose2>& poses);

/// What a map of the scans can resolve, metres: their points' typical σ, the median over every
/// scan's points of √(the larger eigenvalue of its covariance) (ScanPoint::covariance_m2: the
/// range's σ along its beam, the beam's width across it). `localize`'s default voxel and picture
/// cell. (Not scan_matcher.hpp's typicalPointSigma, the correlative search's smoothing.)
/// @throws ValueError when no scan has a point.
double scanMapResolution(const std::vector<SonarScan>& scans);

/// A planar occupancy map of the scans placed with `poses` (as placedScanPoints), in the mapper's
/// internal frame (NWU: nedToMap(), nav/navigation.hpp; write it with writeMapFileInFrame) at
/// depth 0: each point a hit, the ray to it from the sonar that saw it (ScanPoint::toward_sonar ·
/// range_m back from it; the point alone where that is unknown) free, with the octree's default
/// sensor model (OctoMap's: hit 0.7, miss 0.4, clamping 0.12–0.97). Each scan is one insertion per
/// sonar position (insertPointCloud: a voxel is updated once per beam).
/// @throws ValueError for a resolution that is not finite and > 0; OutOfMapError, before anything
///         is inserted, when a point or a sonar position lies outside the map at that resolution
///         (±mapHalfExtent_m, mapping/local_origin.hpp), naming the resolution that would hold them.
OcTree16 mapScans(const std::vector<SonarScan>& scans, const std::vector<Pose2>& poses, double resolution_m);

}  // namespace sonarmap
