#pragma once
// --origin: the local origin a navigation in absolute coordinates (UTM, a national grid) is mapped
// about (sonarmap/mapping/local_origin.hpp), for map, live and localize.

#include <vector>

#include <CLI/CLI.hpp>

#include "sonarmap/mapping/local_origin.hpp"

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

/// `track` as written for the user: in the navigation's own coordinates (moved back by `origin`).
NavTrack inNavigationFrame(NavTrack track, const LocalOrigin& origin);

}  // namespace sonarmap::cli
