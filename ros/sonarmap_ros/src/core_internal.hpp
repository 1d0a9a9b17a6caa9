#pragma once
/// @file core_internal.hpp
/// The C++20 parts of the node's core shared between its files (mapping_core.hpp's bridge is
/// implemented over them): the mapper's options from the node's parameters, and the map's data
/// for the topics.

#include "mapping_core.hpp"
#include "sonarmap/mapping/map_frame.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap_ros {

/// The mapper's options: each mapping option by its command-line name (the option table's
/// conversion and checks, as `sonarmap map`), the sonar's beam where none was given (withSonarBeam),
/// and octomap_server's sensor model.
/// @throws sonarmap::ValueError naming the option for a value out of range or of the wrong kind.
sonarmap::MapperOptions coreMapperOptions(const CoreParameters& parameters, const sonarmap::NominalBeam& beam);

/// `map` (already in frame_id's axes) as MapData; `vehicle_z_m` is projected_map's height.
MapData mapData(const sonarmap::OcTree16& map, const CoreParameters& parameters, double vehicle_z_m);

/// `map`'s octomap_msgs/Octomap data: the `.bt` (binary) or `.ot` (full) file's bytes after its
/// text header, as octomap_msgs/conversions.h's binaryMapToMsg / fullMapToMsg make them.
std::vector<std::int8_t> octomapData(const sonarmap::OcTree16& map, bool binary);

}  // namespace sonarmap_ros
