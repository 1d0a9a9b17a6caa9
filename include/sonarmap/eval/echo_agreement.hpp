#pragma once
/// @file echo_agreement.hpp
/// How well a map agrees with the strong echoes of the log it was made from: the measure for real
/// logs, which have no ground truth (docs/accuracy.md, "Real logs").
///
/// A strong echo is a bin whose intensity rises at least `strong_db` above the median intensity of
/// its range over the log's beams of the same head setting (sweeps.hpp: range scale and gain;
/// the intensities' dB span is the beam's own, else 45 dB): what returns at one range in most
/// bearings (the transducer's ringing, the vehicle, a surface ring) is not an echo of the scene,
/// and the measure uses no detector, threshold model or near-field estimate of the mapper's. Each
/// strong bin is a point on its beam's axis at the bin's centre range, placed in the map frame with
/// the beam's pose. Then, with a tolerance τ (default 0.3 m, about a 2° beam's width at 10 m):
///  - precision: the share of the map's occupied voxels (their centres) within τ of an echo point;
///  - recall: the share of echo points within τ of an occupied voxel's centre;
///  - first-echo recall: the same over each beam's nearest strong echo only (a mapper of first
///    obstacles cannot place what lies behind them: multipath, a second surface, the far side of a
///    target).
/// Made for planar maps (the sonar's plane, where the echo points lie); distances are 3D.

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Options of echoAgreement(), in physical units.
struct EchoAgreementOptions {
  double strong_db = 20.0;    ///< rise above the range's median that makes a bin a strong echo, dB, > 0
  double tolerance_m = 0.3;   ///< match distance τ, metres, > 0
  /// @throws ValueError naming the option when it is not finite and > 0.
  void validate() const;
};

/// The measure's counts and shares (see the file's comment).
struct EchoAgreement {
  std::size_t echo_points = 0;      ///< strong echo bins of the placed beams
  std::size_t beams_with_echo = 0;  ///< placed beams with at least one
  std::size_t occupied = 0;         ///< occupied voxels of the map
  double precision = 0.0;           ///< [0, 1]; 0 when the map has no occupied voxel
  double recall = 0.0;              ///< [0, 1]; 0 when there is no echo point
  double first_echo_recall = 0.0;   ///< [0, 1]; 0 when no beam has a strong echo
};

/// Scores `map` against the strong echoes of `log` (see the file's comment).
/// @param sonar_to_map  per beam of `log`, the sonar's pose in the map frame, nullopt for a beam not
///                      placed (no navigation at its time); empty: every beam at the identity (a
///                      static sonar at the map's origin, as mapSonarLog without navigation).
/// Cost: O(bins) for the medians and echo points, O((points + voxels) log) for the nearest-neighbour
/// queries (nanoflann k-d trees).
/// @throws ValueError for invalid options, or poses that are neither empty nor one per beam.
EchoAgreement echoAgreement(const OcTree16& map, const SonarLog& log,
                            const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map = {},
                            const EchoAgreementOptions& options = {});

}  // namespace sonarmap
