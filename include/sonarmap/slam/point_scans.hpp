#pragma once
/// @file point_scans.hpp
/// The SLAM back end on point scans: scans whose points were detected elsewhere (another
/// sonar driver, a forward-looking sonar's detector, a lidar), given as a point-scan CSV, localized
/// with the same motion compensation, scan matcher, gates and pose graph as `map --slam`.
///
/// Point-scan CSV (`sonarmap localize SCANS.csv`): a header row `scan,time_s,x_m,y_m`, then one
/// row per point: the scan it belongs to (an integer ≥ 0; a scan's rows together, scans in
/// increasing number), the time it was measured (seconds, on the navigation's clock; times never
/// decrease down the file), and where it lay in the vehicle's body frame at that time (metres, x
/// forward, y to starboard: the NED body frame the navigation's yaw turns, navigation.hpp). Blank
/// lines are skipped, CRLF line ends and a UTF-8 byte-order mark are accepted.

#include <cstddef>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sonarmap/mapping/detected_log.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/slam/localizer.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap {

/// One point of a point scan.
struct BodyPoint {
  std::size_t scan = 0;  ///< the scan it belongs to
  double time_s = 0.0;   ///< when it was measured, seconds (the navigation's clock)
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();  ///< body frame at time_s: x forward, y starboard, metres
};

/// Reads a point-scan CSV from `in`; `source` names it in messages.
/// @throws FileError naming the source, the line and the field for a missing or wrong header, a
///         row without exactly four numbers, a value that is not finite, a scan number that is not
///         an integer in [0, 2^53], a scan whose rows are not together or numbers that decrease, a
///         time earlier than the row before, or a file without points.
std::vector<BodyPoint> readPointScans(std::istream& in, const std::string& source);

/// readPointScans of the file at `path`, gzip-compressed or not (`.csv.gz`: io/text_input.hpp).
/// @throws FileError as above, or when the file cannot be opened or its gzip data is truncated or
///         corrupt (openTextInput).
std::vector<BodyPoint> readPointScansCsv(const std::string& path);

/// Checks `points` against the format's rules (finite values, scan numbers up to 2^53, a scan's
/// points together, scans in increasing number, times never decreasing).
/// @throws ValueError naming the first point that breaks one.
void checkPointScans(const std::vector<BodyPoint>& points);

/// Writes `points` as a point-scan CSV that readPointScans reads back exactly.
/// @throws ValueError as checkPointScans.
void writePointScans(std::ostream& out, const std::vector<BodyPoint>& points);

/// The detections of `detected` (one per beam, mapping/detected_log.hpp) as point scans: each in the
/// body frame (`sonar_to_body`, navigation.hpp) at its beam's time, one scan per detected sweep,
/// numbered from 0. What `sonarmap localize` reads, from the beam detector of `map --slam`.
std::vector<BodyPoint> pointScansOf(const DetectedLog& detected, const Eigen::Isometry3d& sonar_to_body);

/// The uncertainty of a point scan's sensor (the dead reckoning's is ScanFormingOptions::odometry).
struct PointScanOptions {
  /// 1σ of a point's range (along its line of sight from the body's origin), metres, > 0: a
  /// sonar's range resolution (a bin, the pulse).
  double range_sigma_m = 0.05;
  /// 1σ of its bearing, radians, > 0: half the horizontal beam width of a 3° MSIS beam.
  double bearing_sigma_rad = 1.5 * 3.14159265358979323846 / 180.0;

  /// @throws ValueError for a sigma that is not finite and > 0.
  void validate() const;
};

/// One scan per scan number of `points`, motion-compensated as formScans does (scan_forming.hpp).
/// A beam's echo listed as several points (every bin above a threshold: points at one time along one
/// line of sight from the body's origin, each within 3 range_sigma_m of the one before and within
/// range_sigma_m of the line through the nearest) is kept as its nearest point, the leading edge, as
/// the beam detector of `map --slam` reports one point per beam; a return behind a wider gap is kept
/// as a point of its own. Each kept point is placed with the dead-reckoning body pose at its own
/// time, expressed in the body frame at the scan's reference time (its middle point's), with its
/// covariance (range_sigma_m along the line of sight from the body's origin, range ·
/// bearing_sigma_rad across it, plus dead reckoning's drift between the two times). Points outside the navigation's time span are
/// skipped, and a scan whose reference time is. An empty `dead_reckoning`: the vehicle believed
/// still at the origin. `forming`: the dead reckoning's noise model (ScanFormingOptions::odometry;
/// its sigmas and max_travel_m are the beams' and do not apply).
/// @throws ValueError for invalid options, points that break the format's rules (checkPointScans)
///         or an invalid navigation track.
std::vector<SonarScan> formPointScans(const std::vector<BodyPoint>& points, const NavTrack& dead_reckoning,
                                      const PointScanOptions& options = {}, const ScanFormingOptions& forming = {});

/// Localizes point scans (formPointScans with slam.forming, then localizeScans as localize does:
/// the odometry's reading period is the navigation's median fix spacing, withNavigationPeriod). The result's trajectory is the dead
/// reckoning corrected (Localizer::correctedTrack); without navigation, the scans' poses. Its
/// report counts the rows left out behind their echoes' leading edges (points_behind_echoes).
/// @throws ValueError for invalid options or an invalid navigation track.
SlamResult localizePointScans(const std::vector<BodyPoint>& points, const NavTrack& dead_reckoning,
                              const PointScanOptions& options = {}, const SlamOptions& slam = {});

}  // namespace sonarmap
