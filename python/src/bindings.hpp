#pragma once
// The parts of the `_sonarmap` extension, one per layer of the library; module.cpp calls each.

#include <optional>

#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>  // paths as str or os.PathLike (pathlib.Path)

#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::python {

namespace py = pybind11;

/// The map object Python sees: an OcTree16 and, for a map made by the sonar mapper, its counts.
struct OccupancyMap {
  OcTree16 tree;
  std::optional<MappingStats> stats;
  std::optional<NavTrack> trajectory;  ///< map_sonar_log(slam=True): the corrected trajectory
  std::optional<SlamReport> slam;      ///< ... and what the localization did
  std::optional<Eigen::Vector3d> origin;  ///< the map's zero in the navigation's frame (NED m), when not zero
  /// The frame of the tree's coordinates: map_sonar_log's map_frame, a read file's header; nullopt
  /// for a map built point by point (its points' frame).
  std::optional<MapFrame> frame = std::nullopt;
  /// The map's zero on the Earth: a read file's header (geodeticOriginOfComments), or set by the user.
  std::optional<GeodeticPoint> geodetic_origin = std::nullopt;
};

/// The tree of `map` in the frame scenes are given in (the mapper's internal NWU): converted back
/// when the map carries a frame, as it is otherwise.
inline OcTree16 treeInSceneFrame(const OccupancyMap& map) {
  return map.frame && *map.frame != MapFrame::kNwu ? mapFromFrame(map.tree, *map.frame) : map.tree;
}

void bindErrors(py::module_& m);    // bind_errors.cpp: sonarmap.Error and its subclasses
void bindMap(py::module_& m);       // bind_map.cpp: OccupancyMap (octree, queries, files)
void bindSonar(py::module_& m);     // bind_sonar.cpp: SonarLog, polar and Cartesian images, detectors
void bindOptions(py::module_& m);   // bind_options.cpp: mapping_options, the mapping keywords
void bindMapping(py::module_& m);   // bind_mapping.cpp: map_sonar_log, MappingStats, navigation
void bindOnline(py::module_& m);    // bind_online.cpp: OnlineMapper
void bindSimEval(py::module_& m);   // bind_sim_eval.cpp: Scene, simulate, evaluate
void bindViews(py::module_& m);     // bind_views.cpp: slices and top/side views of a map as arrays

}  // namespace sonarmap::python

#include <string>
#include <vector>

#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap::python {

/// A sonar log as Python sees it: the library's SonarLog, the beam of the sonar that recorded it
/// (for the mapper's default beam widths), and the beams as contiguous arrays, built once on first
/// access (the library stores each beam's bins in its own vector).
struct PySonarLog {
  SonarLog log;
  std::string format;  ///< "mat", "csv", … (parseLogFormat's names) or "simulated"
  NominalBeam beam;    ///< the sonar's nominal beam widths
  // Contiguous copies for numpy, filled by cache().
  bool cached = false;
  int bins = 0;
  std::vector<std::uint8_t> intensities;  ///< beams × bins, row-major, 0 beyond each beam's bins
  std::vector<std::int32_t> valid_bins;
  std::vector<double> time_s, bearing_rad, bin_length_m;
  // What the head recorded of its settings (Beam's optional fields): NaN, or -1 for the gain, when not.
  std::vector<double> intensity_span_db, pulse_length_m;
  std::vector<std::int32_t> gain_setting;
  void cache();
};

/// The mapping keyword arguments (the keywords of mappingOptionTable(): the command line's option
/// names with '-' as '_', angles with _deg) as MappingArguments. `allowed_extra` names further
/// keywords the caller handles itself (skipped here).
/// @throws TypeError for an unknown keyword (an angle without its unit: saying its name with
///         _deg); sonarmap.ValueError for a value of the wrong kind.
MappingArguments mappingArguments(const py::kwargs& kwargs, const std::vector<std::string>& allowed_extra = {});

/// The mapping keywords for a docstring, "resolution (metres), detector, ...": every one, or with
/// `detection_only` those detect_obstacles uses (OptionStage::kDetection).
std::string mappingKeywordsDoc(bool detection_only);

/// `message` (an error or warning of the library, written for the command line) in the Python
/// module's words: each command-line flag of map_sonar_log's options ("--beam-width",
/// "--nav-class") replaced by its keyword ("beam_width_deg", "nav_class").
std::string inPythonWords(const std::string& message);

/// A keyword's value as a string. @throws sonarmap.ValueError naming `name` when it is not a str.
std::string textArgument(const py::handle& value, const std::string& name);

/// The nominal beam of the sonar the keyword `format` names (parseLogFormat's names: nominalBeam),
/// or nullopt for None or "auto" (no sonar named).
/// @throws sonarmap.ValueError for a value that is not a str or an unknown format name.
std::optional<NominalBeam> namedSonarBeam(const py::handle& format);

/// Every format's nominal beam, for docstrings and errors: "mat, csv, …: 3° × 35°; ping360: 2° × 25°".
std::string sonarBeamsText();

}  // namespace sonarmap::python
