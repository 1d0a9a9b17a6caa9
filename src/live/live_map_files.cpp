/// @file live_map_files.cpp
/// A live run's map files (see live_map_files.hpp).

#include "sonarmap/live/live_map_files.hpp"

#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/geotiff.hpp"
#include "sonarmap/mapping/geo_raster.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/sonar/map_views.hpp"

namespace sonarmap::live {

std::optional<GeodeticPoint> liveGeodeticZero(const LiveOutputs& outputs, const LocalOrigin& origin) {
  if (!outputs.geodetic_origin) return std::nullopt;
  return nedToGeodetic(*outputs.geodetic_origin, origin.ned_m);
}

void writeLiveMapFiles(const OcTree16& shown, const LiveOutputs& outputs, const LocalOrigin& origin) {
  const std::optional<GeodeticPoint> zero = liveGeodeticZero(outputs, origin);
  if (!outputs.map_path.empty()) writeMapFileInFrame(shown, outputs.map_path, outputs.map_frame, origin.ned_m, zero);
  if (outputs.geotiff_path.empty() || !zero) return;
  const std::optional<HeightExtent> band = occupiedHeightExtent(shown);
  writeBytesAtomically(outputs.geotiff_path, encodeGeoTiff(utmRasterOfMap(shown, band ? band->min_m : 0.0,
                                                                          band ? band->max_m : 0.0, *zero)));
}

}  // namespace sonarmap::live
