#include "sonarmap/mapping/map_frame.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kCommentPrefix = "sonarmap map frame: ";
constexpr std::string_view kOriginPrefix = "sonarmap map origin: ";
constexpr std::string_view kGeodeticPrefix = "sonarmap geodetic origin: ";

/// Moves every leaf of `map` by the signed permutation `rotation` (entries 0, ±1).
OcTree16 permuted(const OcTree16& map, const Eigen::Matrix3d& rotation) {
  std::array<int, 3> source{};
  std::array<bool, 3> negate{};
  for (int axis = 0; axis < 3; ++axis) {
    for (int from = 0; from < 3; ++from) {
      if (rotation(axis, from) != 0.0) {
        source[axis] = from;
        negate[axis] = rotation(axis, from) < 0.0;
      }
    }
  }
  OcTree16 out(map.resolution_m(), map.options());
  constexpr long kKeys = 1L << 16;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const long edge = static_cast<long>(leaf.edgeVoxels());
    Key16 key;
    for (int axis = 0; axis < 3; ++axis) {
      const long k = leaf.key[static_cast<std::size_t>(source[axis])];
      // The lowest corner of the negated cube [k, k + edge) is 2^16 − (k + edge).
      key[static_cast<std::size_t>(axis)] = static_cast<Key16::Index>(negate[axis] ? kKeys - k - edge : k);
    }
    out.updateCube(key, leaf.depth, leaf.log_odds);
  });
  out.updateInnerOccupancy();
  return out;
}

}  // namespace

std::vector<Eigen::Vector3d> pointsInMapFrame(const std::vector<Eigen::Vector3d>& points_m, MapFrame frame) {
  const Eigen::Matrix3d rotation = nwuToMapFrame(frame);
  std::vector<Eigen::Vector3d> out;
  out.reserve(points_m.size());
  for (const Eigen::Vector3d& p : points_m) out.push_back(rotation * p);
  return out;
}

OcTree16 mapInFrame(const OcTree16& map, MapFrame frame) { return permuted(map, nwuToMapFrame(frame)); }

OcTree16 mapFromFrame(const OcTree16& map, MapFrame frame) {
  return permuted(map, nwuToMapFrame(frame).transpose());
}

std::string mapFrameComment(MapFrame frame) { return std::string(kCommentPrefix) + mapFrameDescription(frame); }

std::optional<MapFrame> mapFrameOfComments(const std::vector<std::string>& comments) {
  for (const std::string& comment : comments) {
    if (!comment.starts_with(kCommentPrefix)) continue;
    const std::string_view name = std::string_view(comment).substr(kCommentPrefix.size(), 3);
    for (MapFrame frame : {MapFrame::kEnu, MapFrame::kNed, MapFrame::kNwu}) {
      if (name == mapFrameName(frame)) return frame;
    }
  }
  return std::nullopt;
}

std::string mapOriginComment(const Eigen::Vector3d& origin_ned_m) {
  char text[160];
  std::snprintf(text, sizeof text, "%.17g %.17g %.17g m (north, east, down of the navigation's frame)", origin_ned_m.x(),
                origin_ned_m.y(), origin_ned_m.z());
  return std::string(kOriginPrefix) + text;
}

Eigen::Vector3d mapOriginOfComments(const std::vector<std::string>& comments) {
  for (const std::string& comment : comments) {
    if (!comment.starts_with(kOriginPrefix)) continue;
    std::istringstream numbers(comment.substr(kOriginPrefix.size()));
    Eigen::Vector3d origin_ned_m;
    if (!(numbers >> origin_ned_m.x() >> origin_ned_m.y() >> origin_ned_m.z()) || !origin_ned_m.allFinite()) {
      throw ValueError("map header line '" + comment + "': expected three finite numbers, north east down in metres");
    }
    return origin_ned_m;
  }
  return Eigen::Vector3d::Zero();
}

std::string mapGeodeticComment(const GeodeticPoint& map_zero) {
  requireGeodetic(map_zero, "the map's geodetic origin");
  // 1e-9° is 0.1 mm on the Earth, as is 1e-4 m: finer digits are the estimate's rounding noise.
  const auto decimals = [](double value, int places) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", places, value);
    std::string out(text);
    out.erase(out.find_last_not_of('0') + 1);
    if (out.back() == '.') out.pop_back();
    return out == "-0" ? std::string("0") : out;
  };
  return std::string(kGeodeticPrefix) + decimals(map_zero.latitude_deg, 9) + " " +
         decimals(map_zero.longitude_deg, 9) + " " + decimals(map_zero.height_m, 4) +
         " (latitude, longitude in degrees, height in metres above the WGS84 ellipsoid of the map's zero)";
}

std::optional<GeodeticPoint> geodeticOriginOfComments(const std::vector<std::string>& comments) {
  for (const std::string& comment : comments) {
    if (!comment.starts_with(kGeodeticPrefix)) continue;
    std::istringstream numbers(comment.substr(kGeodeticPrefix.size()));
    GeodeticPoint point;
    if (!(numbers >> point.latitude_deg >> point.longitude_deg >> point.height_m)) {
      throw ValueError("map header line '" + comment + "': expected latitude, longitude (degrees) and height (metres)");
    }
    requireGeodetic(point, "map header line '" + comment + "'");
    return point;
  }
  return std::nullopt;
}

std::vector<std::string> mapHeaderComments(MapFrame frame, const Eigen::Vector3d& origin_ned_m,
                                           const std::optional<GeodeticPoint>& map_zero) {
  std::vector<std::string> comments{mapFrameComment(frame)};
  if (!origin_ned_m.isZero(0.0)) comments.push_back(mapOriginComment(origin_ned_m));
  if (map_zero) comments.push_back(mapGeodeticComment(*map_zero));
  return comments;
}

void writeMapFileInFrame(const OcTree16& map, const std::string& path, MapFrame frame, const Eigen::Vector3d& origin_ned_m,
                         const std::optional<GeodeticPoint>& map_zero) {
  writeMapFile(frame == MapFrame::kNwu ? map : mapInFrame(map, frame), path,
               mapHeaderComments(frame, origin_ned_m, map_zero));
}

FramedMap readMapFileToNwu(const std::string& path, const OctreeOptions& options) {
  const std::vector<std::string> comments = readMapFileHeader(path).comments;
  const std::optional<MapFrame> named = mapFrameOfComments(comments);
  const MapFrame frame = named.value_or(MapFrame::kNwu);
  const Eigen::Vector3d origin_ned_m = mapOriginOfComments(comments);
  const std::optional<GeodeticPoint> geodetic = geodeticOriginOfComments(comments);
  OcTree16 map = readMapFile(path, options);
  if (frame == MapFrame::kNwu) return {std::move(map), frame, named.has_value(), origin_ned_m, geodetic};
  return {mapFromFrame(map, frame), frame, named.has_value(), origin_ned_m, geodetic};
}

}  // namespace sonarmap
