/// @file geotiff_writer.cpp
/// GeoTIFF through GDAL (see io/geotiff.hpp).

#include "sonarmap/io/geotiff.hpp"

#include <atomic>
#include <cmath>
#include <memory>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

std::string gdalMessage(const char* what) {
  const char* message = CPLGetLastErrorMsg();
  return std::string("GeoTIFF: ") + what + (message != nullptr && *message != '\0' ? std::string(": ") + message : "");
}

void check(CPLErr status, const char* what) {
  if (status != CE_None) throw Error(gdalMessage(what));
}

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

void writeBand(GDALDataset& dataset, int index, const std::vector<std::uint8_t>& values, const GeoRaster& r) {
  GDALRasterBand* band = dataset.GetRasterBand(index);
  check(band->RasterIO(GF_Write, 0, 0, r.width, r.height, const_cast<std::uint8_t*>(values.data()), r.width, r.height,
                       GDT_Byte, 0, 0),
        "writing a band");
  check(band->SetNoDataValue(0.0), "setting no-data");
}

}  // namespace

std::vector<unsigned char> encodeGeoTiff(const GeoRaster& r) {
  checkRaster(r);
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (driver == nullptr) throw Error("GeoTIFF: GDAL has no GTiff driver");
  static std::atomic<unsigned> count{0};
  const std::string name = "/vsimem/sonarmap_" + std::to_string(reinterpret_cast<std::uintptr_t>(&r)) + "_" +
                           std::to_string(count++) + ".tif";
  char** options = nullptr;
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  const int bands = r.intensity.empty() ? 1 : 2;
  std::unique_ptr<GDALDataset> dataset(driver->Create(name.c_str(), r.width, r.height, bands, GDT_Byte, options));
  CSLDestroy(options);
  if (!dataset) throw Error(gdalMessage("cannot create the dataset"));
  try {
    OGRSpatialReference crs;
    if (crs.importFromEPSG(r.epsg) != OGRERR_NONE) throw Error(gdalMessage(("unknown EPSG code " + std::to_string(r.epsg)).c_str()));
    check(dataset->SetSpatialRef(&crs), "setting the CRS");
    double transform[6] = {r.west_m, r.pixel_m, 0.0, r.north_m, 0.0, -r.pixel_m};
    check(dataset->SetGeoTransform(transform), "setting the geotransform");
    if (!r.description.empty()) dataset->SetMetadataItem("TIFFTAG_IMAGEDESCRIPTION", r.description.c_str());
    dataset->SetMetadataItem("AREA_OR_POINT", "Area");
    writeBand(*dataset, 1, r.classes, r);
    GDALRasterBand* occupancy = dataset->GetRasterBand(1);
    occupancy->SetDescription("occupancy");
    GDALColorTable colours;
    const GDALColorEntry unknown{128, 128, 128, 0}, free{255, 255, 255, 255}, occupied{0, 0, 0, 255};
    colours.SetColorEntry(0, &unknown);
    colours.SetColorEntry(1, &free);
    colours.SetColorEntry(2, &occupied);
    check(occupancy->SetColorTable(&colours), "setting the colour table");
    const char* names[] = {"unknown", "free", "occupied", nullptr};
    check(occupancy->SetCategoryNames(const_cast<char**>(names)), "setting the category names");
    if (bands == 2) {
      writeBand(*dataset, 2, r.intensity, r);
      dataset->GetRasterBand(2)->SetDescription("echo intensity");
      check(dataset->GetRasterBand(2)->SetColorInterpretation(GCI_GrayIndex), "setting band 2's interpretation");
    }
    dataset.reset();  // closes and flushes the file
    vsi_l_offset length = 0;
    GByte* data = VSIGetMemFileBuffer(name.c_str(), &length, FALSE);
    if (data == nullptr) throw Error(gdalMessage("the written file is missing"));
    std::vector<unsigned char> bytes(data, data + length);
    VSIUnlink(name.c_str());
    return bytes;
  } catch (...) {
    dataset.reset();
    VSIUnlink(name.c_str());
    throw;
  }
}

}  // namespace sonarmap
