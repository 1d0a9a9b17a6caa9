/// @file local_origin.cpp
/// The local origin of a navigation far from zero (local_origin.hpp).

#include "sonarmap/mapping/local_origin.hpp"

#include <cmath>
#include <cstdio>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kHalfSpanVoxels = 32767.0;  // depth 16: keys 0 … 65535 about the origin

std::string metres(double value_m) {
  char text[48];
  std::snprintf(text, sizeof text, "%.10g", std::round(value_m * 1000.0) / 1000.0);
  return text;
}

std::string triple(const Eigen::Vector3d& ned_m) {
  return metres(ned_m.x()) + ", " + metres(ned_m.y()) + ", " + metres(ned_m.z());
}

}  // namespace

double mapHalfExtent_m(double resolution_m) { return kHalfSpanVoxels * resolution_m; }

std::string LocalOrigin::describe() const {
  const char* why = given ? "given" : automatic ? "the first fix: the navigation lies farther from zero than the map holds" : "the navigation's own zero";
  return triple(ned_m) + " m (N, E, D; " + why + ")";
}

LocalOrigin chooseLocalOrigin(const NavTrack& track, const std::optional<Eigen::Vector3d>& given, double resolution_m,
                              double reach_m) {
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) throw ValueError("local origin: the resolution must be > 0 m");
  if (!(std::isfinite(reach_m) && reach_m >= 0.0)) throw ValueError("local origin: the beams' reach must be ≥ 0 m");
  LocalOrigin origin;
  if (given) {
    if (!given->allFinite()) throw ValueError("origin: expected finite metres north, east and down");
    origin.ned_m = *given;
    origin.given = true;
    return origin;
  }
  if (track.empty()) return origin;
  const double room_m = mapHalfExtent_m(resolution_m) - reach_m;
  bool horizontal_far = false, vertical_far = false;
  for (const NavSample& fix : track) {
    const Eigen::Vector3d& p = fix.position_ned_m;
    horizontal_far = horizontal_far || std::abs(p.x()) > room_m || std::abs(p.y()) > room_m;
    vertical_far = vertical_far || std::abs(p.z()) > room_m;
  }
  if (!horizontal_far && !vertical_far) return origin;
  const Eigen::Vector3d& first = track.front().position_ned_m;
  origin.ned_m = Eigen::Vector3d(horizontal_far ? first.x() : 0.0, horizontal_far ? first.y() : 0.0,
                                 vertical_far ? first.z() : 0.0);
  origin.automatic = true;
  return origin;
}

void moveToOrigin(NavTrack& track, const Eigen::Vector3d& origin_ned_m) {
  for (NavSample& fix : track) fix.position_ned_m -= origin_ned_m;
}

void moveFromOrigin(NavTrack& track, const Eigen::Vector3d& origin_ned_m) {
  for (NavSample& fix : track) fix.position_ned_m += origin_ned_m;
}

void requireTrackFits(const NavTrack& local_track, const LocalOrigin& origin, double resolution_m, double reach_m,
                      const std::string& origin_knob, const std::string& resolution_knob) {
  const double half_m = mapHalfExtent_m(resolution_m);
  const double room_m = half_m - reach_m;
  for (const NavSample& fix : local_track) {
    const Eigen::Vector3d& p = fix.position_ned_m;
    if (p.cwiseAbs().maxCoeff() <= room_m) continue;
    Eigen::Vector3d low = local_track.front().position_ned_m, high = low;
    for (const NavSample& other : local_track) {
      low = low.cwiseMin(other.position_ned_m);
      high = high.cwiseMax(other.position_ned_m);
    }
    const Eigen::Vector3d half_span_m = (high - low) / 2.0;
    std::string fix_it;
    if (half_span_m.maxCoeff() <= room_m) {
      fix_it = origin_knob + " " + metres(origin.ned_m.x() + (low.x() + high.x()) / 2.0) + "," +
               metres(origin.ned_m.y() + (low.y() + high.y()) / 2.0) + "," +
               metres(origin.ned_m.z() + (low.z() + high.z()) / 2.0) + " (the track's middle) fits it";
    } else {
      char text[256];
      std::snprintf(text, sizeof text,
                    "the track spans %.6g m, more than the map holds at this resolution about any origin (no %s fits "
                    "it): a resolution of at least %.3g m holds it (%s), or map the track in parts",
                    2.0 * half_span_m.maxCoeff(), origin_knob.c_str(), (half_span_m.maxCoeff() + reach_m) / kHalfSpanVoxels,
                    resolution_knob.c_str());
      fix_it = text;
    }
    char where[160];
    std::snprintf(where, sizeof where, "the navigation fix at %.3f s lies at ", fix.time_s);
    char extent[200];
    std::snprintf(extent, sizeof extent,
                  ", %.6g m from the map's origin (%s m N, E, D); at %g m voxels the map holds ±%.6g m about its origin, "
                  "less the beams' reach %.3g m: ",
                  p.cwiseAbs().maxCoeff(), triple(origin.ned_m).c_str(), resolution_m, half_m, reach_m);
    throw ValueError(where + triple(p + origin.ned_m) + " m (N, E, D)" + extent + fix_it);
  }
}

}  // namespace sonarmap
