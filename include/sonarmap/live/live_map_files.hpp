#pragma once
/// @file live_map_files.hpp
/// The files a live run rewrites as the map grows (every --write-every, on the page's "save", at
/// the end): the map file and, when asked for, its GeoTIFF.

#include "sonarmap/live/live_session.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap::live {

/// The map's zero on the Earth: the navigation's NED zero (outputs.geodetic_origin) moved by the
/// local origin `origin`; nullopt without a geodetic origin.
std::optional<GeodeticPoint> liveGeodeticZero(const LiveOutputs& outputs, const LocalOrigin& origin);

/// Writes the internal (NWU) map `shown` to outputs.map_path (writeMapFileInFrame, the header naming
/// the local origin and the map's zero on the Earth) and, when outputs.geotiff_path is set and the
/// zero is known, the GeoTIFF of its occupied band (utmRasterOfMap; the slice z = 0 when nothing is
/// occupied), each atomically.
/// @throws FileError, ValueError as the writers.
void writeLiveMapFiles(const OcTree16& shown, const LiveOutputs& outputs, const LocalOrigin& origin);

}  // namespace sonarmap::live
