/// @file geodetic.cpp
/// Positions on the Earth through GeographicLib (see geodetic.hpp).

#include "sonarmap/nav/geodetic.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

void requireGeodetic(const GeodeticPoint& point, const std::string& what) {
  auto text = [](double v) {
    char s[32];
    std::snprintf(s, sizeof s, "%.9g", v);
    return std::string(s);
  };
  if (!std::isfinite(point.latitude_deg) || std::abs(point.latitude_deg) > 90.0) {
    throw ValueError(what + ": latitude " + text(point.latitude_deg) + " degrees is not within [-90, 90]");
  }
  if (!std::isfinite(point.longitude_deg) || std::abs(point.longitude_deg) > 180.0) {
    throw ValueError(what + ": longitude " + text(point.longitude_deg) + " degrees is not within [-180, 180]");
  }
  if (!std::isfinite(point.height_m)) throw ValueError(what + ": height " + text(point.height_m) + " m is not finite");
}

struct TangentPlane::Impl {
  GeographicLib::LocalCartesian plane;
};

TangentPlane::TangentPlane(const GeodeticPoint& origin) : origin_(origin) {
  requireGeodetic(origin, "geodetic origin");
  impl_ = std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(origin.latitude_deg, origin.longitude_deg, origin.height_m)});
}
TangentPlane::~TangentPlane() = default;
TangentPlane::TangentPlane(TangentPlane&&) noexcept = default;
TangentPlane& TangentPlane::operator=(TangentPlane&&) noexcept = default;

Eigen::Vector3d TangentPlane::toNed(const GeodeticPoint& point) const {
  double east = 0.0, north = 0.0, up = 0.0;  // LocalCartesian is ENU
  impl_->plane.Forward(point.latitude_deg, point.longitude_deg, point.height_m, east, north, up);
  return {north, east, -up};
}

GeodeticPoint TangentPlane::toGeodetic(const Eigen::Vector3d& ned_m) const {
  GeodeticPoint point;
  impl_->plane.Reverse(ned_m.y(), ned_m.x(), -ned_m.z(), point.latitude_deg, point.longitude_deg, point.height_m);
  return point;
}

Eigen::Vector3d geodeticToNed(const GeodeticPoint& origin, const GeodeticPoint& point) {
  requireGeodetic(point, "geodetic point");
  return TangentPlane(origin).toNed(point);
}

GeodeticPoint nedToGeodetic(const GeodeticPoint& origin, const Eigen::Vector3d& ned_m) {
  if (!ned_m.allFinite()) throw ValueError("a position on the tangent plane that is not finite");
  return TangentPlane(origin).toGeodetic(ned_m);
}

std::string UtmZone::describe() const {
  return "UTM zone " + std::to_string(zone) + (north ? "N" : "S") + " (EPSG:" + std::to_string(epsg()) + ")";
}

UtmZone utmZoneOf(const GeodeticPoint& point) {
  requireGeodetic(point, "the point whose UTM zone is asked");
  if (point.latitude_deg < -80.0 || point.latitude_deg >= 84.0) {
    throw ValueError("latitude " + std::to_string(point.latitude_deg) + " is beyond UTM's [-80, 84) degrees (polar: UPS)");
  }
  UtmZone zone;
  zone.zone = GeographicLib::UTMUPS::StandardZone(point.latitude_deg, point.longitude_deg);
  zone.north = point.latitude_deg >= 0.0;
  return zone;
}

Eigen::Vector2d geodeticToUtm(const GeodeticPoint& point, const UtmZone& zone) {
  requireGeodetic(point, "the point to put on UTM");
  int got_zone = 0;
  bool north = false;
  double x = 0.0, y = 0.0;
  try {
    GeographicLib::UTMUPS::Forward(point.latitude_deg, point.longitude_deg, got_zone, north, x, y, zone.zone);
  } catch (const GeographicLib::GeographicErr& error) {
    throw ValueError(std::string("UTM: ") + error.what());
  }
  // The hemisphere is the zone's (a point just south of the equator in a northern zone: negative northing).
  if (north != zone.north) y += north ? -GeographicLib::UTMUPS::UTMShift() : GeographicLib::UTMUPS::UTMShift();
  return {x, y};
}

GeodeticPoint utmToGeodetic(const Eigen::Vector2d& easting_northing_m, const UtmZone& zone) {
  GeodeticPoint point;
  try {
    GeographicLib::UTMUPS::Reverse(zone.zone, zone.north, easting_northing_m.x(), easting_northing_m.y(),
                                   point.latitude_deg, point.longitude_deg);
  } catch (const GeographicLib::GeographicErr& error) {
    throw ValueError(std::string("UTM: ") + error.what());
  }
  return point;
}

std::optional<GeodeticPoint> geodeticOriginOf(const std::vector<GeodeticFix>& fixes, const NavTrack& track) {
  if (fixes.empty() || track.empty()) return std::nullopt;
  const NavInterpolator interpolator(track);
  std::optional<GeodeticPoint> first;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t count = 0;
  for (const GeodeticFix& fix : fixes) {
    requireGeodetic(fix.point, "fix at " + std::to_string(fix.time_s) + " s");
    const std::optional<Eigen::Isometry3d> pose = interpolator.bodyToNedAt(fix.time_s);
    if (!pose) continue;
    if (!first) first = fix.point;
    sum += geodeticToNed(*first, fix.point) - pose->translation();
    ++count;
  }
  if (count == 0) return std::nullopt;
  return nedToGeodetic(*first, sum / static_cast<double>(count));
}

GeodeticPoint parseGeodeticPoint(const std::string& text) {
  double values[3] = {0.0, 0.0, 0.0};
  int n = 0;
  const char* p = text.data();
  const char* end = p + text.size();
  while (p <= end && n < 4) {
    const char* comma = std::find(p, end, ',');
    if (n == 3) throw ValueError("'" + text + "' is not LAT,LON[,HEIGHT]: too many numbers");
    const auto [ptr, ec] = std::from_chars(p, comma, values[n]);
    if (ec != std::errc() || ptr != comma || p == comma) throw ValueError("'" + text + "' is not LAT,LON[,HEIGHT] (degrees, metres)");
    ++n;
    p = comma + 1;
  }
  if (n < 2) throw ValueError("'" + text + "' is not LAT,LON[,HEIGHT]: give both latitude and longitude");
  const GeodeticPoint point{values[0], values[1], values[2]};
  requireGeodetic(point, "'" + text + "'");
  return point;
}

std::string describeGeodetic(const GeodeticPoint& point) {
  char text[96];
  std::snprintf(text, sizeof text, "%.7f %s, %.7f %s, %.2f m", std::abs(point.latitude_deg),
                point.latitude_deg < 0 ? "S" : "N", std::abs(point.longitude_deg), point.longitude_deg < 0 ? "W" : "E",
                std::abs(point.height_m) < 0.005 ? 0.0 : point.height_m);  // no "-0.00"
  return text;
}

}  // namespace sonarmap
