#pragma once
// Navigation tracks (nav/navigation.hpp) as (N, 7) float64 arrays whose columns are the
// navigation CSV's: time_s, x_m, y_m, z_m (NED), roll_rad, pitch_rad, yaw_rad (body FRD, Z-Y-X).

#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::python {

/// The track as an (N, 7) float64 array (a copy).
py::array_t<double> navArray(const NavTrack& track);

/// A track from an (N, 7) float64 array or the path of a navigation CSV.
/// @throws sonarmap.ValueError for another shape or dtype, or non-finite values; sonarmap.FileError
///         for an unreadable CSV. Time order is checked by the library where the track is used.
NavTrack navTrackOf(const py::object& nav);

/// The track `nav` (as navTrackOf) on the clock of `log`: a path's navigation joined by
/// alignNavigationClock (formats/navigation_reader.hpp), an array's times moved by
/// `nav_time_offset_s`. When `sonar_to_body` is given and `nav` is a ROS log whose /tf_static
/// joins its body frame to `log`'s sonar frame, that mounting is written there
/// (formats/ros_bag_mounting.hpp).
/// @throws sonarmap.ValueError for a non-finite offset; as navTrackOf.
NavTrack navTrackForLog(const py::object& nav, const SonarLog& log, double nav_time_offset_s,
                        std::optional<Eigen::Isometry3d>* sonar_to_body = nullptr);

/// map_sonar_log (bind_mapping.cpp), also used by the online mapper's tests of equality; `slam`:
/// localize first (slam/slam_mapping.hpp) and keep the trajectory and report in the map.
OccupancyMap mapLog(const PySonarLog& log, const py::object& nav, const py::object& mounting,
                    const py::object& progress, bool slam, const py::kwargs& kwargs);

}  // namespace sonarmap::python
