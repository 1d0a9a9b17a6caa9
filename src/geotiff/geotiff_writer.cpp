/// @file geotiff_writer.cpp
/// encodeGeoTiff (io/geotiff.hpp): the raster checked here, the file written by the GDAL plugin
/// (geotiff_plugin_abi.h) loaded at the first use.

#include "sonarmap/io/geotiff.hpp"

#include <dlfcn.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <new>

#include "geotiff_plugin_abi.h"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void checkRaster(const GeoRaster& r) {
  if (r.width <= 0 || r.height <= 0) throw ValueError("GeoTIFF: the raster is empty");
  const auto pixels = static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height);
  if (r.classes.size() != pixels) throw ValueError("GeoTIFF: band 1 holds " + std::to_string(r.classes.size()) +
                                                    " values for " + std::to_string(pixels) + " pixels");
  if (!r.intensity.empty() && r.intensity.size() != pixels) {
    throw ValueError("GeoTIFF: band 2 holds " + std::to_string(r.intensity.size()) + " values for " +
                     std::to_string(pixels) + " pixels");
  }
  if (!(r.pixel_m > 0.0) || !std::isfinite(r.pixel_m) || !std::isfinite(r.west_m) || !std::isfinite(r.north_m)) {
    throw ValueError("GeoTIFF: the pixel size and the corner must be finite, the pixel size positive");
  }
}

/// dlerror()'s message, or `otherwise` when it has none.
std::string loaderMessage(const char* otherwise) {
  const char* message = dlerror();
  return message != nullptr ? message : otherwise;
}

/// The plugin's entry point, loaded once (never unloaded: GDAL keeps state until the process ends).
sonarmap_geotiff_encode_v1_fn plugin() {
  // A function-local static: loaded by the first caller while the others wait, and tried again at
  // the next call when it threw.
  static const sonarmap_geotiff_encode_v1_fn encode = [] {
    const std::string path = geoTiffPluginPath();
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      throw Error("GeoTIFF: cannot load the GDAL plugin " + path + " (" + loaderMessage("no reason given") + ")");
    }
    void* symbol = dlsym(handle, SONARMAP_GEOTIFF_ENCODE_V1);
    if (symbol == nullptr) {
      const std::string message = loaderMessage("the symbol is null");
      dlclose(handle);
      throw Error("GeoTIFF: the GDAL plugin " + path + " is not this version's: no " SONARMAP_GEOTIFF_ENCODE_V1 " (" +
                  message + ")");
    }
    return reinterpret_cast<sonarmap_geotiff_encode_v1_fn>(symbol);
  }();
  return encode;
}

/// The plugin's sink: copies the bytes into the std::vector `context` points to.
int takeBytes(void* context, const unsigned char* bytes, std::size_t size) {
  try {
    static_cast<std::vector<unsigned char>*>(context)->assign(bytes, bytes + size);
    return 0;
  } catch (const std::bad_alloc&) {
    return 1;
  }
}

}  // namespace

std::string geoTiffPluginPath() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&geoTiffPluginPath), &info) == 0 || info.dli_fname == nullptr) {
    throw Error("GeoTIFF: cannot tell which file holds the GeoTIFF writer (dladdr failed), so not where its GDAL plugin is");
  }
  return (std::filesystem::absolute(info.dli_fname).parent_path() / SONARMAP_GEOTIFF_PLUGIN_SUBPATH).string();
}

void loadGeoTiffWriter() { plugin(); }

std::vector<unsigned char> encodeGeoTiff(const GeoRaster& r) {
  checkRaster(r);
  const sonarmap_geotiff_encode_v1_fn encode = plugin();
  const sonarmap_geotiff_raster_v1 raster{r.width,  r.height,  r.classes.data(), r.intensity.empty() ? nullptr : r.intensity.data(),
                                          r.west_m, r.north_m, r.pixel_m,        r.epsg,
                                          r.description.c_str()};
  std::vector<unsigned char> bytes;
  char message[512] = "";
  if (encode(&raster, takeBytes, &bytes, message, sizeof message) != 0) throw Error(std::string("GeoTIFF: ") + message);
  return bytes;
}

}  // namespace sonarmap
