#pragma once
// What `sonarmap map` does after reading a log, shared with `sonarmap demo`: mapping with a
// progress bar, staging the .bt and the images, the summary line and the tank report.

#include <functional>
#include <string>
#include <vector>

#include "map_command.hpp"

#include <Eigen/Geometry>

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/mapping/echo_mosaic.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/beam_source.hpp"
#include "sonarmap/sonar/log_survey.hpp"

namespace sonarmap::cli {

/// A finished mapping run.
struct MappedLog {
  SonarMapper mapper;
  double seconds = 0.0;  ///< wall time of the mapping alone (no reading or writing), seconds
  /// Said after the resolution in the summary, e.g. " (auto: the 10 m range scale, 2137 of 3035
  /// beams)" for an automatic resolution in a log of several range scales; empty otherwise.
  std::string resolution_note = {};
  /// Said near the end of the summary: why beams were skipped (skipNote, reader_skips.hpp);
  /// empty when none was.
  std::string skip_note = {};
};

/// One mapping call (a mapSonarLog overload) given the progress callback to report to.
using MapCall = std::function<SonarMapper(const ProgressCallback&)>;

/// Runs `map`, drawing a progress bar on stderr unless `quiet`, and times it.
/// @throws whatever `map` throws (ValueError from mapSonarLog).
MappedLog mapWithProgress(const MapCall& map, bool quiet);

/// The sonar's positions in the map frame (metres) at the navigation fixes within the log's time
/// span: the track drawn on the map figures.
std::vector<Eigen::Vector3d> sonarTrack(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body, const SonarLog& log);
/// The same for a surveyed log (its beams' earliest and latest times).
std::vector<Eigen::Vector3d> sonarTrack(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body, const LogSurvey& survey);

/// Stages args.output_bt (OctoMap binary) and the figures (render/*_figures.hpp: ≥ 800 pixels on
/// their long side, axes, a title line with the input's name, the resolution and the detector, a
/// legend) whose paths are not empty. The .bt is `map` (the mapper's internal NWU frame) converted
/// to args.map_frame, its header naming the frame (map_frame.hpp). The map pictures are charts in
/// ENU whatever args.map_frame: east right, north up. args.map_png (the planar model: the band of
/// heights of the occupied voxels seen from above, the slice z = 0 when nothing is occupied, the
/// title saying which; with args.volume: the top view coloured by height), `side_png` (the side
/// view), each with `track_m` (internal NWU frame, metres; empty: none), args.polar_png and
/// args.cartesian_png (the largest sweep;
/// Cartesian pixels of `pixel_m` metres, each beam spread over args.beam_width_deg, or 3° when 0).
/// @throws FileError when a file cannot be staged; ValueError when images are wanted from a log
///         without beams.
/// args.geotiff, when set with args.map_geodetic_zero: the 2D map (the band of --png) on the UTM grid
/// of the map's zero (utmRasterOfMap), with args.mosaic the echo mosaic (echoMosaic) placed by
/// `pose_at` (empty: the static sonar, staticSonarToMap) as band 2.
void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, const SonarLog& log, const OcTree16& map,
                     double pixel_m, const std::string& side_png = {}, const std::vector<Eigen::Vector3d>& track_m = {},
                     const SonarPoseAt& pose_at = {});
/// The same for a log read beam by beam, surveyed as `survey`: the sweep to draw is found in one more
/// pass over `source`, only when a polar or Cartesian image is asked for.
void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, BeamSource& source, const LogSurvey& survey,
                     const OcTree16& map, double pixel_m, const std::string& side_png = {},
                     const std::vector<Eigen::Vector3d>& track_m = {}, const SonarPoseAt& pose_at = {});

/// The sonar's pose in the map at a time on `nav` (local, moved to the map's origin) mounted by
/// `sonar_to_body`: for --mosaic. `nav` must outlive it; an empty track: the static pose.
SonarPoseAt sonarPoseOn(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body);

/// Prints each warning as one line on stderr: "sonarmap: warning: ...".
void printWarnings(const std::vector<std::string>& warnings);

/// Prints the one-line summary of a mapping run on stdout: beams used and skipped (with
/// `with_nav`, also those without navigation), sweeps, obstacles (EMPTY MAP when none), the
/// resolution, the detector's minimum range and threshold (the calibration of the last sweep), map
/// nodes and leaves, memory, time, why beams were skipped (MappedLog::skip_note), how many warnings
/// were printed, and the .bt written. After the
/// obstacles comes the map's height extent, "occupied z LO .. HI m": the lowest and highest
/// occupied voxel centres (occupiedHeightExtent) in args.map_frame's z ("(up)", or "(down)" in
/// NED), left out when nothing is occupied; with args.map_png (2D), the heights the picture shows
/// ("picture: occupied band z LO .. HI m up, seen from above"). It ends with args.output_bt and
/// its frame ("-> map.bt in ENU (x east, y north, z up)").
void printMapSummary(const MappedLog& run, const MapArgs& args, bool with_nav = false, std::size_t warnings = 0);

/// Prints one line on stdout: the rectangle fitted to the occupied cells of the slice holding the
/// most occupied voxels (the sonar's plane of a 2D map, at the vehicle's depth; its height said)
/// and the map's quality (eval/tank_quality.hpp), or why there are too few cells to fit it.
void printTankReport(const OcTree16& map);

}  // namespace sonarmap::cli
