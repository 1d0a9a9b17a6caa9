#pragma once
/// @file missions.hpp
/// Named missions in the built-in scenes (builtin_scenes.hpp), sized for the head's range R like
/// the scenes themselves, s = R / 5 m: planar paths at depth 0 (the sonar's plane, z = 0 in the
/// map) for studies of mapping and SLAM under navigation drift (dead_reckoning.hpp), and 3D
/// missions over `quay3d` for 3D mapping (the accuracy missions of docs/accuracy.md,
/// eval/simulated_mission.hpp). Each has a default mounting of the sonar on the vehicle (as
/// `--mounting` takes it, mounting.hpp): upright and aligned but for the tilted loop.
///
/// Coordinates below are NED north and east in units of s. The scenes are drawn in the map frame
/// (NWU, navigation.hpp), so a scene's map y is −east: the harbour's piles at map y −4…4 s stand at
/// east 4…−4 s.
///  - `harbour-loop` (scene `harbour`): the rectangle with corners (0, −8), (0, 8), (−1, 8),
///    (−1, −8), flown in that order, clockwise seen from above: it starts at (0, −8) heading east
///    along the quay (face at north 3.5, piles at north 2, east −4…4) and comes back to its start
///    heading north; 34 s a lap (Micron 34 m, SeaKing-30 204 m). Both long legs keep the quay
///    within 4.5 s, inside the reach (5 s); a leg at north −2 would see it at 5.5 s, beyond. Loop
///    closures: the way back passes the same piles, and every lap again.
///  - `harbour-lawnmower` (scene `harbour`): three legs along east from −8 to 8 at north 0, −0.5,
///    −1 (the first eastwards, spaced 0.5 s to the south), joined by 0.5 s crossings; 49 s.
///  - `harbour-featureless` (scene `harbour`): a straight line along east at north 0 from east 0
///    to east 40; the quay ends at east 20, so its second half sees nothing but the seabed (where
///    a SLAM can only dead reckon); 40 s.
///  - `hull-loop` (scene `hull`): the rectangle north ∈ [−4.5, 4.5], east ∈ [−6.5, 0] around the
///    moored hull (north −2…2, east −4.5…−2; mooring piles at north ±3.25, east −2.25), flown
///    counter-clockwise seen from above: from (−4.5, 0) north along east 0, the hull to port;
///    31 s a lap.
/// Every planar path keeps at least 1 s horizontal clearance from anything that crosses the sonar's
/// plane.
///  - `tilted-loop` (scene `quay3d`): a 4 s × 3 s rectangle centred on the origin at 3 s depth,
///    its first side northwards, clockwise seen from above, with the sonar tilted 25° down (pitch
///    −25: its scan is a cone opening downwards, how AUVs map the seabed with an MSIS).
///  - `lawnmower-3d` (scene `quay3d`): three 4 s legs northwards and back, 1.5 s apart, centred on
///    the origin, at 3 s depth and then flown back at 3.5 s (the wide beam sees each surface from
///    two heights); the sonar upright.
/// Their depths lie below quay3d's water surface (depth 0) and 1.5–2.5 s above its seabed; the
/// pontoon (map x ∈ [−1.25, 1.25] s, y ∈ [2.4, 3.6] s) stays clear of both. A lap of the tilted
/// loop is a loop at the same depth; a lap of the lawnmower both depths.
///
/// `laps` repeats a mission: a loop is flown again from its start (it turns in place back to its
/// first heading); a lawnmower or a line is flown back along its path, then forwards again, and so
/// on. The vehicle moves at a constant speed along straight lines and stops at every corner to
/// turn in place at 0.5 rad/s (trajectory.hpp's lawnmowerWaypoints and loopWaypoints, whose
/// waypoints these are), and between depths vertically; yaw along the direction of travel, roll
/// and pitch 0.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// The missions missionPlan() knows, in a fixed order: "harbour-loop", "harbour-lawnmower",
/// "harbour-featureless", "hull-loop", "lawnmower-3d", "tilted-loop".
std::vector<std::string> missionNames();

/// A mission's path for a given head and speed.
struct MissionPlan {
  std::string name;   ///< one of missionNames()
  std::string scene;  ///< the built-in scene it is drawn for ("harbour", "hull", "quay3d")
  /// Waypoints for waypointTrajectory (trajectory.hpp): NED, metres, times in seconds from 0.
  std::vector<NavSample> waypoints;
  double length_m = 0.0;    ///< distance travelled along the path, metres
  double duration_s = 0.0;  ///< time of the last waypoint, seconds (travel and turns in place)
  /// The sonar's default mounting on the vehicle, as `--mounting` takes it (mounting.hpp): X, Y, Z
  /// metres, ROLL, PITCH, YAW degrees; all 0 (upright and aligned) but for the tilted loop's pitch −25.
  std::array<double, 6> mounting{};
};

/// The mission called `name` for a head of range scale `range_m` (metres; lengths scale with
/// s = range_m / 5 m), flown at `speed_mps` (metres per second), `laps` times (see the file's
/// comment).
/// @throws ValueError listing the names for an unknown mission, or naming the argument when
///         range_m or speed_mps is not a finite number > 0 or laps is 0.
MissionPlan missionPlan(const std::string& name, double range_m, double speed_mps, std::size_t laps = 1);

/// The default speed of mission `name` for a head of range scale `range_m` (metres). The planar
/// missions: min(R / 20 s, 0.5 m/s), so that the vehicle moves a twentieth of the range a second
/// (the Micron at 5 m: 0.25 m/s) up to 0.5 m/s (≈ 1 knot; the 30–50 m heads). A turn of a 30–50 m
/// head takes 24–30 s: at 0.5 m/s the vehicle covers 12–15 m of it, under half the range, so
/// consecutive turns still see the same place; at a survey AUV's 1.5 m/s (36–45 m a turn) they
/// barely do, and an MSIS SLAM has little to match (docs/localization.md measures both). The 3D
/// missions: 0.2 · s m/s (the Micron: 0.2 m/s; the tilted loop then lasts 83 s, ten of its turns).
/// @throws ValueError listing the names for an unknown mission, or when range_m is not a finite
///         number > 0.
double defaultMissionSpeed_mps(const std::string& name, double range_m);

}  // namespace sonarmap
