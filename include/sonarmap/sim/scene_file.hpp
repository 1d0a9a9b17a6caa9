#pragma once
/// @file scene_file.hpp
/// The scene text format: a simulation's ground truth, saved beside its log and read back to
/// evaluate maps.
///
/// Format (UTF-8/ASCII text, one primitive per line, fields separated by spaces or tabs; `#`
/// starts a comment to the end of the line; blank lines are ignored). Metres and radians;
/// reflectivity in [0, 1]. The first line names the frame of every coordinate, as a map file's
/// header does (nav/map_frame_axes.hpp):
///
///     # sonarmap scene: map frame ENU (x east, y north, z up), metres, radians; reflectivity in [0, 1]
///
/// with ENU, NED (x north, y east, z down) or NWU (x north, y west, z up). The reader takes the
/// frame from a line that starts "# sonarmap scene: map frame " before the first primitive; a file
/// without such a line, or whose line goes on with "(x north, y west, z up)" (the header written
/// before frames were named), is NWU, the frame scene files used then. Columns:
///
///     plane    px py pz  nx ny nz                    reflectivity
///     box      cx cy cz  size_x size_y size_z yaw_rad reflectivity
///     cylinder cx cy  radius_m  z_min_m z_max_m       reflectivity
///     reverberation level_db                          (at most once; Scene::reverberation_db)
///
///  - plane: a point on the plane and its normal (non-zero, any length, either sense);
///  - box: centre, edge lengths along the box's own axes (> 0), turn about the vertical from the
///    frame's +x towards its +y (counter-clockwise seen from above in ENU and NWU, clockwise in
///    NED; see Box in scene.hpp);
///  - cylinder: a vertical closed cylinder, axis through (cx, cy), radius > 0, z_max_m > z_min_m
///    along the frame's z (in NED depths: z_min_m is the top).
///
/// Numbers are decimal (std::from_chars syntax: no leading '+'); they must be finite. The writer
/// prints the shortest form that reads back to the identical double, and the frames differ by
/// signed permutations of the axes (scene_frame.hpp), so a scene round-trips exactly in any frame.
/// Example (a tank floor 1.5 m down and a pile 2 m east of the origin):
///
///     # sonarmap scene: map frame ENU (x east, y north, z up), metres, radians; reflectivity in [0, 1]
///     plane 0 0 -1.5  0 0 1  0.3
///     cylinder 2 0 0.2 -1.5 0.5 0.8

#include <istream>
#include <ostream>
#include <string>

#include "sonarmap/nav/map_frame_axes.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Reads a scene from `in`, in the frame its header line names (NWU without one), and returns it in
/// the internal NWU frame (scene.hpp); `source` names it in messages (the file's path).
/// @throws FileError "source: line N: …" for an unknown kind, a second reverberation line, a wrong number of fields, a field
///         that is not a number or not finite, or a primitive that fails validatePrimitive (zero
///         normal, non-positive size or radius, z_max_m ≤ z_min_m, reflectivity outside [0, 1]);
///         for a header line naming a frame other than ENU, NED or NWU, a second header line, or
///         one after the first primitive; "source: …" when reading fails or the text holds no
///         primitive.
Scene readScene(std::istream& in, const std::string& source);

/// Reads the scene file at `path`. @throws FileError as above, or when it cannot be opened.
Scene readScene(const std::string& path);

/// Writes the internal (NWU) `scene` in the format above, its coordinates in `frame` (the frame the
/// user maps in, e.g. `map --map-frame`'s), with the header line naming `frame` and comments
/// describing the columns.
/// @throws ValueError when the scene is empty or a primitive is invalid (validateScene).
void writeScene(std::ostream& out, const Scene& scene, MapFrame frame);

/// Writes `scene` to `path` in `frame` atomically (temporary file + rename, atomic_file.hpp).
/// @throws ValueError as writeScene(ostream); FileError when the file cannot be written.
void writeScene(const std::string& path, const Scene& scene, MapFrame frame);

}  // namespace sonarmap
