/// @file geotiff_gdal_plugin.cpp
/// The GeoTIFF writer's GDAL plugin: sonarmap_geotiff_encode_v1 (geotiff_plugin_abi.h), the file
/// written with GDAL's GTiff driver in its memory file system (see io/geotiff.hpp for the file).

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "geotiff_plugin_abi.h"

namespace {

/// GDAL's refusal, with its last message; turned into the entry point's message.
struct GdalFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string gdalMessage(const std::string& what) {
  const char* message = CPLGetLastErrorMsg();
  return what + (message != nullptr && *message != '\0' ? std::string(": ") + message : "");
}

void check(CPLErr status, const char* what) {
  if (status != CE_None) throw GdalFailure(gdalMessage(what));
}

void writeBand(GDALDataset& dataset, int index, const std::uint8_t* values, const sonarmap_geotiff_raster_v1& r) {
  GDALRasterBand* band = dataset.GetRasterBand(index);
  check(band->RasterIO(GF_Write, 0, 0, r.width, r.height, const_cast<std::uint8_t*>(values), r.width, r.height,
                       GDT_Byte, 0, 0),
        "writing a band");
  check(band->SetNoDataValue(0.0), "setting no-data");
}

void setMetadata(GDALDataset& dataset, const sonarmap_geotiff_raster_v1& r) {
  OGRSpatialReference crs;
  if (crs.importFromEPSG(r.epsg) != OGRERR_NONE) throw GdalFailure(gdalMessage("unknown EPSG code " + std::to_string(r.epsg)));
  check(dataset.SetSpatialRef(&crs), "setting the CRS");
  double transform[6] = {r.west_m, r.pixel_m, 0.0, r.north_m, 0.0, -r.pixel_m};
  check(dataset.SetGeoTransform(transform), "setting the geotransform");
  if (r.description != nullptr && *r.description != '\0') dataset.SetMetadataItem("TIFFTAG_IMAGEDESCRIPTION", r.description);
  dataset.SetMetadataItem("AREA_OR_POINT", "Area");
}

void writeBands(GDALDataset& dataset, const sonarmap_geotiff_raster_v1& r) {
  writeBand(dataset, 1, r.classes, r);
  GDALRasterBand* occupancy = dataset.GetRasterBand(1);
  occupancy->SetDescription("occupancy");
  GDALColorTable colours;
  const GDALColorEntry unknown{128, 128, 128, 0}, free{255, 255, 255, 255}, occupied{0, 0, 0, 255};
  colours.SetColorEntry(0, &unknown);
  colours.SetColorEntry(1, &free);
  colours.SetColorEntry(2, &occupied);
  check(occupancy->SetColorTable(&colours), "setting the colour table");
  const char* names[] = {"unknown", "free", "occupied", nullptr};
  check(occupancy->SetCategoryNames(const_cast<char**>(names)), "setting the category names");
  if (r.intensity != nullptr) {
    writeBand(dataset, 2, r.intensity, r);
    dataset.GetRasterBand(2)->SetDescription("echo intensity");
    check(dataset.GetRasterBand(2)->SetColorInterpretation(GCI_GrayIndex), "setting band 2's interpretation");
  }
}

/// Writes the file in /vsimem and hands its bytes to the sink. @throws GdalFailure, std::bad_alloc.
void encode(const sonarmap_geotiff_raster_v1& r, sonarmap_geotiff_sink_v1 sink, void* context) {
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) throw GdalFailure("GDAL has no GTiff driver");
  static std::atomic<unsigned> count{0};  // a name of its own per call, whatever the thread
  const std::string name = "/vsimem/sonarmap_" + std::to_string(count++) + ".tif";
  char** options = nullptr;
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  const int bands = r.intensity == nullptr ? 1 : 2;
  std::unique_ptr<GDALDataset> dataset(driver->Create(name.c_str(), r.width, r.height, bands, GDT_Byte, options));
  CSLDestroy(options);
  if (!dataset) throw GdalFailure(gdalMessage("cannot create the dataset"));
  try {
    setMetadata(*dataset, r);
    writeBands(*dataset, r);
    dataset.reset();  // closes and flushes the file
    vsi_l_offset length = 0;
    const GByte* data = VSIGetMemFileBuffer(name.c_str(), &length, FALSE);
    if (data == nullptr) throw GdalFailure(gdalMessage("the written file is missing"));
    if (sink(context, data, static_cast<std::size_t>(length)) != 0) throw GdalFailure("the file's bytes were not taken");
    VSIUnlink(name.c_str());
  } catch (...) {
    dataset.reset();
    VSIUnlink(name.c_str());
    throw;
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int sonarmap_geotiff_encode_v1(const sonarmap_geotiff_raster_v1* raster,
                                                                                 sonarmap_geotiff_sink_v1 sink,
                                                                                 void* context, char* message,
                                                                                 size_t capacity) {
  try {
    encode(*raster, sink, context);
    return 0;
  } catch (const std::exception& e) {
    if (capacity > 0) std::snprintf(message, capacity, "%s", e.what());
  } catch (...) {
    if (capacity > 0) std::snprintf(message, capacity, "an unknown error");
  }
  return 1;
}

// The entry point's type is the one the loader casts dlsym's result to.
static_assert(std::is_same_v<decltype(&sonarmap_geotiff_encode_v1), sonarmap_geotiff_encode_v1_fn>);
