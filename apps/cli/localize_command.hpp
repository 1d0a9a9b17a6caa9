#pragma once
// `sonarmap localize`: the SLAM back end on point scans detected elsewhere (slam/point_scans.hpp),
// with the scan matcher, gates and pose graph of `map --slam`.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "odometry_options.hpp"
#include "command.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap localize` as typed by the user.
struct LocalizeArgs {
  std::string scans;            ///< point-scan CSV (scan,time_s,x_m,y_m)
  std::string nav = "none";     ///< --nav: the dead reckoning (what map --nav reads), or none
  std::string nav_topic;        ///< --nav-topic of a ROS log
  std::string trajectory;       ///< --trajectory: the corrected track (navigation CSV, or TUM for .tum/.txt)
  double range_sigma_m = 0.05;  ///< --range-sigma, metres, > 0
  double bearing_sigma_deg = 1.5;  ///< --bearing-sigma, degrees, > 0
  OdometryArgs odometry;           ///< --nav-class and its values: how far the navigation is trusted
  bool quiet = false;
  std::vector<double> origin;      ///< --origin N,E[,D]: the dead reckoning's zero for the localization; empty: automatic
  std::string map;                 ///< --map: the point scans mapped on the corrected track (.bt/.ot); empty: none
  std::string png;                 ///< --png: the point scans placed on the dead reckoning and on the corrected track
  double resolution_m = 0.0;       ///< --resolution of --map and --png, metres; 0 (not given): scanMapResolution
};

/// Adds the `localize` subcommand to `app`; its options fill `args`.
Command addLocalizeCommand(CLI::App& app, LocalizeArgs& args);

/// Reads the point scans and the navigation, localizes the scans (localizePointScans), writes the
/// corrected trajectory and, when asked, the map of the scans on it (mapScans, ENU) and their
/// picture beside the dead reckoning's (pointPanelsFigure), all together or none (FileTransaction),
/// and prints the localization's one-line summary (unless quiet).
/// @throws FileError for an unreadable or malformed file or a failed write; ValueError when no scan
///         could be localized (nothing to write).
void runLocalize(const LocalizeArgs& args);

}  // namespace sonarmap::cli
