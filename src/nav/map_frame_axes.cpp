/// @file map_frame_axes.cpp
/// Frame names and the rotations from the internal NWU frame (see map_frame_axes.hpp).

#include "sonarmap/nav/map_frame_axes.hpp"

#include <algorithm>
#include <cctype>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

std::string_view mapFrameName(MapFrame frame) {
  switch (frame) {
    case MapFrame::kEnu: return "ENU";
    case MapFrame::kNed: return "NED";
    case MapFrame::kNwu: return "NWU";
  }
  return "NWU";
}

std::string mapFrameDescription(MapFrame frame) {
  switch (frame) {
    case MapFrame::kEnu: return "ENU (x east, y north, z up)";
    case MapFrame::kNed: return "NED (x north, y east, z down)";
    case MapFrame::kNwu: return "NWU (x north, y west, z up)";
  }
  return "NWU (x north, y west, z up)";
}

MapFrame parseMapFrame(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower == "enu") return MapFrame::kEnu;
  if (lower == "ned") return MapFrame::kNed;
  throw ValueError("map frame must be enu (x east, y north, z up) or ned (x north, y east, z down), got '" +
                   std::string(text) + "'");
}

Eigen::Matrix3d nwuToMapFrame(MapFrame frame) {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  if (frame == MapFrame::kEnu) {
    rotation << 0, -1, 0,  //
        1, 0, 0,           //
        0, 0, 1;
  } else if (frame == MapFrame::kNed) {
    rotation = Eigen::Vector3d(1, -1, -1).asDiagonal();
  }
  return rotation;
}

}  // namespace sonarmap
