#pragma once
// The options of `sonarmap map` and `live`, every one in physical units: the mapping options are
// the library's table (mapping_option_table.hpp), converted into MapperOptions by toMapperOptions
// (mapping_arguments.hpp). Defaults are the library's, not copies.

#include <array>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "odometry_options.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap map` as typed by the user: the mapping options (MappingArguments, shared
/// with the Python module's map_sonar_log) plus the input, the outputs and the navigation.
struct MapArgs : MappingArguments {
  std::string input;
  std::string output_bt;
  std::string map_png;
  std::string polar_png;
  std::string cartesian_png;
  bool quiet = false;
  bool tank_report = false;
  std::string nav_file;          ///< --nav: a navigation CSV or a ROS bag; "none"; empty: the input bag's own, if any
  LogReadOptions log_read;       ///< --sonar-topic, --bearing-unit, --bearing-direction of a ROS bag input
  std::string nav_topic;         ///< --nav-topic of a ROS bag (empty: found by its fields)
  double nav_time_offset_s = 0.0;  ///< --nav-time-offset: seconds added to the navigation's clock
  std::vector<double> mounting;  ///< X,Y,Z (m), ROLL,PITCH,YAW (degrees) of the sonar in the body; empty: default
  bool slam = false;             ///< --slam: correct the navigation by scan matching (slam/localizer.hpp)
  OdometryArgs odometry;         ///< --nav-class and its values: how far --slam trusts the navigation
  std::string trajectory_out;    ///< --trajectory: the trajectory the map was built with (nav CSV, or TUM)
  std::vector<double> origin;    ///< --origin N,E[,D]: the map's zero in the navigation's frame; empty: automatic
  MapFrame map_frame = kDefaultMapFrame;  ///< --map-frame: the frame the map file is written in
  /// Not an option: the local origin the navigation was mapped about (--origin's or the automatic
  /// one, NED m), named in the map file's header when not zero.
  Eigen::Vector3d map_origin_ned_m = Eigen::Vector3d::Zero();
  std::string geo_origin;  ///< --geo-origin LAT,LON[,H]: the navigation's NED zero on the Earth (empty: the log's)
  /// Set by the command (not an option): the map's zero on the Earth, named in the map file's
  /// header and placing the GeoTIFF; nullopt when neither the log nor --geo-origin gives it.
  std::optional<GeodeticPoint> map_geodetic_zero;
  std::string geotiff;  ///< --geotiff: the 2D map as a GeoTIFF in the UTM zone of the map's zero (empty: none)
  bool mosaic = false;  ///< --mosaic: with --geotiff, the echo intensity as the GeoTIFF's second band
  /// Set by the command: bins nearer than this left out of the mosaic (the detector's highest
  /// minimum range over the sweeps: the transducer's ring-down), metres.
  double mosaic_min_range_m = 0.0;
};

/// Adds `--format` (the input log's format: auto, or parseLogFormat's names, for inputFormat) to `cmd`.
void addLogFormatOption(CLI::App& cmd, std::string& format);

/// The one-line help of a command's input log: every extension the readers know, from their
/// registry (logFormats).
std::string logInputHelp();

/// Adds --format, every option of mappingOptionTable() (its flag, its help with unit and range, its
/// default shown, in its help group), --map-frame, --quiet and --tank-report to `cmd`: everything
/// but the input, outputs, --nav and --mounting.
void addMappingOptions(CLI::App& cmd, MapArgs& args);

/// Adds --map-frame enu|ned (help group Output; default enu, kDefaultMapFrame) to `cmd`, parsed
/// into `frame` (parseMapFrame; a bad name is a usage error listing the choices). Its one-line
/// help is `lead` (what is written in the frame) then the choices.
CLI::Option* addMapFrameOption(CLI::App& cmd, MapFrame& frame, const std::string& lead);

/// `mounting` as --mounting takes it, "X,Y,Z,ROLL,PITCH,YAW": each number in the shortest form that
/// reads back exactly (0.3, not 0.29999999999999999), so a printed command rebuilds the same pose.
std::string mountingText(const std::array<double, 6>& mounting);

/// Adds --mounting X,Y,Z,ROLL,PITCH,YAW to `cmd` (help group Navigation), six numbers separated by
/// commas into `mounting` (sonarToBodyOfMounting, nav/mounting.hpp, turns them into the pose): the
/// sonar's frame (FRD) in the vehicle's body frame (FRD), metres and Z-Y-X Euler angles in degrees.
/// Its one-line help is `when` (what it needs, e.g. "With --nav: ") then the frames and units.
CLI::Option* addMountingOption(CLI::App& cmd, std::vector<double>& mounting, const std::string& when);

// inputFormat, withSonarBeam and toMapperOptions live in the library
// (sonarmap/mapping/mapping_arguments.hpp), shared with the Python module.

}  // namespace sonarmap::cli
