#pragma once
/// @file echo_mosaic.hpp
/// The sonar mosaic surveyors know from SeaNet: every bin's echo intensity laid at its place on the
/// map's grid, seen from above, one value per voxel column: the highest intensity heard there.
/// Raw intensities (before detection), so that rock, sand and the shadows behind objects show as
/// the head heard them.

#include <functional>
#include <optional>

#include <Eigen/Geometry>

#include "sonarmap/mapping/geo_raster.hpp"
#include "sonarmap/sonar/beam_source.hpp"

namespace sonarmap {

/// The sonar's pose in the map (internal NWU) at a beam's time; nullopt: the beam has no pose (no
/// navigation then) and is left out.
using SonarPoseAt = std::function<std::optional<Eigen::Isometry3d>(double time_s)>;

/// One pass over `source`: each bin k of each beam placed at its centre, range (k + 0.5) ×
/// bin_length_m along the beam's bearing in the sonar's plane (x ahead, y starboard, z 0: the
/// sonar frame of navigation.hpp), by `pose_at(beam.time_s)`, into the voxel column (map x, y) of
/// edge `resolution_m` holding it (columns aligned on the map's voxels: multiples of resolution_m
/// from its zero). A column's value is the highest intensity of its bins, raised to 1 so that a
/// column heard as silent (0) differs from one never heard (0 in the grid: no data).
/// The grid covers the heard columns; a log without beams gives a 1 × 1 grid of 0.
/// Cost: one pass, O(bins); memory: the heard columns.
/// @throws ValueError when resolution_m is not positive and finite; what the source throws.
MosaicGrid echoMosaic(BeamSource& source, const SonarPoseAt& pose_at, double resolution_m);

}  // namespace sonarmap
