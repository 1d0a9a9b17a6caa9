// Maps placed on the Earth: a simulated bag carrying sensor_msgs/NavSatFix goes through
// `map --geotiff` and GDAL's own tools read the result: gdalinfo -json the CRS (the UTM zone's EPSG
// code), the pixel size and the corners; gdallocationinfo -wgs84 projects a point known in
// latitude and longitude (PROJ, not this project's code) onto its pixel, which must show the wall
// the simulated tank has there within one pixel.
#include <gtest/gtest.h>

#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <regex>
#include <string>

#include "cli_fixture.hpp"

namespace sonarmap::test {
namespace {

using cliGeo = CliTest;

constexpr double kLat = 43.2961, kLon = 5.37;  // the simulated NavSatFix's origin: Marseille, UTM zone 31N
constexpr double kResolution = 0.1;

/// A tool of GDAL (gdal-bin), or "" when it is not installed.
std::string gdalTool(const char* path) { return fs::exists(path) ? path : ""; }

class GeoTiffRun : public cliGeo {
 protected:
  /// Simulates the tank with the vehicle moving north, writing a bag with /gps/fix about
  /// (kLat, kLon), and maps it with --geotiff (and --mosaic).
  void mapTank() {
    const ProgramRun sim = run({"simulate", "tank", "-o", (root_ / "sim").string(), "--speed", "0.1", "--turns", "2",
                                "--bag", (root_ / "run.bag").string(), "--geo-origin",
                                std::to_string(kLat) + "," + std::to_string(kLon), "-q"});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    tif_ = out_ / "map.tif";
    const ProgramRun map = run({"map", (root_ / "run.bag").string(), "-o", (out_ / "map.bt").string(), "--resolution",
                                std::to_string(kResolution), "--geotiff", tif_.string(), "--mosaic", "-q"});
    ASSERT_EQ(map.exit_code, 0) << map.err;
    map_out_ = map.out;
  }
  /// gdallocationinfo's report for `args`.
  std::string locate(const Names& args) {
    const ProgramRun r = runProgram("/usr/bin/gdallocationinfo", args, root_);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  }
  /// Band `band`'s value at pixel (col, row), or -1 outside the raster.
  int valueAt(int band, int col, int row) {
    const std::string out = locate({"-valonly", "-b", std::to_string(band), tif_.string(), std::to_string(col), std::to_string(row)});
    return out.empty() || out == "\n" ? -1 : std::stoi(out);
  }
  /// The pixel GDAL places (lat, lon) on: gdallocationinfo -wgs84 (PROJ's projection into the file's CRS).
  std::pair<int, int> pixelOf(double lat, double lon) {
    char lon_text[32], lat_text[32];
    std::snprintf(lon_text, sizeof lon_text, "%.10f", lon);
    std::snprintf(lat_text, sizeof lat_text, "%.10f", lat);
    const std::string report = locate({"-wgs84", tif_.string(), lon_text, lat_text});
    std::smatch m;
    if (!std::regex_search(report, m, std::regex(R"(Location: \((\d+)P,(\d+)L\))"))) {
      ADD_FAILURE() << "no location in: " << report;
      return {-100, -100};
    }
    return {std::stoi(m[1]), std::stoi(m[2])};
  }
  /// Whether a pixel within one of (col, row) is occupied (class 2).
  bool occupiedNear(std::pair<int, int> pixel) {
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if (valueAt(1, pixel.first + dc, pixel.second + dr) == 2) return true;
      }
    }
    return false;
  }
  fs::path tif_;
  std::string map_out_;
};

TEST_F(GeoTiffRun, GdalinfoReadsTheUtmZonePixelSizeAndCorners) {
  if (gdalTool("/usr/bin/gdalinfo").empty()) GTEST_SKIP() << "gdalinfo (gdal-bin) is not installed";
  mapTank();
  EXPECT_NE(map_out_.find("geodetic origin: the map's zero at 43.2961000 N, 5.3700000 E"), std::string::npos) << map_out_;
  EXPECT_NE(map_out_.find("UTM zone 31N (EPSG:32631)"), std::string::npos) << map_out_;
  const ProgramRun info = runProgram("/usr/bin/gdalinfo", {"-json", tif_.string()}, root_);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json json = nlohmann::json::parse(info.out);
  EXPECT_EQ(json["stac"]["proj:epsg"].get<int>(), 32631);
  EXPECT_NE(json["coordinateSystem"]["wkt"].get<std::string>().find("WGS 84 / UTM zone 31N"), std::string::npos);
  const auto transform = json["geoTransform"].get<std::vector<double>>();
  ASSERT_EQ(transform.size(), 6u);
  EXPECT_DOUBLE_EQ(transform[1], kResolution);
  EXPECT_DOUBLE_EQ(transform[5], -kResolution);
  EXPECT_EQ(transform[2], 0.0);
  EXPECT_EQ(transform[4], 0.0);
  // The corners GDAL computes hold the map's zero, whose UTM coordinates GeographicLib gives.
  int zone = 0;
  bool north = false;
  double easting = 0.0, northing = 0.0;
  GeographicLib::UTMUPS::Forward(kLat, kLon, zone, north, easting, northing);
  ASSERT_EQ(zone, 31);
  const auto upper_left = json["cornerCoordinates"]["upperLeft"].get<std::vector<double>>();
  const auto lower_right = json["cornerCoordinates"]["lowerRight"].get<std::vector<double>>();
  EXPECT_LT(upper_left[0], easting);
  EXPECT_GT(lower_right[0], easting);
  EXPECT_GT(upper_left[1], northing);
  EXPECT_LT(lower_right[1], northing);
  // The tank (4.2 x 4.4 m) and a border: a few metres, not more.
  const auto size = json["size"].get<std::vector<int>>();
  EXPECT_GT(size[0] * kResolution, 4.0);
  EXPECT_LT(size[0] * kResolution, 8.0);
  EXPECT_GT(size[1] * kResolution, 4.0);
  EXPECT_LT(size[1] * kResolution, 8.0);
  ASSERT_EQ(json["bands"].size(), 2u);
  EXPECT_EQ(json["bands"][0]["description"], "occupancy");
  EXPECT_EQ(json["bands"][0]["noDataValue"].get<double>(), 0.0);
  EXPECT_EQ(json["bands"][1]["description"], "echo intensity");
}

TEST_F(GeoTiffRun, WallsKnownInLatitudeAndLongitudeLandOnTheirPixels) {
  if (gdalTool("/usr/bin/gdallocationinfo").empty()) GTEST_SKIP() << "gdallocationinfo (gdal-bin) is not installed";
  mapTank();
  // The tank scene's walls in the vehicle's NED frame (sim/builtin_scenes.cpp, box centre 0 north,
  // 0.4 west, 4.2 x 4.4 m): east wall at 1.8 m east, north wall at 2.1 m north. Placed on the Earth by
  // GeographicLib's LocalCartesian about the NavSatFix origin (ENU arguments).
  const GeographicLib::LocalCartesian plane(kLat, kLon, 0.0);
  auto geodetic = [&](double north_m, double east_m) {
    double lat = 0.0, lon = 0.0, h = 0.0;
    plane.Reverse(east_m, north_m, 0.0, lat, lon, h);
    return std::pair(lat, lon);
  };
  for (const auto& [north_m, east_m, what] : {std::tuple(0.8, 1.8, "east wall"), std::tuple(1.2, 1.8, "east wall"),
                                              std::tuple(2.1, 0.6, "north wall"), std::tuple(2.1, -1.0, "north wall")}) {
    const auto [lat, lon] = geodetic(north_m, east_m);
    const std::pair<int, int> pixel = pixelOf(lat, lon);
    EXPECT_TRUE(occupiedNear(pixel)) << what << " at " << north_m << " N, " << east_m << " E: pixel " << pixel.first << ", "
                                     << pixel.second;
  }
  // The east wall mirrored to the west (the west wall is at 2.6 m west) and a point inside: not occupied.
  for (const auto& [north_m, east_m] : {std::pair(0.8, -1.8), std::pair(1.0, 0.0)}) {
    const auto [lat, lon] = geodetic(north_m, east_m);
    EXPECT_FALSE(occupiedNear(pixelOf(lat, lon))) << north_m << " N, " << east_m << " E";
  }
  // The mosaic heard the walls: band 2 is not empty where band 1 is occupied.
  const auto [lat, lon] = geodetic(1.0, 1.8);
  const std::pair<int, int> wall = pixelOf(lat, lon);
  int loudest = 0;
  for (int dc = -1; dc <= 1; ++dc) loudest = std::max(loudest, valueAt(2, wall.first + dc, wall.second));
  EXPECT_GT(loudest, 1);
}

TEST_F(cliGeo, LiveWritesTheGeoTiffMapWrites) {
  const ProgramRun sim = run({"simulate", "tank", "-o", (root_ / "sim").string(), "--speed", "0.1", "--turns", "1",
                              "--bag", (root_ / "run.bag").string(), "--geo-origin", "60.39,5.32", "-q"});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const ProgramRun map = run({"map", (root_ / "run.bag").string(), "-o", (out_ / "map.bt").string(), "--geotiff",
                              (out_ / "map.tif").string(), "-q"});
  ASSERT_EQ(map.exit_code, 0) << map.err;
  EXPECT_NE(map.out.find("UTM zone 32N (EPSG:32632)"), std::string::npos) << map.out;  // Bergen: Norway's zone 32
  // The replayed bag's own NavSatFix places live's map: the same files as map's, at its last write.
  const ProgramRun live = run({"live", (root_ / "run.bag").string(), "-o", (out_ / "live.bt").string(), "--geotiff",
                               (out_ / "live.tif").string(), "--rate", "0", "-q"});
  ASSERT_EQ(live.exit_code, 0) << live.err;
  EXPECT_EQ(readFile(out_ / "live.bt"), readFile(out_ / "map.bt"));
  EXPECT_EQ(readFile(out_ / "live.tif"), readFile(out_ / "map.tif"));
  EXPECT_NE(live.out.find("geodetic origin: the map's zero at 60.3900000 N, 5.3200000 E"), std::string::npos) << live.out;
}

TEST_F(cliGeo, GeoTiffWithoutAPlaceOnTheEarthIsAnError) {
  const ProgramRun sim = run({"simulate", "tank", "-o", (root_ / "sim").string(), "--turns", "1", "-q"});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const ProgramRun map = run({"map", (root_ / "sim" / "beams.csv").string(), "-o", (out_ / "map.bt").string(), "--geotiff",
                              (out_ / "map.tif").string(), "-q"});
  expectError(map, 1);
  EXPECT_NE(map.err.find("--geo-origin"), std::string::npos) << map.err;
  EXPECT_TRUE(listDir(out_).empty());
  // Given by hand, the static sonar's map is placed there.
  const ProgramRun placed = run({"map", (root_ / "sim" / "beams.csv").string(), "-o", (out_ / "map.bt").string(),
                                 "--geotiff", (out_ / "map.tif").string(), "--geo-origin", "-33.86,151.21", "-q"});
  ASSERT_EQ(placed.exit_code, 0) << placed.err;
  EXPECT_NE(placed.out.find("UTM zone 56S (EPSG:32756)"), std::string::npos) << placed.out;
  EXPECT_NE(readFile(out_ / "map.bt").find("# sonarmap geodetic origin: -33.86 151.21 0 "), std::string::npos);
}

TEST_F(cliGeo, ABadGeoOriginIsOneLine) {
  for (const char* bad : {"91,5", "43,181", "nan,5", "43", "43,5,x"}) {
    const ProgramRun map = run({"map", "beams.csv", "-o", (out_ / "map.bt").string(), "--geo-origin", bad});
    expectError(map, 2);  // a usage error, as CLI11 reports a bad value
  }
  EXPECT_TRUE(listDir(out_).empty());
}

}  // namespace
}  // namespace sonarmap::test
