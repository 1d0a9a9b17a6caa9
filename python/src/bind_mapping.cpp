// Mapping a whole log (mapping/sonar_mapper.hpp: mapSonarLog) with the command line's options
// (mapping/mapping_arguments.hpp, the translation `sonarmap map` uses), the counts of a mapping
// (MappingStats) and navigation tracks (nav/navigation.hpp) as (N, 7) arrays.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "sonarmap/slam/slam_mapping.hpp"
#include "navigation_arrays.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap::python {
namespace {

/// A number as the shortest text that reads back to the same double (what parseOptionNumber reads).
std::string exactText(double value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

bool isNumber(const py::handle& value) {
  return (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) && !py::isinstance<py::bool_>(value);
}

double number(const py::handle& value, const std::string& name) {
  if (!isNumber(value) && !py::hasattr(value, "__float__")) throwValueError(name + " expects a number");
  if (py::isinstance<py::bool_>(value)) throwValueError(name + " expects a number, got a bool");
  return value.cast<double>();
}

/// A number, or "auto"/None.
std::string numberOrAuto(const py::handle& value, const std::string& name) {
  if (value.is_none()) return "auto";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  return exactText(number(value, name));
}

std::string text(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::str>(value)) throwValueError(name + " expects a string");
  return value.cast<std::string>();
}

bool flag(const py::handle& value, const std::string& name) {
  if (!py::isinstance<py::bool_>(value)) throwValueError(name + " expects True or False");
  return value.cast<bool>();
}

}  // namespace

std::vector<std::string> mappingArgumentNames() {
  return {"resolution",       "detector",         "false_alarm",      "min_contrast",     "min_echo_length",
          "leading_edge",     "min_range",        "self_reflection",  "intensity_span",   "smoothing",
          "smoothing_range",  "smoothing_bearing", "cfar_training",   "cfar_guard",       "ray",
          "aggregation",      "max_range",        "beam_width",       "range_tolerance",  "max_voxel_updates",
          "hit_probability",  "volume",           "vertical_aperture", "free_aperture",   "clear_without_obstacle",
          "arc_evidence",     "threads",          "max_near_field",   "extended_returns", "obstacle_surface",
          "seabed_slope",     "face_slope",       "water_surface_depth"};
}

MappingArguments mappingArguments(const py::kwargs& kwargs, const std::vector<std::string>& allowed_extra) {
  MappingArguments args;
  for (const auto& [key, value] : kwargs) {
    const std::string name = key.cast<std::string>();
    if (name == "resolution") args.resolution = numberOrAuto(value, name);
    else if (name == "detector") args.detector = text(value, name);
    else if (name == "false_alarm") args.false_alarm = number(value, name);
    else if (name == "min_contrast") args.min_contrast_db = number(value, name);
    else if (name == "min_echo_length") args.min_echo_length_m = number(value, name);
    else if (name == "leading_edge") args.leading_edge_db = number(value, name);
    else if (name == "min_range") args.min_range = numberOrAuto(value, name);
    else if (name == "max_near_field") args.max_near_field_m = number(value, name);
    else if (name == "self_reflection") args.self_reflection = numberOrAuto(value, name);
    else if (name == "intensity_span") args.intensity_span = numberOrAuto(value, name);
    else if (name == "smoothing") args.smoothing = text(value, name);
    else if (name == "smoothing_range") args.smoothing_range_m = number(value, name);
    else if (name == "smoothing_bearing") args.smoothing_bearing_deg = number(value, name);
    else if (name == "cfar_training") args.cfar_training_m = number(value, name);
    else if (name == "cfar_guard") args.cfar_guard_m = number(value, name);
    else if (name == "ray") args.ray = text(value, name);
    else if (name == "aggregation") args.aggregation = text(value, name);
    else if (name == "max_range") args.max_range_m = value.is_none() ? INFINITY : number(value, name);
    else if (name == "beam_width") {
      if (!value.is_none()) {
        args.beam_width_deg = number(value, name);
        args.beam_width_given = true;
      }
    } else if (name == "range_tolerance") args.range_tolerance = numberOrAuto(value, name);
    else if (name == "max_voxel_updates") args.max_voxel_updates = number(value, name);
    else if (name == "hit_probability") args.hit_probability = number(value, name);
    else if (name == "volume" || name == "3d") args.volume = flag(value, name);
    else if (name == "vertical_aperture") {
      if (!value.is_none()) {
        args.vertical_aperture_deg = number(value, name);
        args.vertical_aperture_given = true;
      }
    } else if (name == "free_aperture") args.free_aperture = numberOrAuto(value, name);
    else if (name == "extended_returns") args.extended_returns = flag(value, name);
    else if (name == "seabed_slope") args.seabed_slope = flag(value, name);
    else if (name == "face_slope") args.face_slope = flag(value, name);
    else if (name == "water_surface_depth") args.water_surface_depth = value.is_none() ? "none" : exactText(number(value, name));
    else if (name == "clear_without_obstacle") {
      if (value.is_none()) args.clear_without_obstacle = "auto";
      else if (py::isinstance<py::bool_>(value)) args.clear_without_obstacle = value.cast<bool>() ? "yes" : "no";
      else args.clear_without_obstacle = text(value, name);
      if (args.clear_without_obstacle != "auto" && args.clear_without_obstacle != "yes" &&
          args.clear_without_obstacle != "no") {
        throwValueError("clear_without_obstacle expects True, False, None, 'yes', 'no' or 'auto'");
      }
    } else if (name == "arc_evidence") args.arc_evidence = text(value, name);
    else if (name == "obstacle_surface") args.obstacle_surface = text(value, name);
    else if (name == "threads") {
      const double threads = number(value, name);
      if (!(threads >= 1.0 && threads <= 64.0) || threads != std::floor(threads)) {
        throwValueError("threads expects an integer in [1, 64]");
      }
      args.threads = static_cast<unsigned>(threads);
    } else if (std::find(allowed_extra.begin(), allowed_extra.end(), name) == allowed_extra.end()) {
      std::string names;
      for (const std::string& known : mappingArgumentNames()) names += (names.empty() ? "" : ", ") + known;
      throw py::type_error("unexpected keyword argument '" + name + "'; the mapping options are: " + names);
    }
  }
  return args;
}

namespace {

/// Counts as a dict of plain Python numbers.
py::dict statsDict(const MappingStats& s) {
  py::dict d;
  d["sweeps"] = s.sweeps;
  d["beams_used"] = s.beams_used;
  d["beams_skipped"] = s.beams_skipped;
  d["obstacles"] = s.obstacles;
  d["free_updates"] = s.free_updates;
  d["occupied_updates"] = s.occupied_updates;
  d["out_of_map"] = s.out_of_map;
  d["beams_clipped"] = s.beams_clipped;
  d["beams_without_nav"] = s.beams_without_nav;
  d["beams_uncalibrated"] = s.beams_uncalibrated;
  d["beams_without_evidence"] = s.beams_without_evidence;
  d["extended_returns"] = s.extended_returns;
  d["farthest_m"] = s.farthest_m;
  return d;
}

void warn(const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (const std::string& line : lines) warn(line, py::handle(PyExc_RuntimeWarning), 2);
}

}  // namespace

OccupancyMap mapLog(const PySonarLog& log, const py::object& nav, const py::object& mounting,
                    const py::object& progress, bool slam, const py::kwargs& kwargs) {
  const MappingArguments args = mappingArguments(kwargs, {"format"});
  NominalBeam beam = log.beam;
  if (kwargs.contains("format") && !kwargs["format"].is_none()) {
    const std::string format = text(kwargs["format"], "format");
    if (format != "auto") beam = nominalBeam(parseLogFormat(format));
  }
  const MapperOptions options = withSonarBeam(toMapperOptions(args), args, beam);
  if (!mounting.is_none() && nav.is_none() && !slam) {
    throwValueError("mounting needs nav or slam (the sonar's mounting on a moving vehicle)");
  }
  std::vector<double> mounting_values;
  if (!mounting.is_none()) mounting_values = mounting.cast<std::vector<double>>();
  const Eigen::Isometry3d sonar_to_body = sonarToBodyOfMounting(mounting_values);
  std::optional<NavTrack> track;
  if (!nav.is_none()) track = navTrackOf(nav);
  warn(optionWarnings(options, log.log));
  ProgressCallback callback;
  if (!progress.is_none()) {
    callback = [&progress](std::size_t done, std::size_t total) {
      py::gil_scoped_acquire acquire;
      progress(done, total);
    };
  }
  std::optional<SonarMapper> mapper;
  std::optional<SlamResult> localized;
  {
    py::gil_scoped_release release;
    if (slam) {
      SlamMapping mapped = mapSonarLogWithSlam(log.log, track ? *track : NavTrack{}, sonar_to_body, options, SlamOptions{}, callback);
      mapper.emplace(std::move(mapped.mapper));
      localized = std::move(mapped.slam);
    } else {
      mapper.emplace(track ? mapSonarLog(log.log, *track, sonar_to_body, options, callback)
                           : mapSonarLog(log.log, options, callback));
    }
  }
  warn(mappingWarnings(mapper->stats(), mapper->options(), mapper->map().resolution_m()));
  OccupancyMap map{std::move(mapper->map()), mapper->stats(), std::nullopt, std::nullopt};
  if (localized) {
    map.trajectory = std::move(localized->trajectory);
    map.slam = std::move(localized->report);
  }
  return map;
}

void bindMapping(py::module_& m) {
  py::class_<MappingStats>(m, "MappingStats", "Counts gathered while mapping (C++ sonarmap::MappingStats).")
      .def_readonly("sweeps", &MappingStats::sweeps, "sweeps integrated")
      .def_readonly("beams_used", &MappingStats::beams_used, "beams integrated into the map")
      .def_readonly("beams_skipped", &MappingStats::beams_skipped, "malformed beams the reader dropped")
      .def_readonly("obstacles", &MappingStats::obstacles, "beams with an obstacle")
      .def_readonly("free_updates", &MappingStats::free_updates, "cells updated free (after per-sweep deduplication)")
      .def_readonly("occupied_updates", &MappingStats::occupied_updates, "cells updated occupied")
      .def_readonly("out_of_map", &MappingStats::out_of_map, "beams whose end lies outside the map (skipped)")
      .def_readonly("beams_clipped", &MappingStats::beams_clipped, "beams longer than max_range (obstacle dropped)")
      .def_readonly("beams_without_nav", &MappingStats::beams_without_nav, "beams outside the navigation's time span")
      .def_readonly("beams_uncalibrated", &MappingStats::beams_uncalibrated,
                    "beams of a range scale or gain used for too few beams in a row to calibrate on (skipped)")
      .def_readonly("beams_without_evidence", &MappingStats::beams_without_evidence,
                    "beams without an obstacle that clear nothing (the volume model's default)")
      .def_readonly("extended_returns", &MappingStats::extended_returns,
                    "beams without an obstacle whose whole echo held a weak extended return (volume model)")
      .def_readonly("farthest_m", &MappingStats::farthest_m, "largest |x|, |y| or |z| a beam reached, metres, map frame")
      .def("as_dict", &statsDict, "The counts as a dict of ints and floats.")
      .def("__repr__", [](const MappingStats& s) { return "MappingStats(" + py::repr(statsDict(s)).cast<std::string>() + ")"; });

  m.def("map_sonar_log", &mapLog, py::arg("log"), py::arg("nav") = py::none(), py::arg("mounting") = py::none(),
        py::arg("progress") = py::none(), py::arg("slam") = false,
        R"doc(Maps every sweep of ``log`` into an occupancy octree, exactly as ``sonarmap map`` does (the same
library call, the same option translation): each beam's first obstacle is detected per sweep and
its wedge (planar model) or cone (volume=True) updated free up to it, the obstacle occupied.

log: sonarmap.SonarLog. nav: None (the sonar static at the map origin), the path of a navigation
CSV, or an (N, 7) float64 array of fixes [time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad]
(NED metres, body FRD Z-Y-X radians, on the beams' clock; the CLI's --nav). mounting: with nav,
(x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg) of the sonar in the body (the CLI's --mounting;
default upright and aligned). progress: callable(sweeps_done, sweeps_total) or None. slam: correct
the navigation by scan matching first and map with the corrected trajectory (the CLI's --slam; without
nav the vehicle is believed still and its motion comes from the scans); the map's ``trajectory`` and
``slam`` then hold the corrected trajectory and what the localization did.
Keyword options (the CLI's flags with '-' as '_', in the CLI's units; None or "auto" where the CLI
takes auto): resolution (m), detector, false_alarm, min_contrast (dB), min_echo_length (m),
leading_edge (dB), min_range (m), max_near_field (m), self_reflection (m), intensity_span (dB), smoothing,
smoothing_range (m), smoothing_bearing (deg), cfar_training (m), cfar_guard (m), ray, aggregation,
max_range (m), format (whose nominal beam to assume; default the log's), beam_width (deg; default the
sonar's), range_tolerance (m), max_voxel_updates, hit_probability, volume (bool, the CLI's --3d),
vertical_aperture (deg), free_aperture (deg), clear_without_obstacle (bool/None), arc_evidence, obstacle_surface,
extended_returns (bool), seabed_slope (bool), face_slope (bool), water_surface_depth (m in the
navigation's NED frame, default 0: a depth sensor's; None: unknown), threads.
Map frame: NWU metres (x north, y west, z up); without nav the sonar frame itself.
Returns sonarmap.OccupancyMap with ``stats`` (sonarmap.MappingStats). What `sonarmap map` prints as
warnings is issued as RuntimeWarning. The GIL is released while mapping.
Raises sonarmap.ValueError for an invalid option (named as the CLI's flag), a log whose work
exceeds max_voxel_updates, or a bad navigation track; sonarmap.FileError for an unreadable nav CSV;
TypeError for an unknown keyword.)doc");

  m.def(
      "read_nav_csv", [](const std::filesystem::path& path) { return navArray(readNavCsv(path.string())); }, py::arg("path"),
      R"doc(Reads a navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad) as an (N, 7) float64 array:
seconds, NED metres, radians (body FRD, Z-Y-X). Raises sonarmap.FileError naming the line and field.)doc");
  m.def(
      "write_nav_csv",
      [](const std::filesystem::path& path, const py::object& nav) { writeNavCsv(path.string(), navTrackOf(py::reinterpret_borrow<py::object>(nav))); },
      py::arg("path"), py::arg("nav"),
      "Writes an (N, 7) navigation array as a navigation CSV, atomically. Raises sonarmap.ValueError, sonarmap.FileError.");
}

}  // namespace sonarmap::python
