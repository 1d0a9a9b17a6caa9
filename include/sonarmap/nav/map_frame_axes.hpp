#pragma once
/// @file map_frame_axes.hpp
/// The frames maps and scene files are written in, chosen by the user: ENU (ROS REP 103/105:
/// x east, y north, z up; the default, so octovis shows it upright and it overlays a ROS `odom`
/// frame) or NED (x north, y east, z down; the navigation's frame); and NWU (x north, y west,
/// z up), the mapper's and the simulator's internal frame (navigation.hpp's nedToMap).
///
/// Each frame differs from NWU by a proper rotation that permutes the axes with signs:
/// NWU → ENU is (x, y, z) ↦ (−y, x, z) (90° about z), NWU → NED is (x, y, z) ↦ (x, −y, −z)
/// (180° about x). Converting a coordinate therefore only moves and negates numbers: exact in
/// floating point. Maps (mapping/map_frame.hpp) and scenes (sim/scene_file.hpp) are converted with
/// nwuToMapFrame on the way out and its transpose on the way in.

#include <string>
#include <string_view>

#include <Eigen/Core>

namespace sonarmap {

/// A frame maps and scenes are written in. kNwu is the internal frame (and that of map and scene
/// files written before frames were named); users choose kEnu or kNed.
enum class MapFrame { kEnu, kNed, kNwu };

/// The frame maps and scenes are written in unless the user chooses another.
inline constexpr MapFrame kDefaultMapFrame = MapFrame::kEnu;

/// "ENU", "NED" or "NWU".
std::string_view mapFrameName(MapFrame frame);

/// The frame and its axes, e.g. "ENU (x east, y north, z up)".
std::string mapFrameDescription(MapFrame frame);

/// The frame a user names: "enu" or "ned", any case.
/// @throws ValueError for any other text; the message lists the choices.
MapFrame parseMapFrame(std::string_view text);

/// Rotation taking internal (NWU) coordinates to `frame`'s: a signed permutation matrix whose
/// z row and column are (0, 0, ±1) (every frame's z is vertical), determinant +1.
Eigen::Matrix3d nwuToMapFrame(MapFrame frame);

}  // namespace sonarmap
