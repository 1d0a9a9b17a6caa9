#pragma once
/// @file scene_file.hpp
/// The scene text format: a simulation's ground truth, saved beside its log and read back to
/// evaluate maps.
///
/// Format (UTF-8/ASCII text, one primitive per line, fields separated by spaces or tabs; `#`
/// starts a comment to the end of the line; blank lines are ignored). Map frame (NWU: x north,
/// y west, z up), metres and radians; reflectivity in [0, 1]:
///
///     plane    px py pz  nx ny nz                    reflectivity
///     box      cx cy cz  size_x size_y size_z yaw_rad reflectivity
///     cylinder cx cy  radius_m  z_min_m z_max_m       reflectivity
///     reverberation level_db                          (at most once; Scene::reverberation_db)
///
///  - plane: a point on the plane and its normal (non-zero, any length, either sense);
///  - box: centre, edge lengths along the box's own axes (> 0), turn about the vertical,
///    counter-clockwise from the map's +x (see Box in scene.hpp);
///  - cylinder: a vertical closed cylinder, axis through (cx, cy), radius > 0, z_max_m > z_min_m.
///
/// Numbers are decimal (std::from_chars syntax: no leading '+'); they must be finite. The writer
/// prints the shortest form that reads back to the identical double, so a scene round-trips
/// exactly. Example:
///
///     # tank floor and a pile
///     plane 0 0 -1.5  0 0 1  0.3
///     cylinder 2 0 0.2 -1.5 0.5 0.8

#include <istream>
#include <ostream>
#include <string>

#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Reads a scene from `in`; `source` names it in messages (the file's path).
/// @throws FileError "source: line N: …" for an unknown kind, a second reverberation line, a wrong number of fields, a field
///         that is not a number or not finite, or a primitive that fails validatePrimitive (zero
///         normal, non-positive size or radius, z_max_m ≤ z_min_m, reflectivity outside [0, 1]);
///         "source: …" when reading fails or the text holds no primitive.
Scene readScene(std::istream& in, const std::string& source);

/// Reads the scene file at `path`. @throws FileError as above, or when it cannot be opened.
Scene readScene(const std::string& path);

/// Writes `scene` in the format above, with a comment header describing the columns.
/// @throws ValueError when the scene is empty or a primitive is invalid (validateScene).
void writeScene(std::ostream& out, const Scene& scene);

/// Writes `scene` to `path` atomically (temporary file + rename, atomic_file.hpp).
/// @throws ValueError as writeScene(ostream); FileError when the file cannot be written.
void writeScene(const std::string& path, const Scene& scene);

}  // namespace sonarmap
