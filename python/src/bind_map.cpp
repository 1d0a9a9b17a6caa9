// sonarmap.OccupancyMap: the library's depth-16 occupancy octree (octree/occupancy_octree.hpp) with
// its files (io/map_file.hpp), point-cloud insertion (algorithms/point_cloud_insertion.hpp), ray
// casting (algorithms/cast_ray.hpp) and batched queries over numpy arrays.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "navigation_arrays.hpp"
#include "numpy_checks.hpp"
#include "sonarmap/algorithms/cast_ray.hpp"
#include "sonarmap/algorithms/point_cloud_insertion.hpp"
#include "sonarmap/io/map_file.hpp"

namespace sonarmap::python {
namespace {

/// Centres (M, 3) and edge lengths (M,) of the leaves `keep(log_odds)` selects, metres, map frame.
template <class Keep>
py::tuple leafVoxels(const OcTree16& tree, Keep keep, bool with_log_odds = false) {
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> sizes;
  std::vector<float> log_odds;
  {
    py::gil_scoped_release release;
    const double resolution_m = tree.resolution_m();
    tree.forEachLeaf([&](const LeafView<16>& leaf) {
      if (!keep(leaf.log_odds)) return;
      const double edge = leaf.edgeVoxels();
      centers.push_back(tree.coder().centerOf(leaf.key) + Eigen::Vector3d::Constant(0.5 * (edge - 1.0) * resolution_m));
      sizes.push_back(edge * resolution_m);
      log_odds.push_back(leaf.log_odds);
    });
  }
  if (with_log_odds) return py::make_tuple(toPointsArray(centers), toArray(sizes), toArray(log_odds));
  return py::make_tuple(toPointsArray(centers), toArray(sizes));
}

OctreeOptions treeOptions(double prob_hit, double prob_miss, double clamping_thres_min, double clamping_thres_max,
                          double occupancy_thres) {
  OctreeOptions options;
  options.occupancy.prob_hit = prob_hit;
  options.occupancy.prob_miss = prob_miss;
  options.occupancy.clamp_min = clamping_thres_min;
  options.occupancy.clamp_max = clamping_thres_max;
  options.occupancy.occupied_above = occupancy_thres;
  options.occupancy.free_below = occupancy_thres;
  return options;
}

std::string repr(const OccupancyMap& map) {
  const NodeCounts counts = map.tree.counts();
  char text[160];
  std::snprintf(text, sizeof text, "OccupancyMap(resolution=%g m, %zu nodes, %zu leaves%s)", map.tree.resolution_m(),
                counts.nodes, counts.leaves, map.stats ? ", with mapping stats" : "");
  return text;
}

}  // namespace

void bindMap(py::module_& m) {
  py::class_<InsertStats>(m, "InsertStats", "What one insert_point_cloud did (C++ sonarmap::InsertStats).")
      .def_readonly("points", &InsertStats::points, "points given (before discretisation)")
      .def_readonly("skipped_nonfinite", &InsertStats::skipped_nonfinite, "points with NaN/inf (always 0 here: they raise)")
      .def_readonly("out_of_map", &InsertStats::out_of_map, "rays whose (clipped) end lies outside the map, ignored")
      .def_readonly("rays", &InsertStats::rays, "rays cast")
      .def_readonly("free_updates", &InsertStats::free_updates, "voxels updated as misses (each once)")
      .def_readonly("occupied_updates", &InsertStats::occupied_updates, "voxels updated as hits (each once)")
      .def_readonly("key_set_bytes", &InsertStats::key_set_bytes,
                    "bytes the insertion's per-scan key sets (crossed and hit voxels) held")
      .def("__repr__", [](const InsertStats& s) {
        return "InsertStats(points=" + std::to_string(s.points) + ", rays=" + std::to_string(s.rays) +
               ", free_updates=" + std::to_string(s.free_updates) +
               ", occupied_updates=" + std::to_string(s.occupied_updates) + ", out_of_map=" + std::to_string(s.out_of_map) + ")";
      });

  const OccupancyParams defaults{};
  py::class_<OccupancyMap>(m, "OccupancyMap", R"doc(
Probabilistic occupancy octree of depth 16 (OctoMap's OcTree layout; Hornung et al. 2013).

Voxels are cubes of edge ``resolution`` metres in the map frame (x, y, z in metres; for sonar
maps: ENU or NED as map_sonar_log's map_frame chose, see ``frame``). Leaves hold clamped log-odds; a voxel is occupied
when its probability is above ``occupancy_thres``, free at or below it, unknown when never
observed. ``.bt``/``.ot`` files interoperate with OctoMap 1.9 (octovis, octomap-python).

OctoMap-python names: insertPointCloud -> insert_point_cloud, getLabels -> classify,
extractPointCloud -> occupied_voxels / free_voxels, writeBinary -> write("x.bt"),
readBinary / read -> OccupancyMap.read, castRay -> cast_ray, size -> num_nodes,
getNumLeafNodes -> num_leaf_nodes, memoryUsage -> memory_bytes, getResolution -> resolution.

The GIL is released during insertions, queries and file I/O: several threads may query one map
at once, but a map must not be modified while another thread reads or modifies it.
)doc")
      .def(py::init([](double resolution, double prob_hit, double prob_miss, double clamping_thres_min,
                       double clamping_thres_max, double occupancy_thres) {
             return OccupancyMap{OcTree16(resolution, treeOptions(prob_hit, prob_miss, clamping_thres_min,
                                                                  clamping_thres_max, occupancy_thres)),
                                 std::nullopt, std::nullopt, std::nullopt, std::nullopt};
           }),
           py::arg("resolution"), py::arg("prob_hit") = defaults.prob_hit, py::arg("prob_miss") = defaults.prob_miss,
           py::arg("clamping_thres_min") = defaults.clamp_min, py::arg("clamping_thres_max") = defaults.clamp_max,
           py::arg("occupancy_thres") = defaults.occupied_above,
           R"doc(An empty map.

resolution: voxel edge in metres, finite and > 0.
prob_hit, prob_miss: P(occupied | hit), P(occupied | miss) of insert_point_cloud (OctoMap: 0.7, 0.4).
clamping_thres_min, clamping_thres_max: clamping probabilities (OctoMap: 0.1192, 0.971).
occupancy_thres: a voxel is occupied above this probability, free at or below (OctoMap: 0.5).
Raises sonarmap.ValueError for a resolution that is not finite and > 0, or probabilities out of
(0, 1) or out of order (prob_miss < 0.5 < prob_hit, clamping_thres_min <= occupancy_thres <= clamping_thres_max).)doc")
      .def_static(
          "read",
          [](const std::filesystem::path& path) {
            py::gil_scoped_release release;
            const std::vector<std::string> comments = readMapFileHeader(path.string()).comments;
            const Eigen::Vector3d origin_ned_m = mapOriginOfComments(comments);
            return OccupancyMap{readMapFile(path.string()), std::nullopt, std::nullopt, std::nullopt,
                                origin_ned_m.isZero(0.0) ? std::nullopt : std::optional(origin_ned_m),
                                mapFrameOfComments(comments), geodeticOriginOfComments(comments)};
          },
          py::arg("path"), R"doc(Reads a map file: ``.bt`` (OctoMap binary: free leaves get the lower, occupied the
upper clamping log-odds) or ``.ot`` (OctoMap full tree, exact log-odds), chosen by the extension
(any case); OctoMap's default sensor model. The coordinates are the file's; ``frame`` is the frame its
header names (None when it names none). Raises sonarmap.FileError for an unknown extension,
a file that cannot be opened, or a malformed/truncated file (naming the field or offset);
sonarmap.ValueError for a resolution that is not finite and > 0.)doc")
      .def(
          "write",
          [](const OccupancyMap& map, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            std::vector<std::string> comments;
            if (map.frame) {
              comments = mapHeaderComments(*map.frame, map.origin.value_or(Eigen::Vector3d::Zero()), map.geodetic_origin);
            } else if (map.geodetic_origin) {
              comments.push_back(mapGeodeticComment(*map.geodetic_origin));
            }
            writeMapFile(map.tree, path.string(), comments);
          },
          py::arg("path"), R"doc(Writes the map to ``path`` atomically in the format its extension names: ``.bt``
(maximum likelihood, as OctoMap's writeBinary) or ``.ot`` (full log-odds). The map is not modified
(no pruning or thresholding); a map with a ``frame`` names it in the header (a ``#`` comment line
OctoMap skips), and a ``geodetic_origin`` too. Raises sonarmap.FileError for an unknown extension or a file that
cannot be written (an existing file is then left untouched).)doc")
      .def_property_readonly("resolution", [](const OccupancyMap& map) { return map.tree.resolution_m(); },
                             "Voxel edge in metres.")
      .def_property_readonly(
          "frame",
          [](const OccupancyMap& map) -> py::object {
            return map.frame ? py::str(std::string(mapFrameName(*map.frame))) : py::object(py::none());
          },
          "The frame of the map's coordinates: \"ENU\" (x east, y north, z up), \"NED\" (x north, y east, z down), "
          "\"NWU\" (a file written before frames were named); None for a map built point by point.")
      .def_property_readonly(
          "stats", [](const OccupancyMap& map) { return map.stats; },
          "The mapper's counts (sonarmap.MappingStats) for a map made by map_sonar_log or OnlineMapper; None otherwise.")
      .def_property_readonly(
          "trajectory",
          [](const OccupancyMap& map) -> py::object {
            if (!map.trajectory) return py::none();
            return navArray(*map.trajectory);
          },
          "map_sonar_log(slam=True): the corrected trajectory the map was built with, an (N, 7) float64 array "
          "[time_s, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad] (NED metres, radians; one row per dead-reckoning "
          "fix, or three per scan without nav), in nav's own coordinates (the origin added back); None otherwise.")
      .def_property_readonly(
          "origin",
          [](const OccupancyMap& map) -> py::object {
            if (!map.origin) return py::none();
            return py::make_tuple(map.origin->x(), map.origin->y(), map.origin->z());
          },
          "map_sonar_log: the map's zero in nav's frame, (north_m, east_m, down_m), when nav was mapped about a "
          "local origin (the keyword origin, or nav's first fix when nav lies far from zero); read: the origin "
          "the file's header names; write names it. None otherwise.")
      .def_property(
          "geodetic_origin",
          [](const OccupancyMap& map) -> py::object {
            if (!map.geodetic_origin) return py::none();
            const GeodeticPoint& g = *map.geodetic_origin;
            return py::make_tuple(g.latitude_deg, g.longitude_deg, g.height_m);
          },
          [](OccupancyMap& map, const py::object& value) {
            if (value.is_none()) {
              map.geodetic_origin.reset();
              return;
            }
            const auto t = value.cast<std::vector<double>>();
            if (t.size() != 2 && t.size() != 3) throw ValueError("geodetic_origin: (latitude_deg, longitude_deg[, height_m])");
            const GeodeticPoint point{t[0], t[1], t.size() == 3 ? t[2] : 0.0};
            requireGeodetic(point, "geodetic_origin");
            map.geodetic_origin = point;
          },
          "The map's zero on the Earth, (latitude_deg, longitude_deg, height_m) on WGS84, as the file's header "
          "names it (`sonarmap map` writes it when the log carries latitude and longitude, or with --geo-origin); "
          "None when unknown. Settable (a 2- or 3-sequence, or None); write names it. Raises sonarmap.ValueError "
          "for a latitude outside [-90, 90], a longitude outside [-180, 180] or a value that is not finite.")
      .def_property_readonly(
          "slam",
          [](const OccupancyMap& map) -> py::object {
            if (!map.slam) return py::none();
            py::dict report;
            report["scans"] = map.slam->scans;
            report["scans_with_points"] = map.slam->scans_with_points;
            report["matches_accepted"] = map.slam->matches_accepted;
            report["matches_refused"] = map.slam->matches_refused;
            report["matches_beyond_limits"] = map.slam->matches_beyond_limits;
            report["odometry_scale"] = map.slam->odometry_scale;
            report["odometry_scale_sigma"] = map.slam->odometry_scale_sigma;
            report["odometry_scale_observed"] = map.slam->odometry_scale_observed;
            report["heading_only"] = map.slam->heading_only;
            report["compass_deviation_deg"] =
                map.slam->heading_deviation_observed
                    ? py::object(py::make_tuple(map.slam->heading_deviation_rad.x() * 180.0 / std::numbers::pi,
                                                map.slam->heading_deviation_rad.y() * 180.0 / std::numbers::pi))
                    : py::object(py::none());
            py::list loops;
            for (const LoopClosure& loop : map.slam->loop_closures) {
              py::dict entry;
              entry["from_scan"] = loop.from;
              entry["to_scan"] = loop.to;
              entry["accepted"] = loop.accepted;
              entry["reason"] = loop.reason;
              loops.append(entry);
            }
            report["loop_closures"] = loops;
            return report;
          },
          "map_sonar_log(slam=True): what the localization did, a dict (scans, scans_with_points, matches_accepted, "
          "matches_refused and matches_beyond_limits among them (beyond max_speed or max_turn_rate), odometry_scale and its 1-sigma odometry_scale_sigma (the dead reckoning's distances times "
          "it are the scans'; slam/localizer.hpp), odometry_scale_observed (False: the scans do not constrain it, "
          "so it is 1), heading_only (True: the navigation gave the heading only and the position came from the "
          "scans), compass_deviation_deg ((a, b) of the compass's deviation a cos(heading) + b sin(heading) in "
          "degrees, when the matches showed one; None otherwise), loop_closures: a list of dicts from_scan, to_scan, "
          "accepted, reason); None otherwise.")
      .def(
          "insert_point_cloud",
          [](OccupancyMap& map, const py::object& points, const py::object& origin, double max_range, bool discretize,
             bool lazy_eval) {
            const PointsView view = requirePoints(points, "points");
            const Eigen::Vector3d origin_m = requirePoint(origin, "origin");
            InsertOptions options;
            options.max_range_m = max_range;
            options.discretize = discretize;
            options.lazy_eval = lazy_eval;
            py::gil_scoped_release release;
            PointCloud cloud(view.size());
            for (std::size_t i = 0; i < view.size(); ++i) cloud[i] = view[i];
            const InsertStats stats = insertPointCloud(map.tree, cloud, origin_m, options);
            if (!lazy_eval) map.tree.updateDirtyInnerOccupancy();
            return stats;
          },
          py::arg("points"), py::arg("origin"), py::arg("max_range") = -1.0, py::arg("discretize") = false,
          py::arg("lazy_eval") = false,
          R"doc(Integrates one scan (OctoMap's insertPointCloud): the voxels each ray crosses from ``origin`` to a
point are misses, the voxel of each point a hit; a voxel is updated at most once per call, a hit
wins over a miss. Rays are traversed with a 3D DDA (Amanatides & Woo 1987).

points: (N, 3) float64, map frame, metres (any strides; float32 or NaN/inf are refused, not converted).
origin: (3,) sensor position, map frame, metres.
max_range: longest ray in metres; < 0: no limit (a farther point clears up to max_range, no hit).
discretize: one ray per end-point voxel, to its centre (OctoMap's discretize).
lazy_eval: update leaves only; call update_inner_occupancy() before relying on inner nodes.
Returns sonarmap.InsertStats. Raises sonarmap.ValueError for a bad array, sonarmap.OutOfMapError
when the origin lies outside the map. Points outside the map are counted (out_of_map), never wrapped.)doc")
      .def(
          "insert_ray",
          [](OccupancyMap& map, const py::object& origin, const py::object& end, double max_range) {
            const Eigen::Vector3d origin_m = requirePoint(origin, "origin");
            const Eigen::Vector3d end_m = requirePoint(end, "end");
            py::gil_scoped_release release;
            const bool inserted = insertRay(map.tree, origin_m, end_m, max_range, map.tree.options().lazy);
            if (map.tree.options().lazy) map.tree.updateDirtyInnerOccupancy();
            return inserted;
          },
          py::arg("origin"), py::arg("end"), py::arg("max_range") = -1.0,
          R"doc(Integrates one ray (OctoMap's insertRay): misses from ``origin`` (3,) up to the voxel of ``end`` (3,),
which is a hit (map frame, metres). max_range > 0: free space stops there and no hit is marked.
Returns False, changing nothing, when the origin or the (clipped) end lies outside the map.)doc")
      .def(
          "classify",
          [](const OccupancyMap& map, const py::object& points) {
            const PointsView view = requirePoints(points, "points", true);
            py::array_t<std::int8_t> out(static_cast<py::ssize_t>(view.size()));
            std::int8_t* labels = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (std::size_t i = 0; i < view.size(); ++i) {
                const std::optional<OcTree16::KeyType> key = map.tree.coder().keyOf(view[i]);
                const Occupancy occupancy = key ? map.tree.occupancyOf(*key) : Occupancy::kUnknown;
                labels[i] = occupancy == Occupancy::kOccupied ? 1 : (occupancy == Occupancy::kFree ? 0 : -1);
              }
            }
            return out;
          },
          py::arg("points"), R"doc(Classes of the voxels holding ``points`` (OctoMap-python's getLabels).

points: (N, 3) float64 (or one (3,) point), map frame, metres.
Returns int8 (N,): -1 unknown (never observed, or outside the map), 0 free, 1 occupied, by the
map's occupancy threshold. Raises sonarmap.ValueError for a bad shape, dtype or NaN/inf.)doc")
      .def(
          "occupancy",
          [](const OccupancyMap& map, const py::object& points) {
            const PointsView view = requirePoints(points, "points", true);
            py::array_t<double> out(static_cast<py::ssize_t>(view.size()));
            double* probability_out = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (std::size_t i = 0; i < view.size(); ++i) {
                const std::optional<OcTree16::KeyType> key = map.tree.coder().keyOf(view[i]);
                const std::optional<float> log_odds = key ? map.tree.search(*key) : std::nullopt;
                probability_out[i] = log_odds ? probability(*log_odds) : std::numeric_limits<double>::quiet_NaN();
              }
            }
            return out;
          },
          py::arg("points"), R"doc(Occupancy probabilities of the voxels holding ``points`` (OctoMap's search + getOccupancy).

points: (N, 3) float64 (or one (3,) point), map frame, metres.
Returns float64 (N,) in [clamping_thres_min, clamping_thres_max]; NaN where unknown (never
observed, or outside the map). Raises sonarmap.ValueError for a bad shape, dtype or NaN/inf.)doc")
      .def(
          "log_odds",
          [](const OccupancyMap& map, const py::object& points) {
            const PointsView view = requirePoints(points, "points", true);
            py::array_t<double> out(static_cast<py::ssize_t>(view.size()));
            double* log_odds_out = out.mutable_data();
            {
              py::gil_scoped_release release;
              for (std::size_t i = 0; i < view.size(); ++i) {
                const std::optional<OcTree16::KeyType> key = map.tree.coder().keyOf(view[i]);
                const std::optional<float> log_odds = key ? map.tree.search(*key) : std::nullopt;
                log_odds_out[i] = log_odds ? *log_odds : std::numeric_limits<double>::quiet_NaN();
              }
            }
            return out;
          },
          py::arg("points"), "As occupancy(), in log-odds: float64 (N,), NaN where unknown.")
      .def(
          "occupied_voxels", [](const OccupancyMap& map) {
            const LogOddsModel& model = map.tree.model();
            return leafVoxels(map.tree, [&](float l) { return model.classify(l) == Occupancy::kOccupied; });
          },
          R"doc(The occupied leaves (OctoMap-python's extractPointCloud, occupied part).

Returns (centers, sizes): centers float64 (M, 3), map frame, metres, the centre of each leaf;
sizes float64 (M,), each leaf's edge in metres (the resolution, or a multiple of it for a pruned
leaf covering 2^k voxels per edge). Depth-first order.)doc")
      .def(
          "free_voxels", [](const OccupancyMap& map) {
            const LogOddsModel& model = map.tree.model();
            return leafVoxels(map.tree, [&](float l) { return model.classify(l) == Occupancy::kFree; });
          },
          "The free leaves as (centers (M, 3) float64 metres, sizes (M,) float64 metres); see occupied_voxels.")
      .def(
          "leaves", [](const OccupancyMap& map) { return leafVoxels(map.tree, [](float) { return true; }, true); },
          "Every leaf as (centers (M, 3) float64 m, sizes (M,) float64 m, log_odds (M,) float32).")
      .def(
          "cast_ray",
          [](const OccupancyMap& map, const py::object& origin, const py::object& direction, bool ignore_unknown,
             double max_range) -> py::object {
            const Eigen::Vector3d origin_m = requirePoint(origin, "origin");
            const Eigen::Vector3d direction_v = requirePoint(direction, "direction");
            std::optional<Eigen::Vector3d> hit;
            {
              py::gil_scoped_release release;
              hit = castRay(map.tree, origin_m, direction_v, max_range, ignore_unknown);
            }
            if (!hit) return py::none();
            py::array_t<double> out(3);
            std::copy(hit->data(), hit->data() + 3, out.mutable_data());
            return out;
          },
          py::arg("origin"), py::arg("direction"), py::arg("ignore_unknown") = false, py::arg("max_range") = -1.0,
          R"doc(The centre of the first occupied voxel along a ray (OctoMap's castRay), walked with a 3D DDA.

origin: (3,) start, map frame, metres. direction: (3,) a DIRECTION (any non-zero length), not an
end point: pass end - origin for a segment. ignore_unknown: walk through unknown voxels as free
(OctoMap's default False stops there). max_range: metres, <= 0 no limit.
Returns float64 (3,), or None when unknown space, the range limit or the map's border comes first.
Raises sonarmap.ValueError for a zero or non-finite direction, sonarmap.OutOfMapError for an
origin outside the map.)doc")
      .def(
          "update_inner_occupancy",
          [](OccupancyMap& map) {
            py::gil_scoped_release release;
            map.tree.updateInnerOccupancy();
          },
          "Recomputes every inner node from its children and prunes (OctoMap's updateInnerOccupancy).")
      .def("num_nodes", [](const OccupancyMap& map) { return map.tree.counts().nodes; },
           "Nodes in the tree, inner nodes and leaves (OctoMap's size()).")
      .def("num_leaf_nodes", [](const OccupancyMap& map) { return map.tree.counts().leaves; },
           "Leaves in the tree (OctoMap's getNumLeafNodes()).")
      .def("num_inner_nodes", [](const OccupancyMap& map) { return map.tree.counts().inner; }, "Inner nodes in the tree.")
      .def("memory_bytes", [](const OccupancyMap& map) { return map.tree.memoryBytes(); },
           "Bytes the nodes occupy, 8 per slot in use (compare OctoMap's memoryUsage()).")
      .def("memory_bytes_allocated", [](const OccupancyMap& map) { return map.tree.memoryBytesAllocated(); },
           "Bytes allocated by the tree, including capacity kept for growth.")
      .def("is_empty", [](const OccupancyMap& map) { return map.tree.empty(); }, "True when nothing is known.")
      .def("copy", [](const OccupancyMap& map) { return OccupancyMap(map); }, "A deep copy.")
      .def("__repr__", &repr);
}

}  // namespace sonarmap::python
