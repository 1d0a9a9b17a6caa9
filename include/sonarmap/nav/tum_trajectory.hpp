#pragma once
/// @file tum_trajectory.hpp
/// Trajectories in the TUM RGB-D benchmark's text format (Sturm et al. 2012, "A benchmark for the
/// evaluation of RGB-D SLAM systems", IROS; the format of its evaluate_ate.py / evaluate_rpe.py and
/// of the `evo` tools), so that a sonarmap navigation track or a SLAM estimate can be compared with
/// those tools, and their files with sonarmap's (eval/trajectory_error.hpp).
///
/// One pose per line: `time x y z qx qy qz qw`, separated by spaces or tabs; lines starting with
/// '#' are comments; blank lines are skipped. Here the pose is the vehicle body's in NED
/// (navigation.hpp): x, y, z = NavSample::position_ned_m (metres north, east, down) and the unit
/// quaternion of bodyToNed(fix)'s rotation, Rz(yaw)·Ry(pitch)·Rx(roll).

#include <iosfwd>
#include <string>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// Writes `track` as TUM lines (after one '#' comment line naming the columns and the frames),
/// numbers in their shortest exact decimal form; the quaternion with qw ≥ 0.
/// @throws ValueError (before writing anything) when the track is empty, holds a non-finite value
///         or its times are not strictly increasing.
void writeTumTrajectory(std::ostream& out, const NavTrack& track);

/// The same, written atomically to `path` (temporary file + rename, as writeNavCsv).
/// @throws ValueError as above; FileError when the file cannot be written.
void writeTumTrajectory(const std::string& path, const NavTrack& track);

/// Reads a TUM trajectory: each pose's position as position_ned_m and its quaternion (normalised)
/// as roll, pitch, yaw (Z-Y-X Euler angles of navigation.hpp; yaw in (−π, π], pitch in [−π/2, π/2]).
/// @throws FileError naming the file and the 1-based line: the file cannot be opened, a line does
///         not hold exactly 8 numbers, a value is not finite, a quaternion has norm 0, a time is
///         not after the previous pose's, or the file holds no pose.
NavTrack readTumTrajectory(const std::string& path);

/// Reads a navigation CSV (readNavCsv) or a TUM trajectory (readTumTrajectory), told apart by the
/// first line that is neither blank nor a '#' comment: one that starts with `time_s` (the CSV's
/// header) is a navigation CSV, anything else TUM.
/// @throws FileError as the reader of the detected format, or when the file cannot be opened.
NavTrack readTrajectory(const std::string& path);

}  // namespace sonarmap
