/// @file geo_raster.cpp
/// The 2D map on a UTM grid (see geo_raster.hpp).

#include "sonarmap/mapping/geo_raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sonarmap/mapping/map_slice.hpp"

namespace sonarmap {
namespace {

/// The value of `image` (laid out as a SliceView) at map (x, y); `outside` beyond its edges.
std::uint8_t valueAt(const cv::Mat& image, double left_m, double bottom_m, double pixel_m, double x_m, double y_m,
                     std::uint8_t outside) {
  const double col = std::floor((x_m - left_m) / pixel_m);
  const double row_from_bottom = std::floor((y_m - bottom_m) / pixel_m);
  if (col < 0 || row_from_bottom < 0 || col >= image.cols || row_from_bottom >= image.rows) return outside;
  return image.at<std::uint8_t>(image.rows - 1 - static_cast<int>(row_from_bottom), static_cast<int>(col));
}

RasterClass classOfPixel(std::uint8_t value) {
  if (value == 0) return RasterClass::kOccupied;
  if (value == 255) return RasterClass::kFree;
  return RasterClass::kUnknown;
}

}  // namespace

GeoRaster utmRasterOfMap(const OcTree16& map, double z_min_m, double z_max_m, const GeodeticPoint& map_zero,
                         const MosaicGrid* mosaic) {
  const SliceView view = renderBandView(map, z_min_m, z_max_m);
  const UtmZone zone = utmZoneOf(map_zero);
  const TangentPlane plane(map_zero);
  const double pixel_m = view.pixel_m;
  // The view's corners (NWU x north, y west) on the UTM grid: the box holding them.
  double east_min = std::numeric_limits<double>::infinity(), east_max = -east_min;
  double north_min = east_min, north_max = -east_min;
  const double right_m = view.left_m + view.image.cols * pixel_m, top_m = view.bottom_m + view.image.rows * pixel_m;
  for (const double x : {view.left_m, right_m}) {
    for (const double y : {view.bottom_m, top_m}) {
      const Eigen::Vector2d utm = geodeticToUtm(plane.toGeodetic(Eigen::Vector3d(x, -y, 0.0)), zone);
      east_min = std::min(east_min, utm.x());
      east_max = std::max(east_max, utm.x());
      north_min = std::min(north_min, utm.y());
      north_max = std::max(north_max, utm.y());
    }
  }
  GeoRaster raster;
  raster.pixel_m = pixel_m;
  raster.epsg = zone.epsg();
  // In whole pixels from UTM's zero, one pixel of border each side.
  const double west_px = std::floor(east_min / pixel_m) - 1.0, east_px = std::ceil(east_max / pixel_m) + 1.0;
  const double south_px = std::floor(north_min / pixel_m) - 1.0, north_px = std::ceil(north_max / pixel_m) + 1.0;
  raster.west_m = west_px * pixel_m;
  raster.north_m = north_px * pixel_m;
  raster.width = static_cast<int>(east_px - west_px);
  raster.height = static_cast<int>(north_px - south_px);
  const auto pixels = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height);
  raster.classes.assign(pixels, static_cast<std::uint8_t>(RasterClass::kUnknown));
  if (mosaic != nullptr) raster.intensity.assign(pixels, 0);
  for (int row = 0; row < raster.height; ++row) {
    const double northing = raster.north_m - (row + 0.5) * pixel_m;
    for (int col = 0; col < raster.width; ++col) {
      const double easting = raster.west_m + (col + 0.5) * pixel_m;
      GeodeticPoint point = utmToGeodetic(Eigen::Vector2d(easting, northing), zone);
      point.height_m = map_zero.height_m;
      const Eigen::Vector3d ned = plane.toNed(point);
      const double x_m = ned.x(), y_m = -ned.y();  // NWU
      const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(raster.width) + static_cast<std::size_t>(col);
      raster.classes[i] =
          static_cast<std::uint8_t>(classOfPixel(valueAt(view.image, view.left_m, view.bottom_m, pixel_m, x_m, y_m, 128)));
      if (mosaic != nullptr) {
        raster.intensity[i] = valueAt(mosaic->image, mosaic->left_m, mosaic->bottom_m, mosaic->pixel_m, x_m, y_m, 0);
      }
    }
  }
  char text[320];
  std::snprintf(text, sizeof text,
                "sonarmap 2D map: band 1 occupancy (0 unknown = no data, 1 free, 2 occupied)%s; %s; %g m pixels; map heights "
                "%.2f .. %.2f m up about its zero at %s",
                mosaic != nullptr ? ", band 2 echo intensity (max per voxel column, 0 = no echo)" : "",
                zone.describe().c_str(), pixel_m, z_min_m, z_max_m, describeGeodetic(map_zero).c_str());
  raster.description = text;
  return raster;
}

}  // namespace sonarmap
