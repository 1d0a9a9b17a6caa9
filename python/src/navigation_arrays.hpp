#pragma once
// Navigation tracks (nav/navigation.hpp) as (N, 7) float64 arrays whose columns are the
// navigation CSV's: time_s, x_m, y_m, z_m (NED), roll_rad, pitch_rad, yaw_rad (body FRD, Z-Y-X).

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

/// map_sonar_log (bind_mapping.cpp), also used by the online mapper's tests of equality; `slam`:
/// localize first (slam/slam_mapping.hpp) and keep the trajectory and report in the map.
OccupancyMap mapLog(const PySonarLog& log, const py::object& nav, const py::object& mounting,
                    const py::object& progress, bool slam, const py::kwargs& kwargs);

}  // namespace sonarmap::python
