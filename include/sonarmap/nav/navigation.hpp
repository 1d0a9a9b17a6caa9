#pragma once
/// @file navigation.hpp
/// Vehicle navigation for a moving sonar: fixes in the local NED frame (the marine convention),
/// pose interpolation at beam times, and the sonar's mounting on the vehicle.
///
/// Frames (the one statement of the project's convention; docs/formats.md, "Frames", explains it with examples):
///  - NED: local tangent frame, x north, y east, z down, metres; the navigation's frame.
///  - body: the vehicle's frame, x forward, y starboard, z down (FRD); roll, pitch, yaw are the
///    usual Z-Y-X (yaw, then pitch, then roll) Euler angles of body in NED, radians: pitch
///    positive raises the bow (nose up), negative lowers it; roll positive lowers the starboard side.
///  - sonar: the head's frame, the same axes and handedness as the body frame: x along the head's
///    zero bearing ("ahead", each reader maps its head's ahead there), y to starboard, z down (FRD)
///    for a head mounted upright. A beam's bearing (beam.hpp) is measured from +x towards +y:
///    clockwise seen from above, so bearing b points along (cos b, sin b, 0) in the sonar frame
///    and bearing π/2 is to starboard. A sonar mounted upright and aligned has the identity
///    mounting (defaultSonarToBody(), `--mounting 0,0,0,0,0,0`); a mounting's roll, pitch, yaw
///    have the body's meaning, so a head tilted 25° down is pitch −25°.
///  - map: the frame the octree is written in, z up so that octovis shows it upright: NWU,
///    x north, y west, z up (NED with y and z negated). A log without navigation is mapped as
///    from a vehicle at the NED origin with zero attitude and the default mounting
///    (staticSonarToMap()), so a static log maps the same with or without a navigation at rest.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap {

/// One navigation fix.
struct NavSample {
  double time_s = 0.0;                                    ///< same clock as the beams' time_s
  Eigen::Vector3d position_ned_m = Eigen::Vector3d::Zero();  ///< vehicle origin in NED, metres
  double roll_rad = 0.0;   ///< about body x; positive lowers the starboard side
  double pitch_rad = 0.0;  ///< about body y; positive raises the bow
  double yaw_rad = 0.0;    ///< heading, clockwise from north seen from above
};

/// Navigation fixes sorted by strictly increasing time.
using NavTrack = std::vector<NavSample>;

/// Whether every value of `sample` (time, position, attitude) is finite.
bool isFinite(const NavSample& sample);

/// The first place where a track breaks NavTrack's rules: fix `index` holds a value that is not
/// finite (kNotFinite), or its time is not after fix index − 1's (kNotAfter).
struct NavTrackFault {
  enum class Kind { kNotFinite, kNotAfter };
  Kind kind = Kind::kNotFinite;
  std::size_t index = 0;
};

/// The first fault of `track`, fix by fix in order (a fix's values before its time); nullopt when
/// it has none (an empty track has none). Each caller words its own error.
std::optional<NavTrackFault> findNavTrackFault(const NavTrack& track);

/// Pose of the body frame in NED (maps body coordinates to NED) for one fix: rotation
/// Rz(yaw)·Ry(pitch)·Rx(roll) (Z-Y-X Euler angles, Eigen::AngleAxis about NED's axes), translation
/// `position_ned_m`. Yaw π/2 turns body +x (forward) to NED +y (east). No check on the values.
Eigen::Isometry3d bodyToNed(const NavSample& sample);

/// NED → map (NWU): (n, e, d) ↦ (n, −e, −d), the rotation diag(1, −1, −1) with no translation.
Eigen::Isometry3d nedToMap();

/// The sonar's mounting on the vehicle: sonar frame (FRD, see the frames above) → body frame (FRD).
/// Default: upright and aligned, at the body origin: the identity.
Eigen::Isometry3d defaultSonarToBody();

/// Pose of the sonar in the map for a log without navigation: a vehicle at the NED origin with
/// zero attitude, the sonar mounted with defaultSonarToBody(): sonarToMap(NavSample{},
/// defaultSonarToBody()), which is nedToMap(). Bearing 0 then points north (map +x) and bearing
/// π/2 east (map −y).
Eigen::Isometry3d staticSonarToMap();

/// Pose of the sonar frame in the map frame for one navigation fix:
/// nedToMap() · bodyToNed(fix) · sonar_to_body.
Eigen::Isometry3d sonarToMap(const NavSample& fix, const Eigen::Isometry3d& sonar_to_body);

/// Pose of the vehicle body in NED at `time_s`: position interpolated linearly, attitude by
/// quaternion slerp (Eigen, shortest arc: a yaw from 179° to −179° passes through 180°, not 0°)
/// between the two fixes around it. At a fix's own time the result is that fix's bodyToNed.
/// nullopt when `time_s` lies outside [first fix, last fix] or is NaN (the beam is then skipped
/// and counted by the caller).
/// Cost: O(fixes) to check the track, plus O(log fixes) for the search.
/// @throws ValueError when the track is empty, holds a non-finite value, or its times are not
///         strictly increasing.
std::optional<Eigen::Isometry3d> interpolateBodyToNed(const NavTrack& track, double time_s);

/// interpolateBodyToNed for many times on one track: the track is checked once, at construction,
/// and each bodyToNedAt costs O(log fixes). Keeps a reference: `track` must outlive it.
class NavInterpolator {
 public:
  /// @throws ValueError as interpolateBodyToNed for an invalid track.
  explicit NavInterpolator(const NavTrack& track);
  /// Tag: the track was already checked, fix by fix as it grew (OnlineMapper::addNavFix checks
  /// each fix's values and order), so the O(fixes) check is skipped: a live mapper interpolates
  /// once per beam on a track that keeps growing. Not empty; a track that breaks the rules gives
  /// undefined poses.
  struct Prechecked {};
  NavInterpolator(const NavTrack& track, Prechecked) : track_(track) {}
  /// As interpolateBodyToNed(track, time_s).
  std::optional<Eigen::Isometry3d> bodyToNedAt(double time_s) const;

 private:
  const NavTrack& track_;
};

/// Reads a navigation CSV (docs/formats.md, "Navigation CSV"): header row exactly
/// `time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad`, then one fix per row: time in seconds (the
/// beams' clock), x, y, z of the vehicle origin in NED (metres north, east, down), roll, pitch, yaw
/// in radians (Z-Y-X, as NavSample). Numbers as std::from_chars reads them (no leading '+').
/// Spaces and tabs around fields, CRLF line ends, blank lines and a UTF-8 byte-order mark are
/// accepted.
/// The file may be gzip-compressed (`nav.csv.gz`: io/text_input.hpp).
/// @return the fixes in file order (strictly increasing times).
/// @throws FileError naming the file, the 1-based line and the field for anything malformed: the
///         file cannot be opened, is empty, or its gzip data is truncated or corrupt; the header differs; a row has missing or extra
///         fields, a value that is not a number or not finite, or a time not after the previous
///         row's; the file has a header row only ("no fixes").
NavTrack readNavCsv(const std::string& path);

/// Navigation CSV rows arriving as a stream (a vehicle's navigation sent over UDP, TCP or a serial
/// line to `sonarmap live`): bytes in, whole fixes out. Rows as readNavCsv reads them (the header
/// row is optional and skipped); a row cut by the end of a chunk waits for the rest. A malformed
/// row, or one whose time is not after the previous fix's, is skipped and counted, not thrown: a
/// live run goes on.
class NavCsvStream {
 public:
  /// @param source  name used in skip reasons (e.g. "udp://0.0.0.0:5000").
  explicit NavCsvStream(std::string source);
  /// The fixes whose rows `bytes` completed, in order, times strictly increasing.
  std::vector<NavSample> feed(std::span<const std::uint8_t> bytes);
  std::size_t skippedRows() const { return skipped_; }
  /// Why the last row was skipped (empty when none was).
  const std::string& lastSkipReason() const { return last_reason_; }

 private:
  std::string source_;
  std::string partial_;  ///< bytes of a row not yet ended by its newline
  std::optional<double> last_time_s_;
  std::size_t rows_ = 0;
  std::size_t skipped_ = 0;
  std::string last_reason_;
};

/// Writes a navigation CSV readable by readNavCsv, numbers in their shortest exact decimal form
/// (reading back gives the identical doubles). Written atomically: temporary file + rename, so
/// an existing file is untouched on failure.
/// @throws ValueError (before writing anything) when the track is empty, holds a non-finite
///         value, or its times are not strictly increasing: readNavCsv would reject the file.
/// @throws FileError when the file cannot be written.
void writeNavCsv(const std::string& path, const NavTrack& track);

/// The same CSV written to a stream (e.g. to stage it with other outputs, io/atomic_file.hpp).
/// @throws ValueError as writeNavCsv(path, track), before writing anything.
void writeNavCsv(std::ostream& out, const NavTrack& track);

}  // namespace sonarmap
