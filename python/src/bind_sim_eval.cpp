// The 3D model side: ground-truth scenes (sim/scene.hpp, scene_file.hpp, builtin_scenes.hpp), the
// MSIS simulator (sim/msis_simulator.hpp, with `sonarmap simulate`'s arguments:
// sim/simulation_arguments.hpp) and the scoring of a map against a scene (eval/ground_truth.hpp).
#include <array>
#include <filesystem>
#include <numbers>
#include <variant>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "navigation_arrays.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/eval/ground_truth.hpp"
#include "sonarmap/eval/simulated_mission.hpp"
#include "sonarmap/eval/trajectory_error.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/nav/tum_trajectory.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/missions.hpp"
#include "sonarmap/sim/scene_file.hpp"
#include "sonarmap/sim/simulation_arguments.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap::python {
namespace {

/// A simulated run as Python sees it.
struct PySimulation {
  PySonarLog log;
  NavTrack nav;             ///< the true track
  NavTrack dead_reckoning;  ///< the believed track; empty without dead-reckoning errors
  Scene scene;
  std::array<double, 6> mounting{};  ///< simulationMounting: X, Y, Z metres, ROLL, PITCH, YAW degrees
};

/// A simulated 3D mission (eval/simulated_mission.hpp) as Python sees it: the run without its log
/// (moved into `log`), which missionTruthOptions needs to score a map of it.
struct PyMission {
  PySonarLog log;
  MissionRun run;
  std::string name;
};

py::dict primitiveDict(const Primitive& primitive) {
  py::dict d;
  d["kind"] = primitiveKind(primitive);
  std::visit(
      [&d](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, Plane>) {
          d["point_m"] = std::vector<double>{p.point_m.x(), p.point_m.y(), p.point_m.z()};
          d["normal"] = std::vector<double>{p.normal.x(), p.normal.y(), p.normal.z()};
        } else if constexpr (std::is_same_v<T, Box>) {
          d["center_m"] = std::vector<double>{p.center_m.x(), p.center_m.y(), p.center_m.z()};
          d["size_m"] = std::vector<double>{p.size_m.x(), p.size_m.y(), p.size_m.z()};
          d["yaw_rad"] = p.yaw_rad;
        } else {
          d["center_x_m"] = p.center_x_m;
          d["center_y_m"] = p.center_y_m;
          d["radius_m"] = p.radius_m;
          d["z_min_m"] = p.z_min_m;
          d["z_max_m"] = p.z_max_m;
        }
        d["reflectivity"] = p.reflectivity;
      },
      primitive);
  return d;
}

py::dict reportDict(const GroundTruthReport& r) {
  py::dict d;
  d["precision"] = r.precision;
  d["recall"] = r.recall;
  d["erosion"] = r.erosion;
  d["free_accuracy"] = r.free_accuracy;
  d["occupied_voxels"] = r.occupied_voxels;
  d["occupied_on_surface"] = r.occupied_on_surface;
  d["occupied_in_water"] = r.occupied_in_water;
  d["surface_voxels"] = r.surface_voxels;
  d["surface_voxels_found"] = r.surface_voxels_found;
  d["surface_voxels_free"] = r.surface_voxels_free;
  d["free_voxels"] = r.free_voxels;
  d["free_in_water"] = r.free_in_water;
  d["matched_voxels"] = r.matched_voxels;
  d["wall_error_mean_m"] = r.mean_distance_m;
  d["wall_error_rms_m"] = r.rms_distance_m;
  d["surface_error_median_m"] = r.surface_error_median_m;
  d["surface_error_p90_m"] = r.surface_error_p90_m;
  d["tolerance_m"] = r.tolerance_m;
  d["z_min_m"] = r.z_min_m;
  d["z_max_m"] = r.z_max_m;
  d["max_range_m"] = r.max_range_m;
  py::list surfaces;
  for (const SurfaceOffset& s : r.surfaces) {
    py::dict e;
    e["primitive"] = s.primitive;
    e["voxels"] = s.voxels;
    e["median_signed_offset_m"] = s.median_signed_offset_m;
    surfaces.append(e);
  }
  d["surfaces"] = surfaces;
  return d;
}

/// A track from an (N, 7) array, or a navigation CSV or TUM file's path (readTrajectory).
NavTrack trajectoryArgument(const py::object& track) {
  if (py::isinstance<py::str>(track) || py::hasattr(track, "__fspath__")) {
    return readTrajectory(py::module_::import("os").attr("fspath")(track).cast<std::string>());
  }
  return navTrackOf(track);
}

Scene sceneArgument(const py::object& scene, const MsisHeadOptions& head) {
  if (py::isinstance<Scene>(scene)) return scene.cast<Scene>();
  if (!py::isinstance<py::str>(scene) && !py::hasattr(scene, "__fspath__")) {
    throwValueError("scene expects a sonarmap.Scene, a built-in scene name or a scene file path");
  }
  return sceneOf(py::module_::import("os").attr("fspath")(scene).cast<std::string>(), head);
}

}  // namespace

void bindSimEval(py::module_& m) {
  py::class_<Scene>(m, "Scene", R"doc(
A ground-truth scene: planes, boxes and vertical cylinders in the internal frame (NWU: x north,
y west, z up; metres; C++ sonarmap::Scene), whatever frame its file was written in. Build one with
builtin_scene or read_scene; simulate and evaluate take it; write saves it in ENU or NED.
)doc")
      .def_property_readonly(
          "primitives",
          [](const Scene& scene) {
            py::list out;
            for (const Primitive& p : scene.primitives) out.append(primitiveDict(p));
            return out;
          },
          "The primitives as dicts (kind, geometry in metres/radians in the internal NWU frame, reflectivity), in "
          "scene order.")
      .def_property_readonly(
          "reverberation_db", [](const Scene& scene) { return scene.reverberation_db; },
          "An enclosed basin's diffuse reverberation after the TVG, dB in the echo model's units, or None "
          "(open water; C++ Scene::reverberation_db).")
      .def(
          "distance",
          [](const Scene& scene, const py::object& points) {
            const PointsView view = requirePoints(points, "points", true);
            py::array_t<double> out(static_cast<py::ssize_t>(view.size()));
            double* distance = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (std::size_t i = 0; i < view.size(); ++i) distance[i] = distanceToSurface(scene, view[i]);
            }
            return out;
          },
          py::arg("points"), "Distance of each point (N, 3) float64 m, map frame) to the nearest surface: float64 (N,), metres.")
      .def(
          "write",
          [](const Scene& scene, const std::filesystem::path& path, const std::string& frame) {
            writeScene(path.string(), scene, parseMapFrame(frame));
          },
          py::arg("path"), py::arg("frame") = "enu",
          "Writes the scene file (scene_file.hpp format), atomically, its coordinates in ``frame``: \"enu\" (default, "
          "x east, y north, z up) or \"ned\" (x north, y east, z down), named in its first line; write it in the frame "
          "you map in (map_sonar_log's map_frame). Raises sonarmap.FileError, sonarmap.ValueError (also for another "
          "frame).")
      .def("__len__", [](const Scene& scene) { return scene.primitives.size(); })
      .def("__repr__", [](const Scene& scene) { return "Scene(" + std::to_string(scene.primitives.size()) + " primitives)"; });

  m.def(
      "builtin_scene",
      [](const std::string& name, double reach_m, double vertical_beam_width_deg) {
        return builtinScene(name, reach_m, vertical_beam_width_deg * std::numbers::pi / 180.0);
      },
      py::arg("name"), py::arg("reach_m") = kBuiltinSceneReach_m, py::arg("vertical_beam_width_deg") = 35.0,
      R"doc(A built-in scene ("tank", "harbour", "hull", "soft", "open-water", 3D: "quay3d") built for a head of
range scale reach_m (metres) and vertical beam width (degrees). Raises sonarmap.ValueError listing
the names for an unknown one.)doc");
  m.def("builtin_scene_names", &allBuiltinSceneNames, "Names builtin_scene and simulate accept.");
  m.def("sonar_preset_names", &sonarPresetNames, "Head presets simulate accepts (its sonar= argument).");
  m.def(
      "read_scene", [](const std::filesystem::path& path) { return readScene(path.string()); }, py::arg("path"),
      "Reads a scene file in the frame its first line names (ENU, NED; NWU for files without one or with the "
      "header written before frames were named). Raises sonarmap.FileError naming the line and field, or an "
      "unknown frame.");

  py::class_<PySimulation>(m, "Simulation", "A simulated MSIS run: its log, navigation track and scene.")
      .def_readonly("log", &PySimulation::log, "sonarmap.SonarLog of the simulated beams (format \"simulated\").")
      .def_property_readonly("nav", [](const PySimulation& s) { return navArray(s.nav); },
                             "float64 (N, 7) true navigation fixes [time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad] "
                             "(NED, FRD): the poses the beams were simulated from.")
      .def_property_readonly("truth_nav", [](const PySimulation& s) { return navArray(s.nav); },
                             "float64 (N, 7) the true track, as nav (the CLI's truth_nav.csv).")
      .def_property_readonly(
          "dead_reckoning", [](const PySimulation& s) { return navArray(s.dead_reckoning); },
          "float64 (N, 7) the track a dead-reckoning navigation with the run's DVL and heading errors believes "
          "(the CLI's nav.csv then), same times as nav; (0, 7) without dead-reckoning errors.")
      .def_readonly("scene", &PySimulation::scene, "sonarmap.Scene that was scanned (map frame).")
      .def_property_readonly(
          "mounting", [](const PySimulation& s) { return std::vector<double>(s.mounting.begin(), s.mounting.end()); },
          "The sonar in the body frame as simulated, as map_sonar_log's mounting= takes it: [x_m, y_m, z_m, "
          "roll_deg, pitch_deg, yaw_deg] (the CLI's --mounting; the mission's default when none was given).")
      .def("__repr__", [](const PySimulation& s) {
        return "Simulation(" + std::to_string(s.log.log.beams.size()) + " beams, " + std::to_string(s.nav.size()) +
               " nav fixes, " + std::to_string(s.scene.primitives.size()) + " primitives)";
      });

  const SimulationArguments defaults{};
  m.def(
      "simulate",
      [](const py::object& scene, const std::string& sonar, std::size_t turns, std::uint64_t seed, double sector,
         double sector_center, double speed, double heading, double nav_rate, const std::string& mission,
         std::size_t laps, double dvl_noise, double dvl_scale_error, double heading_bias_deg, double gyro_walk,
         std::optional<double> depth, std::optional<std::vector<double>> mounting) {
        SimulationArguments args;
        if (depth) args.depth_m = *depth;
        if (mounting) args.mounting = *mounting;
        args.mission = mission;
        args.laps = laps;
        args.dvl_noise_mps = dvl_noise;
        args.dvl_scale_error = dvl_scale_error;
        args.heading_bias_deg = heading_bias_deg;
        args.gyro_walk_deg_per_sqrt_s = gyro_walk;
        args.sonar = sonar;
        args.turns = turns;
        args.seed = seed;
        args.sector_deg = sector;
        args.sector_center_deg = sector_center;
        args.speed_mps = speed;
        args.heading_deg = heading;
        args.nav_rate_hz = nav_rate;
        const std::string scene_name = py::isinstance<py::str>(scene) ? scene.cast<std::string>() : std::string();
        const MsisSimulationOptions options = toSimulationOptions(args, scene_name);
        if (py::isinstance<py::str>(scene)) checkMissionScene(args, scene_name);
        const Scene ground_truth = sceneArgument(scene, options.head);
        PySimulation out;
        {
          py::gil_scoped_release release;
          MsisSimulation run = simulateMsis(ground_truth, options);
          out.log.log = std::move(run.log);
          out.nav = std::move(run.nav);
          out.dead_reckoning = std::move(run.dead_reckoning);
          out.scene = std::move(run.scene);
        }
        out.mounting = simulationMounting(args);
        out.log.format = "simulated";
        out.log.beam = NominalBeam{options.head.horizontal_beam_width_rad, options.head.vertical_beam_width_rad};
        return out;
      },
      py::arg("scene"), py::arg("sonar") = defaults.sonar, py::arg("turns") = defaults.turns,
      py::arg("seed") = defaults.seed, py::arg("sector") = defaults.sector_deg,
      py::arg("sector_center") = defaults.sector_center_deg, py::arg("speed") = defaults.speed_mps,
      py::arg("heading") = defaults.heading_deg, py::arg("nav_rate") = defaults.nav_rate_hz,
      py::arg("mission") = defaults.mission, py::arg("laps") = defaults.laps,
      py::arg("dvl_noise") = defaults.dvl_noise_mps, py::arg("dvl_scale_error") = defaults.dvl_scale_error,
      py::arg("heading_bias_deg") = defaults.heading_bias_deg, py::arg("gyro_walk") = defaults.gyro_walk_deg_per_sqrt_s,
      py::arg("depth") = py::none(), py::arg("mounting") = py::none(),
      R"doc(Simulates an MSIS scanning a scene, as ``sonarmap simulate`` (the same arguments, the same run).

scene: a built-in scene name (built for the preset's range), a scene file path, or a sonarmap.Scene.
sonar: head preset (sonar_preset_names()). turns: full turns (or sector passes), >= 1. seed: of the
speckle and noise (a seed always gives the same beams). sector: scanned width in degrees, (0, 360].
sector_center: degrees, clockwise from the sonar's ahead (bearing 0). speed: m/s along heading (degrees
clockwise from north). nav_rate: fixes per second (0: none). depth: metres, NED down from the origin,
without a mission; None: the built-in scene's (3 m in quay3d at 5 m range, under its water surface at
depth 0, scaled with the range; 0 elsewhere).
mission: a named mission (mission_plan_names(); scene must then be its built-in scene, by name) flown
laps times, speed 0 meaning its default speed; turns and heading are then ignored.
mounting: the sonar on the vehicle as map_sonar_log's mounting= (and the CLI's --mounting) takes it,
[x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg]; None: the mission's (tilted-loop: pitch -25), else
all 0. .mounting holds the one simulated.
dvl_noise (m/s per axis and fix), dvl_scale_error (fraction), heading_bias_deg (degrees), gyro_walk
(degrees per sqrt(s)): dead-reckoning errors; with any set, .dead_reckoning holds the drifting
believed track (nav and truth_nav stay the truth; the beams do not change).
Returns sonarmap.Simulation (log, nav, truth_nav, dead_reckoning, scene, mounting).
``simulate(...).log.write_csv(p)`` writes the file
the CLI writes as beams.csv. Raises sonarmap.ValueError for a value out of range or an unknown
scene or preset; sonarmap.FileError for a bad scene file.)doc");

  py::class_<PyMission>(m, "Mission",
                        "A simulated 3D mission (simulate_mission): its log, navigation, scene and the sonar's mounting.")
      .def_readonly("log", &PyMission::log, "sonarmap.SonarLog of the simulated beams (format \"simulated\").")
      .def_property_readonly("nav", [](const PyMission& s) { return navArray(s.run.simulation.nav); },
                             "float64 (N, 7) navigation fixes [time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad] (NED, FRD).")
      .def_property_readonly("scene", [](const PyMission& s) { return s.run.simulation.scene; },
                             "sonarmap.Scene that was scanned (map frame).")
      .def_property_readonly(
          "mounting",
          [](const PyMission& s) { return std::vector<double>(s.run.mounting.begin(), s.run.mounting.end()); },
          "The sonar in the body frame as map_sonar_log's mounting= takes it: [x_m, y_m, z_m, roll_deg, pitch_deg, "
          "yaw_deg] (the CLI's --mounting).")
      .def_property_readonly(
          "beam_width_deg", [](const PyMission& s) { return s.run.options.head.horizontal_beam_width_rad * 180.0 / std::numbers::pi; },
          "The head's horizontal beam width, degrees (map_sonar_log's beam_width_deg=).")
      .def_property_readonly(
          "vertical_aperture_deg", [](const PyMission& s) { return s.run.options.head.vertical_beam_width_rad * 180.0 / std::numbers::pi; },
          "The head's vertical beam width, degrees (map_sonar_log's vertical_aperture_deg=).")
      .def_property_readonly("range", [](const PyMission& s) { return s.run.options.head.range_m; },
                             "The head's range, metres.")
      .def(
          "evaluate",
          [](const PyMission& s, const OccupancyMap& map, double tolerance) {
            const GroundTruthOptions options = missionTruthOptions(s.run, tolerance);
            GroundTruthReport report;
            {
              py::gil_scoped_release release;
              report = evaluateAgainstScene(treeInSceneFrame(map), s.run.simulation.scene, options);
            }
            return reportDict(report);
          },
          py::arg("map"), py::arg("tolerance") = 0.1,
          R"doc(Scores a map of this mission as docs/accuracy.md does (eval/simulated_mission.hpp,
missionTruthOptions): against the scene, seen from 24 sonar poses along the navigation with the
head's vertical aperture and range as the field of view, so that only what the sonar could see
counts. tolerance: match distance, metres. Returns evaluate()'s dict. Raises sonarmap.ValueError
for a map with nothing known.)doc")
      .def("__repr__", [](const PyMission& s) {
        return "Mission(" + s.name + ", " + std::to_string(s.log.log.beams.size()) + " beams, " +
               std::to_string(s.run.simulation.nav.size()) + " nav fixes)";
      });

  m.def("mission_names", &simulatedMissionNames, "The simulated 3D missions: \"lawnmower-3d\", \"tilted-loop\".");
  const SimulatedMission mission_defaults{};
  m.def(
      "simulate_mission",
      [](const std::string& mission, const std::string& sonar, const std::string& scene, std::uint64_t seed) {
        PyMission out;
        out.name = mission;
        {
          py::gil_scoped_release release;
          out.run = simulateMission(SimulatedMission{sonar, scene, mission, seed});
          out.log.log = std::move(out.run.simulation.log);
          out.run.simulation.log = SonarLog{};
        }
        out.log.format = "simulated";
        const MsisHeadOptions& head = out.run.options.head;
        out.log.beam = NominalBeam{head.horizontal_beam_width_rad, head.vertical_beam_width_rad};
        return out;
      },
      py::arg("mission") = mission_defaults.mission, py::arg("sonar") = mission_defaults.preset,
      py::arg("scene") = mission_defaults.scene, py::arg("seed") = mission_defaults.seed,
      R"doc(Simulates one of the 3D missions of docs/accuracy.md (eval/simulated_mission.hpp): a head
preset on a moving vehicle over a built-in 3D scene, as ``sonarmap demo`` does for its 3D run and
``sonarmap simulate quay3d --sonar SONAR --mission MISSION --seed SEED`` does (the same run).

mission: mission_names() ("tilted-loop": a rectangle with the sonar tilted 25 degrees down;
"lawnmower-3d": legs at two depths, the sonar upright). sonar: sonar_preset_names(). scene: a
built-in scene ("quay3d"), built for the head's range. seed: of the speckle and noise.
Map it with ``map_sonar_log(m.log, nav=m.nav, mounting=m.mounting, volume=True,
beam_width_deg=m.beam_width_deg, vertical_aperture_deg=m.vertical_aperture_deg, resolution=...)`` and score the map
with ``m.evaluate(map)``. Returns sonarmap.Mission. Raises sonarmap.ValueError for an unknown
mission, preset or scene.)doc");

  m.def("mission_plan_names", &missionNames,
        "The named missions simulate(mission=...) flies (sim/missions.hpp): \"harbour-loop\", "
        "\"harbour-lawnmower\", \"harbour-featureless\", \"hull-loop\" (planar), \"lawnmower-3d\", \"tilted-loop\" (over quay3d).");
  m.def(
      "eval_trajectory",
      [](const py::object& estimate, const py::object& truth, bool se3, double segment_m) {
        const NavTrack estimated = trajectoryArgument(estimate), true_track = trajectoryArgument(truth);
        TrajectoryErrorOptions options;
        options.se3 = se3;
        options.segment_m = segment_m;
        TrajectoryError e;
        {
          py::gil_scoped_release release;
          e = evaluateTrajectory(estimated, true_track, options);
        }
        py::dict d;
        d["poses"] = e.poses;
        d["distance_m"] = e.distance_m;
        d["ate_rmse_m"] = e.ate_rmse_m;
        d["ate_max_m"] = e.ate_max_m;
        d["ate_start_rmse_m"] = e.ate_start_rmse_m;
        d["rpe_segments"] = e.rpe_segments;
        d["rpe_rmse_m"] = e.rpe_rmse_m;
        d["rpe_yaw_rmse_deg"] = e.rpe_yaw_rmse_deg;
        d["final_drift_m"] = e.final_drift_m;
        d["final_drift_pct"] = e.final_drift_pct;
        return d;
      },
      py::arg("estimate"), py::arg("truth"), py::arg("se3") = false, py::arg("segment_m") = 10.0,
      R"doc(Scores an estimated vehicle track against the true one, as ``sonarmap eval-trajectory``
(eval/trajectory_error.hpp): ATE after a rigid alignment (SE(2) in the horizontal plane, or SE(3)
with se3=True) and with the start positions matched, RPE over segments of segment_m metres travelled, final drift (unaligned).

estimate, truth: float64 (N, 7) arrays as Simulation.nav, or paths of a navigation CSV or a TUM
trajectory. Returns a dict: poses, distance_m, ate_rmse_m, ate_max_m, ate_start_rmse_m (the start
positions matched instead of a fit), rpe_segments, rpe_rmse_m,
rpe_yaw_rmse_deg, final_drift_m, final_drift_pct (NaN where undefined). Raises sonarmap.ValueError
for fewer than 3 estimate fixes within the truth's time span or a bad array; sonarmap.FileError for a
bad file.)doc");

  m.def(
      "evaluate",
      [](const OccupancyMap& map, const py::object& scene, double tolerance, std::optional<double> z_min,
         std::optional<double> z_max, std::optional<double> max_range, const py::object& sensor) {
        // As `sonarmap eval --truth`: an existing file wins over a built-in name (built Micron-sized).
        const bool is_file = py::isinstance<py::str>(scene) && std::filesystem::exists(scene.cast<std::string>());
        const Scene truth = is_file ? readScene(scene.cast<std::string>()) : sceneArgument(scene, MsisHeadOptions{});
        GroundTruthOptions options;
        options.tolerance_m = tolerance;
        options.z_min_m = z_min;
        options.z_max_m = z_max;
        options.max_range_m = max_range;
        if (!sensor.is_none()) {
          const PointsView view = requirePoints(sensor, "sensor", true);
          options.sensor_positions_m.clear();
          for (std::size_t i = 0; i < view.size(); ++i) options.sensor_positions_m.push_back(view[i]);
        }
        options.validate();
        GroundTruthReport report;
        {
          py::gil_scoped_release release;
          report = evaluateAgainstScene(treeInSceneFrame(map), truth, options);
        }
        return reportDict(report);
      },
      py::arg("map"), py::arg("scene"), py::arg("tolerance") = 0.1, py::arg("z_min") = py::none(),
      py::arg("z_max") = py::none(), py::arg("max_range") = py::none(), py::arg("sensor") = py::none(),
      R"doc(Scores a map against a ground-truth scene, as ``sonarmap eval`` (eval/ground_truth.hpp).
A map with a ``frame`` (ENU, NED) is turned back into the internal frame of scenes (NWU: x north,
y west, z up; a scene file's own frame is read by read_scene) first; ``sensor`` positions, z_min and
z_max are in that internal NWU frame.

map: sonarmap.OccupancyMap. scene: sonarmap.Scene, a scene file, or a built-in name (Micron-sized;
an existing file of that name wins, as in the CLI).
tolerance: match distance, metres (raised to one voxel diagonal). z_min, z_max: the evaluated slab,
map frame, metres (default: the known voxels'). max_range: sonar reach, metres (default: the map's
reach). sensor: (K, 3) float64 sonar positions, map frame (default: the origin).
Returns a dict: precision, recall, erosion, free_accuracy (fractions), voxel counts,
wall_error_mean_m, wall_error_rms_m, surface_error_median_m, surface_error_p90_m, the tolerance,
slab and range used, and per-surface offsets. Raises sonarmap.ValueError for invalid options or a
map with nothing known in the slab.)doc");
}

}  // namespace sonarmap::python
