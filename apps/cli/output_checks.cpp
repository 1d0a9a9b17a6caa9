#include "output_checks.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {
namespace {

std::string lowerCase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

void requireOutputExtension(const std::string& path, std::initializer_list<std::string_view> extensions,
                            std::string_view option, std::string_view what) {
  if (path.empty()) return;
  const std::string extension = lowerCase(std::filesystem::path(path).extension().string());
  if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) return;
  throw ValueError(std::string(option) + " '" + path + "': " + std::string(what) + ", not " +
                   (extension.empty() ? std::string("a name without extension") : "'" + extension + "'"));
}

void requireMapOutput(const std::string& path, std::string_view option) {
  requireOutputExtension(path, {".bt", ".ot"}, option, "the map is an OctoMap file, .bt (binary tree) or .ot (full tree)");
}

void requireTrajectoryOutput(const std::string& path, std::string_view option) {
  requireOutputExtension(path, {".csv", ".tum", ".txt"}, option,
                         "the trajectory is a navigation .csv, or TUM text (.tum, .txt)");
}

void requirePngOutput(const std::string& path, std::string_view option) {
  requireOutputExtension(path, {".png"}, option, "the picture is a .png");
}

void requireGeoTiffOutput(const std::string& path, bool mosaic) {
  requireOutputExtension(path, {".tif", ".tiff"}, "--geotiff", "a GeoTIFF is a .tif or .tiff");
  if (mosaic && path.empty()) throw ValueError("--mosaic is the GeoTIFF's second band: give --geotiff FILE.tif");
}

}  // namespace sonarmap::cli
