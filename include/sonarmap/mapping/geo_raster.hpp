#pragma once
/// @file geo_raster.hpp
/// The 2D map laid on the Earth: a band of the map's heights seen from above (map_slice.hpp's
/// renderBandView) resampled onto the UTM grid of the zone holding the map's zero, pixel edge the
/// map's resolution, ready for a GeoTIFF (io/geotiff.hpp).
///
/// Frames: the map (internal NWU, metres) is the local tangent plane about `map_zero` (its x north,
/// y west on the plane: geodetic.hpp's NED with y negated). Each UTM pixel's centre is taken to the
/// Earth (GeographicLib's UTMUPS), onto the tangent plane (LocalCartesian), and given the class of
/// the map's column there (nearest voxel): exact whatever the grid convergence (the angle between
/// UTM's grid north and true north, up to a few degrees away from the zone's central meridian), at
/// the price of nearest-neighbour resampling (a voxel may show in one pixel more or less).

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "sonarmap/io/geotiff.hpp"
#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// An echo-intensity mosaic on the map's grid (see echo_mosaic.hpp): one value per voxel column,
/// internal NWU frame, same layout as map_slice.hpp's SliceView (column 0 at map x = left_m, the
/// last row at map y = bottom_m).
struct MosaicGrid {
  cv::Mat image;         ///< CV_8U: 1 … 255 an intensity, 0 no echo heard
  double left_m = 0.0;
  double bottom_m = 0.0;
  double pixel_m = 0.0;
};

/// The band of heights [z_min_m, z_max_m] (map z, up, metres) of the internal NWU map `map`, seen
/// from above as renderBandView draws it, on the UTM grid of utmZoneOf(map_zero): pixels of the
/// map's resolution, the grid aligned on whole multiples of it, covering the band's known voxels
/// and a border of one pixel; classes RasterClass (occupied where the band's column holds an
/// occupied voxel, else free where it holds a free one, else unknown). With `mosaic`, band 2 holds
/// its value at each pixel's centre (0 outside it). The description names the map's zero, the
/// resolution and the band.
/// Cost: two GeographicLib conversions per pixel (about 1 µs each).
/// @throws OutOfMapError, ValueError as renderBandView; ValueError as utmZoneOf (a polar map zero).
GeoRaster utmRasterOfMap(const OcTree16& map, double z_min_m, double z_max_m, const GeodeticPoint& map_zero,
                         const MosaicGrid* mosaic = nullptr);

}  // namespace sonarmap
