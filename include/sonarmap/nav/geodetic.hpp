#pragma once
/// @file geodetic.hpp
/// Positions on the Earth: latitude, longitude and height on the WGS84 ellipsoid, the local
/// tangent plane about a geodetic origin (the navigation's NED frame, navigation.hpp) and UTM.
/// Every conversion is GeographicLib's (Karney; Debian libgeographiclib-dev): LocalCartesian for
/// the tangent plane (its ENU turned into NED here: north = y, east = x, down = −z) and UTMUPS for
/// the zone and the grid. No geodesy is written here.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

/// A point on the Earth, WGS84.
struct GeodeticPoint {
  double latitude_deg = 0.0;   ///< degrees north, [−90, 90]
  double longitude_deg = 0.0;  ///< degrees east, [−180, 180]
  double height_m = 0.0;       ///< metres above the WGS84 ellipsoid
};

/// A latitude and longitude read from a log at a time on the navigation's clock.
struct GeodeticFix {
  double time_s = 0.0;  ///< same clock as the track's fixes
  GeodeticPoint point;
};

/// @throws ValueError naming `what` (e.g. "GPS record at 12.3 s") when the point's latitude is not
///         finite or outside [−90, 90], its longitude not finite or outside [−180, 180], or its
///         height not finite.
void requireGeodetic(const GeodeticPoint& point, const std::string& what);

/// `point` in the local NED frame whose zero is `origin` (metres north, east, down on the tangent
/// plane: GeographicLib::LocalCartesian's ENU with axes swapped). Exact (no small-area
/// approximation): a point 10 km away is placed to GeographicLib's accuracy (nanometres).
/// @throws ValueError as requireGeodetic for either point.
Eigen::Vector3d geodeticToNed(const GeodeticPoint& origin, const GeodeticPoint& point);

/// The inverse: the point at `ned_m` (metres north, east, down) of the tangent frame about `origin`.
/// @throws ValueError as requireGeodetic for `origin`, or when ned_m is not finite.
GeodeticPoint nedToGeodetic(const GeodeticPoint& origin, const Eigen::Vector3d& ned_m);

/// The tangent frame about one origin, set up once for many conversions (geodeticToNed and
/// nedToGeodetic set one up per call): GeographicLib::LocalCartesian.
class TangentPlane {
 public:
  /// @throws ValueError as requireGeodetic for `origin`.
  explicit TangentPlane(const GeodeticPoint& origin);
  ~TangentPlane();
  TangentPlane(TangentPlane&&) noexcept;
  TangentPlane& operator=(TangentPlane&&) noexcept;
  const GeodeticPoint& origin() const { return origin_; }
  /// As geodeticToNed(origin(), point), without checking `point`.
  Eigen::Vector3d toNed(const GeodeticPoint& point) const;
  /// As nedToGeodetic(origin(), ned_m), without checking `ned_m`.
  GeodeticPoint toGeodetic(const Eigen::Vector3d& ned_m) const;

 private:
  struct Impl;
  GeodeticPoint origin_;
  std::unique_ptr<Impl> impl_;
};

/// A UTM zone: its number, hemisphere and EPSG code (WGS 84 / UTM: 32600 + zone north,
/// 32700 + zone south).
struct UtmZone {
  int zone = 0;        ///< 1 .. 60
  bool north = true;   ///< northern hemisphere (latitude ≥ 0)
  int epsg() const { return (north ? 32600 : 32700) + zone; }
  /// "UTM zone 31N (EPSG:32631)".
  std::string describe() const;
};

/// The standard UTM zone holding `point` (GeographicLib::UTMUPS::StandardZone: Norway's and
/// Svalbard's exceptions included).
/// @throws ValueError as requireGeodetic, or for a latitude beyond UTM's [−80, 84] (polar: UPS).
UtmZone utmZoneOf(const GeodeticPoint& point);

/// `point` in `zone` (forced: a point just across a zone's edge stays in it): easting, northing in
/// metres (false easting 500 km; false northing 10,000 km south).
/// @throws ValueError as requireGeodetic, or when GeographicLib refuses it (too far from the zone).
Eigen::Vector2d geodeticToUtm(const GeodeticPoint& point, const UtmZone& zone);

/// The inverse: the point at `easting_northing_m` of `zone` (height 0).
/// @throws ValueError when GeographicLib refuses it.
GeodeticPoint utmToGeodetic(const Eigen::Vector2d& easting_northing_m, const UtmZone& zone);

/// The geodetic position of the zero of `track`'s NED frame from latitudes and longitudes `fixes`
/// read on the same clock: each fix within the track's span is placed on the tangent plane about
/// the first such fix, the track's position at its time (interpolated) subtracted, and the mean of
/// these offsets taken back to the Earth. A track without horizontal positions (north and east
/// held at 0: a BlueROV2 without a DVL) thus gets the fixes' mean place; one whose positions come
/// from the same fixes gets the fixes' own origin. Heights: the same, along down.
/// nullopt when no fix lies within the track's span (or either is empty).
/// @throws ValueError as requireGeodetic for a fix, or as NavInterpolator for an invalid track.
std::optional<GeodeticPoint> geodeticOriginOf(const std::vector<GeodeticFix>& fixes, const NavTrack& track);

/// "LAT,LON" or "LAT,LON,HEIGHT" (degrees, degrees, metres) as the CLI's --geo-origin takes it.
/// @throws ValueError for anything else, or as requireGeodetic.
GeodeticPoint parseGeodeticPoint(const std::string& text);

/// "43.2961240 N, 5.3699520 E, 12.00 m" (seven decimals: about 1 cm).
std::string describeGeodetic(const GeodeticPoint& point);

}  // namespace sonarmap
