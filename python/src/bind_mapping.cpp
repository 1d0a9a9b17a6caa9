// Mapping a whole log (mapping/sonar_mapper.hpp: mapSonarLog) with the command line's options
// (the library's option table, read as keywords by bind_options.cpp: the translation `sonarmap
// map` uses), the counts of a mapping (MappingStats) and navigation tracks (nav/navigation.hpp) as
// (N, 7) arrays.
#include <cmath>
#include <optional>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "sonarmap/slam/point_scans.hpp"
#include "sonarmap/slam/slam_mapping.hpp"
#include "navigation_arrays.hpp"
#include "sonarmap/formats/navigation_reader.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"

namespace sonarmap::python {
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

/// The navigation's noise model for localization: the class (`auto`: navigationClassOf the track)
/// and the vehicle's limits where no position is measured (max_speed in m/s, max_turn_rate in °/s,
/// the CLI's --max-speed and --max-turn-rate; None: the class's).
OdometryNoise odometryOf(const std::string& nav_class, const py::object& max_speed, const py::object& max_turn_rate,
                         const NavTrack& track) {
  OdometryNoise noise = odometryNoiseOf(nav_class == "auto" ? navigationClassOf(track) : nav_class);
  const auto limit = [](const py::object& given, double unit, double& field, const char* name) {
    if (given.is_none()) return;
    const double value = given.cast<double>();
    if (!(std::isfinite(value) && value > 0.0)) throw ValueError(std::string(name) + " must be > 0");
    field = value * unit;
  };
  limit(max_speed, 1.0, noise.max_speed_mps, "max_speed (m/s)");
  limit(max_turn_rate, 3.14159265358979323846 / 180.0, noise.max_turn_rate_radps, "max_turn_rate (degrees/s)");
  return noise;
}

py::object kwarg(const py::kwargs& kwargs, const char* name) {
  return kwargs.contains(name) ? py::object(kwargs[name]) : py::object(py::none());
}

void warn(const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (const std::string& line : lines) warn(inPythonWords(line), py::handle(PyExc_RuntimeWarning), 2);
}

/// The origin `track` is mapped about (chooseLocalOrigin with the keyword origin's (north_m,
/// east_m[, down_m]), at the map's resolution and the log's reach), `track` moved to it and checked.
LocalOrigin moveToLocalOrigin(std::optional<NavTrack>& track, const py::object& given, const SonarLog& log,
                              const MapperOptions& options) {
  std::optional<Eigen::Vector3d> point;
  if (!given.is_none()) {
    const std::vector<double> values = given.cast<std::vector<double>>();
    if (values.size() != 2 && values.size() != 3) throwValueError("origin: expected (north_m, east_m) or (north_m, east_m, down_m)");
    point = Eigen::Vector3d(values[0], values[1], values.size() == 3 ? values[2] : 0.0);
  }
  if (!track) {
    if (point) throwValueError("origin needs nav: without it the map's zero is the sonar's");
    return {};
  }
  const double resolution_m = options.resolution_m.value_or(autoResolutionForLog(log, options).resolution_m);
  const double reach_m = logReach_m(log, options.max_range_m);
  const LocalOrigin origin = chooseLocalOrigin(*track, point, resolution_m, reach_m);
  moveToOrigin(*track, origin.ned_m);
  requireTrackFits(*track, origin, resolution_m, reach_m, "origin=(north_m, east_m[, down_m])", "resolution=");
  return origin;
}

}  // namespace

OccupancyMap mapLog(const PySonarLog& log, const py::object& nav, const py::object& mounting,
                    const py::object& progress, bool slam, const py::kwargs& kwargs) {
  const MappingArguments args =
      mappingArguments(kwargs, {"format", "nav_time_offset_s", "nav_class", "max_speed", "max_turn_rate", "origin", "map_frame"});
  const MapFrame frame = kwargs.contains("map_frame") ? parseMapFrame(textArgument(kwargs["map_frame"], "map_frame"))
                                                      : kDefaultMapFrame;
  const std::string nav_class = kwargs.contains("nav_class") ? textArgument(kwargs["nav_class"], "nav_class") : "auto";
  const double nav_time_offset_s =
      kwargs.contains("nav_time_offset_s") ? kwargs["nav_time_offset_s"].cast<double>() : 0.0;
  const NominalBeam beam = namedSonarBeam(kwarg(kwargs, "format")).value_or(log.beam);
  const MapperOptions options = withSonarBeam(toMapperOptions(args), args, beam);
  if (!mounting.is_none() && nav.is_none() && !slam) {
    throwValueError("mounting needs nav or slam (the sonar's mounting on a moving vehicle)");
  }
  std::vector<double> mounting_values;
  if (!mounting.is_none()) mounting_values = mounting.cast<std::vector<double>>();
  std::optional<Eigen::Isometry3d> from_log;  // a ROS log's /tf_static, when mounting is not given
  std::optional<NavTrack> track;
  if (!nav.is_none()) track = navTrackForLog(nav, log.log, nav_time_offset_s, mounting.is_none() ? &from_log : nullptr);
  const LocalOrigin origin = moveToLocalOrigin(track, kwarg(kwargs, "origin"), log.log, options);
  SlamOptions slam_options;
  slam_options.forming.odometry =
      odometryOf(nav_class, kwarg(kwargs, "max_speed"), kwarg(kwargs, "max_turn_rate"), track ? *track : NavTrack{});
  const Eigen::Isometry3d sonar_to_body = from_log ? *from_log : sonarToBodyOfMounting(mounting_values);
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
      SlamMapping mapped = mapSonarLogWithSlam(log.log, track ? *track : NavTrack{}, sonar_to_body, options, slam_options, callback);
      mapper.emplace(std::move(mapped.mapper));
      localized = std::move(mapped.slam);
    } else {
      mapper.emplace(track ? mapSonarLog(log.log, *track, sonar_to_body, options, callback)
                           : mapSonarLog(log.log, options, callback));
    }
  }
  warn(mappingWarnings(mapper->stats(), mapper->options(), mapper->map().resolution_m()));
  OccupancyMap map{mapInFrame(mapper->map(), frame), mapper->stats(), std::nullopt, std::nullopt, std::nullopt, frame};
  if (!origin.isZero()) map.origin = origin.ned_m;
  if (localized) {
    moveFromOrigin(localized->trajectory, origin.ned_m);
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

  const std::string map_doc = R"doc(Maps every sweep of ``log`` into an occupancy octree, exactly as ``sonarmap map`` does (the same
library call, the same option translation): each beam's first obstacle is detected per sweep and
its wedge (planar model) or cone (volume=True) updated free up to it, the obstacle occupied.

log: sonarmap.SonarLog. nav: None (the sonar static at the map origin), the path of a navigation
file (a CSV, a ROS log's navigation topic, a BlueROV2 .tlog or dataflash .BIN: read_navigation; its
clock joined to the log's as the CLI does, moved by the keyword nav_time_offset_s), or an (N, 7)
float64 array of fixes [time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad] (NED metres, body FRD
Z-Y-X radians, on the beams' clock; the CLI's --nav). mounting: with nav, (x_m, y_m, z_m, roll_deg,
pitch_deg, yaw_deg) of the sonar in the body (the CLI's --mounting); default: a ROS log nav's
/tf_static mounting of the log's sonar frame when it has one, else upright and aligned (all zeros;
pitch_deg -25 is a head tilted 25 degrees down). progress: callable(sweeps_done, sweeps_total) or None. slam: correct
the navigation by scan matching first and map with the corrected trajectory (the CLI's --slam; without
nav the vehicle is believed still and its motion comes from the scans); the map's ``trajectory`` and
``slam`` then hold the corrected trajectory and what the localization did; keyword nav_class (the CLI's
--nav-class: "dvl-ahrs", "dvl-ins", "absolute", "ahrs" (the heading only: the position comes from the
scans) or "auto", the default: "ahrs" when nav's north and east never change, else "dvl-ahrs") says how
far it trusts the navigation; keywords max_speed (m/s, default 2) and max_turn_rate (degrees/s, default
30, without nav only; the CLI's --max-speed and --max-turn-rate) are the vehicle's limits where nav gives
no position (no nav, or the heading only): no scan match needing more is accepted. Keyword origin:
(north_m, east_m[, down_m]), the map's zero in nav's frame (the CLI's --origin): nav far from zero (UTM)
is mapped relative to it, and the map's ``origin`` and ``trajectory`` say so; default: nav's first fix
when some fix lies farther from zero than the map holds (32,767 voxels less the log's reach), else zero.
Keyword options: the CLI's flags with '-' as '_', in the CLI's units, an angle's keyword ending in
_deg (beam_width_deg: the navigation's angles above are radians), None or "auto" where the CLI
takes auto (sonarmap.mapping_options() gives each one's unit, range, default and help): )doc" +
                              mappingKeywordsDoc(false) + R"doc(; and format (whose nominal beam to
assume; default the log's).
Keyword map_frame: the frame of the returned map, "enu" (default: x east, y north, z up, ROS REP
103/105) or "ned" (x north, y east, z down); the map's ``frame`` says it and ``write`` names it in
the file's header. Without nav the vehicle is taken at the NED origin heading north.
Returns sonarmap.OccupancyMap with ``stats`` (sonarmap.MappingStats). What `sonarmap map` prints as
warnings is issued as RuntimeWarning. The GIL is released while mapping.
Raises sonarmap.ValueError for an invalid option (named by its keyword), a log whose work
exceeds max_voxel_updates_per_beam, a bad navigation track, or one the map cannot hold about any origin (naming
the fix and what fits); sonarmap.FileError for an unreadable nav CSV;
TypeError for an unknown keyword.)doc";
  m.def("map_sonar_log", &mapLog, py::arg("log"), py::arg("nav") = py::none(), py::arg("mounting") = py::none(),
        py::arg("progress") = py::none(), py::arg("slam") = false, map_doc.c_str());

  m.def(
      "localize_point_scans",
      [](const py::object& scans, const py::object& nav, double range_sigma, double bearing_sigma,
         const std::string& nav_class, const py::object& max_speed, const py::object& max_turn_rate) {
        std::vector<BodyPoint> points;
        if (py::isinstance<py::str>(scans) || py::hasattr(scans, "__fspath__")) {
          points = readPointScansCsv(py::str(py::module_::import("os").attr("fspath")(scans)));
        } else {
          const auto array = py::array_t<double, py::array::forcecast>::ensure(scans);
          if (!array || array.ndim() != 2 || array.shape(1) != 4 || !py::isinstance<py::array_t<double>>(scans)) {
            throw ValueError("scans: expected a float64 array of shape (N, 4) [scan, time_s, x_m, y_m] or a path");
          }
          const auto view = array.unchecked<2>();
          for (py::ssize_t i = 0; i < view.shape(0); ++i) {
            const double scan = view(i, 0);
            if (!(scan >= 0.0 && scan <= 9007199254740992.0 && std::floor(scan) == scan)) {
              throw ValueError("scans: row " + std::to_string(i) + "'s scan is not an integer in [0, 2^53]");
            }
            points.push_back({static_cast<std::size_t>(scan), view(i, 1), Eigen::Vector2d(view(i, 2), view(i, 3))});
          }
        }
        const NavTrack track = nav.is_none() ? NavTrack{} : navTrackOf(nav);
        SlamOptions slam;
        slam.forming.odometry = odometryOf(nav_class, max_speed, max_turn_rate, track);
        PointScanOptions options;
        options.range_sigma_m = range_sigma;
        options.bearing_sigma_rad = bearing_sigma * 3.14159265358979323846 / 180.0;
        SlamResult result;
        {
          py::gil_scoped_release release;
          result = localizePointScans(points, track, options, slam);
        }
        py::dict out;
        out["trajectory"] = navArray(result.trajectory);
        out["scans"] = result.report.scans;
        out["matches_accepted"] = result.report.matches_accepted;
        out["matches_beyond_limits"] = result.report.matches_beyond_limits;
        out["points_behind_echoes"] = result.report.points_behind_echoes;
        out["loop_closures_accepted"] = result.report.loopClosuresAccepted();
        out["compass_deviation_deg"] =
            result.report.heading_deviation_observed
                ? py::object(py::make_tuple(result.report.heading_deviation_rad.x() * 180.0 / 3.14159265358979323846,
                                            result.report.heading_deviation_rad.y() * 180.0 / 3.14159265358979323846))
                : py::object(py::none());
        return out;
      },
      py::arg("scans"), py::arg("nav") = py::none(), py::arg("range_sigma") = 0.05, py::arg("bearing_sigma") = 1.5,
      py::arg("nav_class") = "auto", py::arg("max_speed") = py::none(), py::arg("max_turn_rate") = py::none(),
      R"doc(Localizes point scans detected elsewhere, as `sonarmap localize` (slam/point_scans.hpp): the scan
matcher, loop closures and pose graph of map_sonar_log(slam=True).

scans: the path of a point-scan CSV (scan,time_s,x_m,y_m; gzip-compressed or not) or a float64 (N, 4) array of the same columns:
each point's scan (an integer; a scan's rows together, in increasing number), time (s, the navigation's
clock, never decreasing) and place in the body frame then (m, x forward, y to starboard). nav: the dead
reckoning, an (N, 7) array or a navigation CSV's path; None: the vehicle believed still. range_sigma
(metres) and bearing_sigma (degrees): 1-sigma of a point's range and bearing. nav_class: how far the
navigation is trusted, by its sensors (slam/odometry_noise.hpp odometryNoiseOf: "dvl-ahrs", "dvl-ins",
"absolute", "ahrs"; the CLI's --nav-class; "auto": navigationClassOf the nav). max_speed (m/s) and
max_turn_rate (degrees/s): the vehicle's limits where nav gives no position (the CLI's --max-speed and
--max-turn-rate; None: 2 m/s and 30 degrees/s). Returns a dict: trajectory
(the corrected dead reckoning, an (M, 7) float64 array; without nav, three rows per scan), scans,
matches_accepted, matches_beyond_limits (refused as beyond max_speed or max_turn_rate),
points_behind_echoes (rows left out behind their echo's leading edge: several points of one beam's
echo are kept as its nearest), loop_closures_accepted, compass_deviation_deg ((a, b) of the compass's
deviation a cos(heading) + b sin(heading) in degrees when the matches showed one, else None). Raises sonarmap.FileError for a broken CSV (naming the line),
sonarmap.ValueError for a bad array, option or track.)doc");
  m.def(
      "read_nav_csv", [](const std::filesystem::path& path) { return navArray(readNavCsv(path.string())); }, py::arg("path"),
      R"doc(Reads a navigation CSV (time_s,x_m,y_m,z_m,roll_rad,pitch_rad,yaw_rad) as an (N, 7) float64 array:
seconds, NED metres, radians (body FRD, Z-Y-X). Raises sonarmap.FileError naming the line and field.)doc");
  m.def(
      "read_navigation",
      [](const std::filesystem::path& path, const std::string& nav_topic, const std::string& msg_path) {
        return navArray(readNavigation(path.string(), nav_topic, msg_path).track);
      },
      py::arg("path"), py::arg("nav_topic") = "", py::arg("msg_path") = "",
      R"doc(Reads a vehicle's navigation as an (N, 7) float64 array (time_s, x_m, y_m, z_m, roll_rad, pitch_rad,
yaw_rad: seconds, NED metres, radians, body FRD, Z-Y-X): a navigation CSV; a ROS log's navigation topic
(`.bag`, `.mcap`, `.db3`: nav_topic, or nav_msgs/Odometry, else the topic with a header and a pose that has
most messages; ENU poses, REP 103, turned into NED; frames named *ned* taken as NED); a BlueROV2's MAVLink
telemetry log (`.tlog`: seconds since 1970, UTC) or ArduPilot dataflash log (`.BIN`: seconds since boot).
Times are the file's own clock (map_sonar_log joins them to the log's). Raises sonarmap.FileError (an
unreadable file, a file without navigation, a bag without the topic named).)doc");
  m.def(
      "read_bag_topics",
      [](const std::filesystem::path& path, const std::string& msg_path) {
        py::list topics;
        for (const RosBagTopic& t : listRosBagTopics(path.string(), msg_path)) {
          py::dict topic;
          topic["topic"] = t.topic;
          topic["type"] = t.type;
          topic["messages"] = t.messages;
          topic["first_s"] = t.first_s;
          topic["last_s"] = t.last_s;
          topics.append(topic);
        }
        return topics;
      },
      py::arg("path"), py::arg("msg_path") = "",
      R"doc(Every topic of a ROS log (a ROS 1 ``.bag``, a ROS 2 ``.mcap``, a rosbag2 ``.db3`` or folder), in the
log's order, as dicts: ``topic``, ``type``, ``messages`` (count), ``first_s`` and ``last_s`` (the first and
last message's record time, seconds since 1970; 0 without messages); ``msg_path`` as read_sonar_log's. The
CLI's ``sonarmap info LOG`` lists the same. Raises sonarmap.FileError for a file that is no readable ROS log.)doc");
  m.def(
      "write_nav_csv",
      [](const std::filesystem::path& path, const py::object& nav) { writeNavCsv(path.string(), navTrackOf(py::reinterpret_borrow<py::object>(nav))); },
      py::arg("path"), py::arg("nav"),
      "Writes an (N, 7) navigation array as a navigation CSV, atomically. Raises sonarmap.ValueError, sonarmap.FileError.");
}

}  // namespace sonarmap::python
