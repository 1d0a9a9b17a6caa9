#pragma once
/// @file map_frame.hpp
/// The frame a map is written and drawn in (MapFrame, nav/map_frame_axes.hpp), chosen by the
/// user: ENU (ROS REP 103/105: x east, y north, z up; the default, so octovis shows it upright and
/// it overlays a ROS `odom` frame) or NED (x north, y east, z down; the navigation's frame).
///
/// The mapper builds its octree in one internal frame, NWU (x north, y west, z up:
/// navigation.hpp's nedToMap), and every public output is converted from it on the way out. Each
/// conversion is a signed permutation of the axes: NWU → ENU is (x, y, z) ↦ (−y, x, z), NWU → NED
/// is (x, y, z) ↦ (x, −y, −z). On a depth-16 key, negating a coordinate is k ↦ 2^16 − 1 − k
/// (the voxel [k, k + 1) · res about the key origin goes to [−k − 1, −k) · res), so the converted
/// tree holds exactly the same voxels and log-odds, pruned leaves included.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/nav/map_frame_axes.hpp"
#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// `points_m` (NWU, metres) in `frame`, each multiplied by nwuToMapFrame(frame).
std::vector<Eigen::Vector3d> pointsInMapFrame(const std::vector<Eigen::Vector3d>& points_m, MapFrame frame);

/// The internal (NWU) map `map` with its voxels in `frame`: every leaf moved exactly (see the file
/// comment), same resolution, options and log-odds; inner nodes recomputed. A leaf of log-odds
/// exactly 0 (present but unknown) is left out: it carries no evidence.
OcTree16 mapInFrame(const OcTree16& map, MapFrame frame);

/// The inverse of mapInFrame: a map in `frame` back in the internal NWU frame.
OcTree16 mapFromFrame(const OcTree16& map, MapFrame frame);

/// The header comment line naming `frame` in map files ("sonarmap map frame: ENU (x east, ...)").
std::string mapFrameComment(MapFrame frame);

/// The frame named by a mapFrameComment line among a file's header `comments`; nullopt when none
/// is (files written before frames were named, or by another tool).
std::optional<MapFrame> mapFrameOfComments(const std::vector<std::string>& comments);

/// The header comment line naming the map's zero as a point of the navigation's own frame (NED
/// metres: north, east, down; local_origin.hpp), written when a navigation far from zero (UTM) was
/// mapped about a local origin: "sonarmap map origin: 4600000 500000 0 m (north, east, down ...)".
/// Positions in the map plus this origin (as NED) are the navigation's coordinates.
std::string mapOriginComment(const Eigen::Vector3d& origin_ned_m);

/// The origin named by a mapOriginComment line among `comments`, NED metres; zero when none is.
/// @throws ValueError for such a line whose three numbers do not read as finite numbers.
Eigen::Vector3d mapOriginOfComments(const std::vector<std::string>& comments);

/// The header comment line placing the map's zero on the Earth (geodetic.hpp): "sonarmap geodetic
/// origin: 43.296124 5.369952 0 (latitude, longitude in degrees, height in metres above the WGS84
/// ellipsoid of the map's zero)", to 1e-9° and 0.1 mm (0.1 mm on the Earth), trailing zeros dropped. The map's frame is the local tangent plane there
/// (x east, y north, z up in ENU; GeographicLib::LocalCartesian), so a point of the map is placed
/// on the Earth by nedToGeodetic(origin, its NED coordinates).
std::string mapGeodeticComment(const GeodeticPoint& map_zero);

/// The point named by a mapGeodeticComment line among `comments`; nullopt when none is.
/// @throws ValueError for such a line whose numbers do not read, or are out of range (requireGeodetic).
std::optional<GeodeticPoint> geodeticOriginOfComments(const std::vector<std::string>& comments);

/// The header comments of a map written in `frame` about `origin_ned_m`: the frame's line
/// (mapFrameComment), then the origin's (mapOriginComment) when the origin is not zero, then the
/// geodetic origin's (mapGeodeticComment) when `map_zero` is given.
std::vector<std::string> mapHeaderComments(MapFrame frame, const Eigen::Vector3d& origin_ned_m,
                                           const std::optional<GeodeticPoint>& map_zero = std::nullopt);

/// Writes the internal (NWU) map `map` to `path` (map_file.hpp: .bt or .ot by extension) in
/// `frame`, its header naming the frame and, when not zero, the local origin `origin_ned_m`
/// (mapHeaderComments).
/// @throws FileError as writeMapFile.
void writeMapFileInFrame(const OcTree16& map, const std::string& path, MapFrame frame,
                         const Eigen::Vector3d& origin_ned_m = Eigen::Vector3d::Zero(),
                         const std::optional<GeodeticPoint>& map_zero = std::nullopt);

/// A map file read back into the internal NWU frame, converted from the frame its header names
/// (NWU when it names none: files written before the frame was named, or by another tool).
struct FramedMap {
  OcTree16 map;     ///< internal NWU frame
  MapFrame frame;   ///< the frame the file was written in
  bool frame_named = false;  ///< whether its header names `frame` (else NWU is assumed)
  Eigen::Vector3d origin_ned_m = Eigen::Vector3d::Zero();  ///< its local origin (mapOriginOfComments)
  std::optional<GeodeticPoint> geodetic_origin;  ///< its zero on the Earth (geodeticOriginOfComments)
};

/// Reads the map file `path` (map_file.hpp) and converts it to the internal NWU frame.
/// @throws FileError, ValueError as readMapFile.
FramedMap readMapFileToNwu(const std::string& path, const OctreeOptions& options = {});

}  // namespace sonarmap
