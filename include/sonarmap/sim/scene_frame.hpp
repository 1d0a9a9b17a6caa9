#pragma once
/// @file scene_frame.hpp
/// Scenes moved between the internal frame (NWU: x north, y west, z up; scene.hpp) and the frame a
/// user writes a scene file in (ENU or NED, nav/map_frame_axes.hpp), each primitive kept the same
/// solid. Every frame's z is vertical and the frames differ by proper rotations that permute the
/// axes with signs, so only numbers move and change sign: the conversion is exact and a round trip
/// gives back the identical doubles (a −0 is written as 0).
///
/// In a frame F a primitive reads as in scene.hpp with F's axes: a plane's point and normal and a
/// box's centre are F coordinates; a box's yaw turns from F's +x towards F's +y (counter-clockwise
/// seen from above in ENU and NWU, clockwise, a heading from north, in NED) and its sizes are along
/// its own axes; a cylinder's (cx, cy) are F's x, y and z_min_m < z_max_m are along F's z (in NED,
/// depths: the top of a pile is its z_min_m).
///
/// Per primitive (NWU → F): point, normal, centre: p ↦ R p with R = nwuToMapFrame(F). Box: NED
/// negates the yaw (F's y and the turn's sense flip); ENU keeps the yaw and swaps size_x and
/// size_y (the box's second axis, turned by R, lies along the first axis of the same yaw, and a box
/// is symmetric under a half turn about each of its axes). Cylinder: (cx, cy) ↦ R's top-left 2 × 2
/// block times (cx, cy); z range [a, b] ↦ [−b, −a] in NED.

#include "sonarmap/nav/map_frame_axes.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// The internal (NWU) primitive `nwu` in `frame`'s coordinates (file comment). Valid in, valid out.
Primitive primitiveInFrame(const Primitive& nwu, MapFrame frame);

/// The inverse of primitiveInFrame: `framed`, in `frame`'s coordinates, in the internal NWU frame.
Primitive primitiveFromFrame(const Primitive& framed, MapFrame frame);

/// Every primitive of the internal (NWU) `nwu` in `frame` (primitiveInFrame); the reverberation,
/// a level, is kept.
Scene sceneInFrame(const Scene& nwu, MapFrame frame);

/// The inverse of sceneInFrame.
Scene sceneFromFrame(const Scene& framed, MapFrame frame);

}  // namespace sonarmap
