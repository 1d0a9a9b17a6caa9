// --origin (see origin_option.hpp).

#include "origin_option.hpp"

#include "help_groups.hpp"
#include "sonarmap/core/errors.hpp"

#include <cstdio>

namespace sonarmap::cli {

void addOriginOption(CLI::App& cmd, std::vector<double>& origin) {
  cmd.add_option("--origin", origin, "Map's zero in the navigation's frame, METRES north,east[,down]")
      ->delimiter(',')
      ->expected(2, 3)
      ->type_name("N,E[,D]")
      ->group(help_group::kNavigation);
}

std::optional<Eigen::Vector3d> givenOrigin(const std::vector<double>& origin) {
  if (origin.empty()) return std::nullopt;
  return Eigen::Vector3d(origin[0], origin[1], origin.size() > 2 ? origin[2] : 0.0);
}

LocalOrigin moveTrackToOrigin(NavTrack& track, const std::vector<double>& origin, double resolution_m, double reach_m) {
  const LocalOrigin chosen = chooseLocalOrigin(track, givenOrigin(origin), resolution_m, reach_m);
  moveToOrigin(track, chosen.ned_m);
  requireTrackFits(track, chosen, resolution_m, reach_m, "--origin", "--resolution");
  return chosen;
}

void printOrigin(const LocalOrigin& origin) {
  if (!origin.isZero()) std::printf("origin: %s; the map's zero is there\n", origin.describe().c_str());
}

void addGeoOriginOption(CLI::App& cmd, std::string& text) {
  cmd.add_option("--geo-origin", text, "The navigation's zero on the Earth where the log gives none, DEGREES")
      ->type_name("LAT,LON[,H]")
      ->check([](const std::string& value) {
        try {
          parseGeodeticPoint(value);
        } catch (const ValueError& error) {
          return std::string(error.what());
        }
        return std::string();
      })
      ->group(help_group::kNavigation);
}

std::optional<GeodeticPoint> mapGeodeticZero(const std::optional<GeodeticPoint>& from_log, const std::string& given,
                                             const LocalOrigin& origin) {
  const std::optional<GeodeticPoint> zero = given.empty() ? from_log : std::optional(parseGeodeticPoint(given));
  if (!zero) return std::nullopt;
  return nedToGeodetic(*zero, origin.ned_m);
}

void printGeodeticZero(const std::optional<GeodeticPoint>& map_zero, const std::string& from) {
  if (!map_zero) return;
  std::printf("geodetic origin: the map's zero at %s (%s), %s\n", describeGeodetic(*map_zero).c_str(), from.c_str(),
              utmZoneOf(*map_zero).describe().c_str());
}

NavTrack inNavigationFrame(NavTrack track, const LocalOrigin& origin) {
  moveFromOrigin(track, origin.ned_m);
  return track;
}

}  // namespace sonarmap::cli
