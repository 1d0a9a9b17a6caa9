#pragma once
/// @file resample.hpp
/// An occupancy octree copied to a coarser resolution: what a live map does when its automatic
/// resolution must grow because the user turned the sonar's range up (online_mapper.hpp).

#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// A copy of `map` at `resolution_m`, with the same occupancy parameters and options. Each voxel
/// of the new map gets the largest log-odds of the leaves of `map` that hold its centre, or, for a
/// leaf holding no new voxel's centre (a leaf smaller than the new voxels), of the voxel that holds
/// the leaf's centre: the maximum (OctoMap's max inner-node rule), so an occupied voxel keeps its
/// coarser voxel occupied and nothing unknown becomes known. Inner nodes are brought up to date
/// (updateInnerOccupancy); equal siblings are pruned as the options say. Deterministic: the same
/// map gives the same bytes. Cost: O(leaves + new voxels covered).
/// @param resolution_m  the new voxel edge, metres, ≥ map.resolution_m() (coarsening only).
/// @throws ValueError when `resolution_m` is not finite or finer than the map's.
/// @throws OutOfMapError when a leaf lies outside the new map (a map spanning more than
///         ±32768 new voxels from its origin).
OcTree16 resampledMap(const OcTree16& map, double resolution_m);

}  // namespace sonarmap
