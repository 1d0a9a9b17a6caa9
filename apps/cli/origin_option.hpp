#pragma once
// --origin: the local origin a navigation in absolute coordinates (UTM, a national grid) is mapped
// about (sonarmap/mapping/local_origin.hpp), for map, live and localize.

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/nav/geodetic.hpp"

namespace sonarmap::cli {

/// Adds --origin N,E[,D] (metres in the navigation's frame) into `origin`.
void addOriginOption(CLI::App& cmd, std::vector<double>& origin);

/// --origin's point (nullopt when not given; D 0 when only N,E).
std::optional<Eigen::Vector3d> givenOrigin(const std::vector<double>& origin);

/// The origin `track` is mapped about at `resolution_m` with beams reaching `reach_m`
/// (chooseLocalOrigin), `track` moved to it and checked (requireTrackFits, naming --origin and
/// --resolution).
/// @throws ValueError as requireTrackFits.
LocalOrigin moveTrackToOrigin(NavTrack& track, const std::vector<double>& origin, double resolution_m, double reach_m);

/// "origin: ..." on stdout when the map's zero is not the navigation's.
void printOrigin(const LocalOrigin& origin);

/// Adds --geo-origin LAT,LON[,H] (degrees, metres above the WGS84 ellipsoid) into `text`: the
/// navigation's NED zero on the Earth where the log gives none (or in place of the log's).
void addGeoOriginOption(CLI::App& cmd, std::string& text);

/// The map's zero on the Earth: --geo-origin's point (`given`, when not empty) or else the log's
/// (`from_log`: NavigationSource::geodetic_origin), moved by the local origin `origin` (the map's
/// zero in the navigation's frame; nedToGeodetic); nullopt when neither is there.
/// @throws ValueError as parseGeodeticPoint.
std::optional<GeodeticPoint> mapGeodeticZero(const std::optional<GeodeticPoint>& from_log, const std::string& given,
                                             const LocalOrigin& origin);

/// "geodetic origin: 43.2961240 N, ... (from ...); UTM zone 31N (EPSG:32631)" on stdout, when there is one.
void printGeodeticZero(const std::optional<GeodeticPoint>& map_zero, const std::string& from);

/// `track` as written for the user: in the navigation's own coordinates (moved back by `origin`).
NavTrack inNavigationFrame(NavTrack track, const LocalOrigin& origin);

}  // namespace sonarmap::cli
