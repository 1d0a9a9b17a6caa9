#pragma once
/// @file missions.hpp
/// Named long missions in the built-in scenes (builtin_scenes.hpp), for studies of mapping and
/// SLAM under navigation drift (dead_reckoning.hpp): planar paths at depth 0 (the sonar's plane,
/// z = 0 in the map), sized for the head's range R like the scenes themselves, s = R / 5 m.
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
/// Every path keeps at least 1 s horizontal clearance from anything that crosses the sonar's plane.
///
/// `laps` repeats a mission: a loop is flown again from its start (it turns in place back to its
/// first heading); a lawnmower or a line is flown back along its path, then forwards again, and so
/// on. The vehicle moves at a constant speed along straight lines and stops at every corner to
/// turn in place at 0.5 rad/s (trajectory.hpp's lawnmowerWaypoints and loopWaypoints, whose
/// waypoints these are); yaw along the direction of travel, roll and pitch 0.

#include <cstddef>
#include <string>
#include <vector>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// The missions missionPlan() knows, in a fixed order: "harbour-loop", "harbour-lawnmower",
/// "harbour-featureless", "hull-loop".
std::vector<std::string> missionNames();

/// A mission's path for a given head and speed.
struct MissionPlan {
  std::string name;   ///< one of missionNames()
  std::string scene;  ///< the built-in scene it is drawn for ("harbour", "hull")
  /// Waypoints for waypointTrajectory (trajectory.hpp): NED, metres, times in seconds from 0.
  std::vector<NavSample> waypoints;
  double length_m = 0.0;    ///< distance travelled along the path, metres
  double duration_s = 0.0;  ///< time of the last waypoint, seconds (travel and turns in place)
};

/// The mission called `name` for a head of range scale `range_m` (metres; lengths scale with
/// s = range_m / 5 m), flown at `speed_mps` (metres per second), `laps` times (see the file's
/// comment).
/// @throws ValueError listing the names for an unknown mission, or naming the argument when
///         range_m or speed_mps is not a finite number > 0 or laps is 0.
MissionPlan missionPlan(const std::string& name, double range_m, double speed_mps, std::size_t laps = 1);

/// A mission speed suited to a head of range scale `range_m` (metres): min(R / 20 s, 0.5 m/s), so
/// that the vehicle moves a twentieth of the range a second (the Micron at 5 m: 0.25 m/s) up to
/// 0.5 m/s (≈ 1 knot; the 30–50 m heads). A turn of a 30–50 m head takes 24–30 s: at 0.5 m/s the
/// vehicle covers 12–15 m of it, under half the range, so consecutive turns still see the same
/// place; at a survey AUV's 1.5 m/s (36–45 m a turn) they barely do, and an MSIS SLAM has little
/// to match (docs/localization.md measures both).
/// @throws ValueError when range_m is not a finite number > 0.
double defaultMissionSpeed_mps(double range_m);

}  // namespace sonarmap
