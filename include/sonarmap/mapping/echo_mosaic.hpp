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

/// What the mosaic takes of each beam.
struct EchoMosaicOptions {
  double resolution_m = 0.05;   ///< edge of a column: the map's resolution (> 0)
  double beam_width_rad = 0.0;  ///< each bin spread over this arc about the bearing (the head's width); 0: a ray
  double min_range_m = 0.0;     ///< bins nearer than this left out (the transducer's ring-down: the detector's minimum range)
};

/// One pass over `source`: each bin k of each beam at range (k + 0.5) × bin_length_m, spread over
/// options.beam_width_rad about the beam's bearing in the sonar's plane (x ahead, y starboard, z 0:
/// the sonar frame of navigation.hpp; points every half column along the arc), placed by
/// `pose_at(beam.time_s)` into the voxel columns (map x, y) of edge options.resolution_m it meets
/// (aligned on the map's voxels: multiples of the edge from its zero). A column's value is the
/// highest intensity of its bins, raised to 1 so that a column heard as silent (0) differs from one
/// never heard (0 in the grid: no data). Bins nearer than options.min_range_m are left out.
/// The grid covers the heard columns; a log without beams gives a 1 × 1 grid of 0.
/// Cost: one pass, O(bins × arc points); memory: the heard columns.
/// @throws ValueError when an option is negative, not finite, or the resolution not positive; what
///         the source throws.
MosaicGrid echoMosaic(BeamSource& source, const SonarPoseAt& pose_at, const EchoMosaicOptions& options);

}  // namespace sonarmap
