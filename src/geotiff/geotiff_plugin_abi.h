#pragma once
/// @file geotiff_plugin_abi.h
/// The one entry point of the GeoTIFF writer's GDAL plugin (sonarmap_geotiff_gdal.so,
/// geotiff_gdal_plugin.cpp), which libsonarmap_geotiff.so (geotiff_writer.cpp) dlopens at the first
/// GeoTIFF written, so that no other use of sonarmap loads GDAL (63 of the full tool's 167 shared
/// objects).
///
/// A C function over C types: no C++ object, allocation or exception crosses between the two
/// libraries, and the version is in the symbol's name, so a plugin of another version is refused by
/// dlsym (no such symbol) instead of being called with a layout it does not know. A new layout is a
/// new struct and a new name (_v2), the loader asking for the one it was built with.

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// A north-up raster on a projected grid, as sonarmap::GeoRaster (io/geotiff.hpp) whose fields it
/// points into; the loader has checked it (sizes, finite corner, pixel_m > 0).
struct sonarmap_geotiff_raster_v1 {
  int width;                 /* columns, west to east */
  int height;                /* rows, north to south */
  const uint8_t* classes;    /* band 1: width * height values, row-major, row 0 the northern edge */
  const uint8_t* intensity;  /* band 2: width * height values, or NULL for a single band */
  double west_m;             /* easting of the western edge of column 0, metres */
  double north_m;            /* northing of the northern edge of row 0, metres */
  double pixel_m;            /* edge of a square pixel, metres */
  int epsg;                  /* the grid's coordinate reference system */
  const char* description;   /* TIFFTAG_IMAGEDESCRIPTION, NUL-terminated; "" for none */
};

/// Receives the file's bytes, valid during the call only; returns 0 when it took them.
typedef int (*sonarmap_geotiff_sink_v1)(void* context, const unsigned char* bytes, size_t size);

/// Encodes `raster` as GeoTIFF bytes and hands them to `sink(context, ...)` once.
/// Returns 0 on success; otherwise non-zero with a NUL-terminated message (GDAL's, or that the sink
/// refused the bytes) in `message` (`capacity` bytes, truncated to fit). Never throws.
typedef int (*sonarmap_geotiff_encode_v1_fn)(const struct sonarmap_geotiff_raster_v1* raster,
                                             sonarmap_geotiff_sink_v1 sink, void* context, char* message,
                                             size_t capacity);

#define SONARMAP_GEOTIFF_ENCODE_V1 "sonarmap_geotiff_encode_v1"

#ifdef __cplusplus
}
#endif
