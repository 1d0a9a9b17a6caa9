// Positions on the Earth (nav/geodetic.hpp) against GeographicLib's geodesics (the distance and
// azimuth on the ellipsoid, an independent route to the same place), the curvature of the Earth
// (a point 1 km away on the ellipsoid lies below the tangent plane by s²/2R), and the UTM zones and
// EPSG codes the EPSG registry gives (Marseille 32631, Sydney 32756, south-west Norway's zone 32).
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <cmath>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/nav/geodetic.hpp"

namespace sonarmap {
namespace {

const GeodeticPoint kMarseille{43.2961, 5.37, 0.0};

/// The point `distance_m` from `from` along the geodesic leaving at `azimuth_deg` (clockwise from north).
GeodeticPoint geodesicDirect(const GeodeticPoint& from, double azimuth_deg, double distance_m) {
  GeodeticPoint to;
  GeographicLib::Geodesic::WGS84().Direct(from.latitude_deg, from.longitude_deg, azimuth_deg, distance_m, to.latitude_deg,
                                          to.longitude_deg);
  return to;
}

TEST(navGeodetic, NorthEastDownOnTheTangentPlane) {
  constexpr double kDistance_m = 1000.0;
  const double sag_m = kDistance_m * kDistance_m / (2.0 * 6371000.0);  // 7.8 cm below the plane
  const Eigen::Vector3d north = geodeticToNed(kMarseille, geodesicDirect(kMarseille, 0.0, kDistance_m));
  EXPECT_NEAR(north.x(), kDistance_m, 1e-3);
  EXPECT_NEAR(north.y(), 0.0, 1e-6);
  EXPECT_NEAR(north.z(), sag_m, 2e-3);  // down is positive: the ellipsoid falls away
  const Eigen::Vector3d east = geodeticToNed(kMarseille, geodesicDirect(kMarseille, 90.0, kDistance_m));
  EXPECT_NEAR(east.x(), 0.0, 0.1);  // a geodesic leaving east curves south of the parallel by ~ s² tan(lat) / 2R
  EXPECT_LT(east.x(), 0.0);
  EXPECT_NEAR(east.y(), kDistance_m, 1e-3);
  EXPECT_NEAR(east.z(), sag_m, 2e-3);
  // 30 degrees west of south, 250 m: the NED vector's bearing and length are the geodesic's.
  const Eigen::Vector3d sw = geodeticToNed(kMarseille, geodesicDirect(kMarseille, 210.0, 250.0));
  EXPECT_NEAR(std::atan2(sw.y(), sw.x()) * 180.0 / M_PI, -150.0, 1e-4);
  EXPECT_NEAR(sw.head<2>().norm(), 250.0, 1e-4);
}

TEST(navGeodetic, NedToGeodeticIsTheInverse) {
  for (const Eigen::Vector3d& ned : {Eigen::Vector3d(12.5, -7.25, 3.0), Eigen::Vector3d(-1500.0, 2200.0, -40.0)}) {
    const GeodeticPoint p = nedToGeodetic(kMarseille, ned);
    EXPECT_LT((geodeticToNed(kMarseille, p) - ned).norm(), 1e-8);
  }
  const GeodeticPoint up = nedToGeodetic(kMarseille, Eigen::Vector3d(0.0, 0.0, -10.0));
  EXPECT_NEAR(up.height_m, 10.0, 1e-8);
  EXPECT_NEAR(up.latitude_deg, kMarseille.latitude_deg, 1e-12);
  const TangentPlane plane(kMarseille);
  EXPECT_EQ(plane.toNed(up), geodeticToNed(kMarseille, up));
}

TEST(navGeodetic, UtmZonesAndEpsgCodes) {
  EXPECT_EQ(utmZoneOf(kMarseille).epsg(), 32631);
  EXPECT_EQ(utmZoneOf({-33.86, 151.21, 0.0}).epsg(), 32756);
  EXPECT_EQ(utmZoneOf({60.0, 5.0, 0.0}).zone, 32);  // Norway's exception: 31 by longitude
  EXPECT_EQ(utmZoneOf({-33.86, 151.21, 0.0}).describe(), "UTM zone 56S (EPSG:32756)");
  EXPECT_THROW(utmZoneOf({85.0, 0.0, 0.0}), ValueError);  // polar: UPS
  // The zone's central meridian (3 E for 31) at the equator: easting 500 km, northing 0.
  const Eigen::Vector2d centre = geodeticToUtm({0.0, 3.0, 0.0}, UtmZone{31, true});
  EXPECT_NEAR(centre.x(), 500000.0, 1e-6);
  EXPECT_NEAR(centre.y(), 0.0, 1e-6);
  // UTM's scale on the central meridian is 0.9996: 1 degree of latitude there.
  const Eigen::Vector2d one = geodeticToUtm({1.0, 3.0, 0.0}, UtmZone{31, true});
  double meridian_m = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(0.0, 3.0, 1.0, 3.0, meridian_m);
  EXPECT_NEAR(one.y(), 0.9996 * meridian_m, 1e-3);
  const GeodeticPoint back = utmToGeodetic(geodeticToUtm(kMarseille, utmZoneOf(kMarseille)), utmZoneOf(kMarseille));
  EXPECT_NEAR(back.latitude_deg, kMarseille.latitude_deg, 1e-10);
  EXPECT_NEAR(back.longitude_deg, kMarseille.longitude_deg, 1e-10);
}

TEST(navGeodetic, BadPointsAreRejectedByName) {
  try {
    requireGeodetic({std::nan(""), 5.0, 0.0}, "NavSatFix at 3 s");
    FAIL();
  } catch (const ValueError& e) {
    EXPECT_STREQ(e.what(), "NavSatFix at 3 s: latitude nan degrees is not within [-90, 90]");
  }
  EXPECT_THROW(requireGeodetic({43.0, 181.0, 0.0}, "x"), ValueError);
  EXPECT_THROW(requireGeodetic({43.0, 5.0, INFINITY}, "x"), ValueError);
  EXPECT_THROW(geodeticToNed(kMarseille, {-90.5, 0.0, 0.0}), ValueError);
  EXPECT_EQ(parseGeodeticPoint("43.2961,5.37").longitude_deg, 5.37);
  EXPECT_EQ(parseGeodeticPoint("-33.86,151.21,12").height_m, 12.0);
  for (const char* bad : {"43", "43,", ",5", "43,5,1,2", "43;5", "91,5", "a,b"}) {
    EXPECT_THROW(parseGeodeticPoint(bad), ValueError) << bad;
  }
}

TEST(navGeodetic, OriginOfFixesAlongATrack) {
  // A track whose fixes a positioning system also gave in latitude and longitude, about an origin.
  const GeodeticPoint origin{43.3, 5.4, 2.0};
  NavTrack track;
  std::vector<GeodeticFix> fixes;
  for (int i = 0; i < 20; ++i) {
    NavSample s;
    s.time_s = i;
    s.position_ned_m = Eigen::Vector3d(3.0 * i, -1.5 * i, 0.2 * i);
    track.push_back(s);
    fixes.push_back({i + 0.5, nedToGeodetic(origin, s.position_ned_m + Eigen::Vector3d(1.5, -0.75, 0.1))});
  }
  const std::optional<GeodeticPoint> found = geodeticOriginOf(fixes, track);
  ASSERT_TRUE(found);
  // The last fix, at 19.5 s, lies outside the track. The offsets are taken on the plane about the first fix,
  // tilted from the origin's by 1.7 m / R: 10 µm over the 60 m track.
  EXPECT_LT(geodeticToNed(origin, *found).norm(), 1e-4);
  // A track without horizontal positions (north, east held at 0): the fixes' mean place.
  for (NavSample& s : track) s.position_ned_m.setZero();
  const std::optional<GeodeticPoint> mean = geodeticOriginOf(fixes, track);
  ASSERT_TRUE(mean);
  EXPECT_NEAR(geodeticToNed(origin, *mean).x(), 3.0 * 9.0 + 1.5, 1e-3);  // mean of 3 i + 1.5 over i = 0 .. 18
  EXPECT_FALSE(geodeticOriginOf({{100.0, origin}}, track));  // outside the track's span
  EXPECT_FALSE(geodeticOriginOf({}, track));
}

}  // namespace
}  // namespace sonarmap
