#pragma once
/// @file geotiff.hpp
/// A north-up raster on a UTM grid written as a GeoTIFF with GDAL (Debian libgdal-dev; GDAL's GTiff
/// driver, gdal.org/drivers/raster/gtiff.html): the map's occupancy in band 1 and, optionally, the
/// sonar's echo intensity (the mosaic) in band 2, georeferenced by an EPSG code and an affine
/// geotransform, so that QGIS, Cockpit's map and gdalinfo place it on the Earth.
///
/// Built as its own shared library, libsonarmap_geotiff.so, which does not link GDAL: the GDAL code
/// is a plugin, sonarmap_geotiff_gdal.so, that it loads (dlopen) at the first GeoTIFF encoded, so a
/// program that writes none never loads GDAL (63 of the full tool's 167 shared objects, about two
/// thirds of its start-up: docs/performance.md, "Start-up"). The plugin is looked for
/// in the folder `sonarmap` beside the file that holds libsonarmap_geotiff.so (dladdr): in the build
/// tree src/geotiff/sonarmap/, installed ${CMAKE_INSTALL_LIBDIR}/sonarmap/ (the Debian package's
/// /usr/lib/sonarmap/).

#include <cstdint>
#include <string>
#include <vector>

namespace sonarmap {

/// Band 1's values: three occupancy classes, kUnknown being the file's no-data value.
enum class RasterClass : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

/// A north-up raster on a projected grid.
struct GeoRaster {
  int width = 0;   ///< columns, west to east (> 0)
  int height = 0;  ///< rows, north to south (> 0)
  /// Band 1: a RasterClass per pixel, row-major, row 0 the northern edge; width × height values.
  std::vector<std::uint8_t> classes;
  /// Band 2 when not empty: echo intensity per pixel (1 … 255, 0 where no echo was heard: no
  /// data), same layout as `classes`.
  std::vector<std::uint8_t> intensity;
  double west_m = 0.0;   ///< easting of the western edge of column 0, metres
  double north_m = 0.0;  ///< northing of the northern edge of row 0, metres
  double pixel_m = 0.0;  ///< edge of a (square) pixel, metres (> 0)
  int epsg = 0;          ///< the grid's coordinate reference system, e.g. 32631 (WGS 84 / UTM zone 31N)
  std::string description;  ///< written as the dataset's TIFFTAG_IMAGEDESCRIPTION
};

/// The GeoTIFF bytes of `raster`: GTiff, DEFLATE-compressed, Byte bands; band 1 "occupancy" with a
/// colour table (unknown transparent, free white, occupied black), category names "unknown",
/// "free", "occupied" and no-data 0; band 2 "echo intensity" (grey) when present; the CRS
/// EPSG:`epsg` (OGRSpatialReference::importFromEPSG) and the geotransform
/// (west_m, pixel_m, 0, north_m, 0, −pixel_m). Written in GDAL's memory file system (/vsimem),
/// so a caller writes the bytes atomically (io/atomic_file.hpp's writeBytesAtomically or a
/// FileTransaction) and no file is half-written.
/// The raster is checked before the plugin is loaded.
/// @throws ValueError for an empty or inconsistent raster (sizes, pixel_m ≤ 0 or not finite, an
///         intensity band of another size); Error when GDAL refuses (an unknown EPSG code, ...),
///         with GDAL's message; Error as loadGeoTiffWriter when the plugin cannot be loaded.
std::vector<unsigned char> encodeGeoTiff(const GeoRaster& raster);

/// Loads the GDAL plugin now (once per process; later calls return at once), so that a command
/// asked for a GeoTIFF fails before its work rather than at its end.
/// @throws Error naming the plugin's path (geoTiffPluginPath) and the dynamic loader's message
///         (dlerror) when it is missing, cannot be loaded (GDAL's runtime library missing...) or is
///         of another version (its entry point sonarmap_geotiff_encode_v1 missing).
void loadGeoTiffWriter();

/// Where the GDAL plugin is looked for: `<folder of libsonarmap_geotiff.so>/sonarmap/sonarmap_geotiff_gdal.so`,
/// absolute. @throws Error when the dynamic loader cannot say which file holds this function (dladdr).
std::string geoTiffPluginPath();

}  // namespace sonarmap
