#pragma once
/// @file local_origin.hpp
/// A local origin for navigation given in absolute coordinates (UTM, a national grid: millions of
/// metres north and east). The map's octree (depth 16) holds 2^15 voxels either side of its origin,
/// ±1,638 m at 5 cm: a navigation that far from zero is mapped about a local origin instead, the
/// navigation's positions moved by it before mapping and moved back in what is written for the user
/// (trajectories). The origin is a point of the navigation's own frame (NED: metres north, east,
/// down), so the map's zero is that point.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// How far from its origin the map can hold a point along each axis at `resolution_m` (> 0):
/// 32,767 voxels of a depth-16 octree, metres.
double mapHalfExtent_m(double resolution_m);

/// The origin a navigation is mapped about.
struct LocalOrigin {
  Eigen::Vector3d ned_m = Eigen::Vector3d::Zero();  ///< metres north, east, down in the navigation's frame
  bool given = false;      ///< set by the user (chooseLocalOrigin's `given`)
  bool automatic = false;  ///< chosen as the first fix because the navigation is far from zero
  /// Whether the map's zero is the navigation's own (no origin moved anything).
  bool isZero() const { return ned_m.isZero(0.0); }
  /// "4600000, 500000, 0 m (N, E, D; the first fix, the navigation being far from zero)" and the like.
  std::string describe() const;
};

/// The origin `track` (NED) is mapped about: `given` when set; else, when some fix lies farther
/// from zero than the map holds (mapHalfExtent_m(resolution_m) less `reach_m`, the beams' reach)
/// along north or east, the first fix's north and east (and its depth when some depth is that far
/// too); else zero. An empty track: `given`, else zero.
/// @throws ValueError when `given` holds a non-finite value or resolution_m ≤ 0 or reach_m < 0.
LocalOrigin chooseLocalOrigin(const NavTrack& track, const std::optional<Eigen::Vector3d>& given, double resolution_m,
                              double reach_m);

/// Moves every fix's position by −origin_ned_m (into the map's local frame).
void moveToOrigin(NavTrack& track, const Eigen::Vector3d& origin_ned_m);

/// Moves every fix's position by +origin_ned_m (back into the navigation's own coordinates).
void moveFromOrigin(NavTrack& track, const Eigen::Vector3d& origin_ned_m);

/// Checks that a beam from every fix of `local_track` (positions already moved to `origin`) stays
/// within the map at `resolution_m`: |position| + reach_m ≤ mapHalfExtent_m along each axis.
/// @throws ValueError naming the first fix that does not (its time and position in the
///         navigation's own coordinates, its distance from the origin), the map's extent at that
///         resolution, and the fix: `origin_knob` (how the caller's user sets the origin, e.g.
///         "--origin") at the track's middle when the track's span fits the map, else the finest
///         resolution (`resolution_knob`) that holds it.
void requireTrackFits(const NavTrack& local_track, const LocalOrigin& origin, double resolution_m, double reach_m,
                      const std::string& origin_knob, const std::string& resolution_knob);

}  // namespace sonarmap
