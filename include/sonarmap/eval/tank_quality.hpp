#pragma once
/// @file tank_quality.hpp
/// Quality of a 2D map of a rectangular tank (the CRAS data, paper §2.1): do the occupied cells of
/// the slice trace four walls, and is the inside free?

#include <cstddef>

#include "sonarmap/eval/rectangle_fit.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

struct TankMapQuality {
  WallFitReport walls;                 ///< rectangle fitted to the occupied cells of the slice
  std::size_t occupied_cells = 0;      ///< occupied finest voxels in the slice
  std::size_t interior_cells = 0;      ///< voxels of the slice inside the rectangle, shrunk by the wall tolerance
  double interior_free_share = 0.0;    ///< share of the interior voxels that are free, [0, 1]
  double interior_occupied_share = 0.0;///< share of the interior voxels that are occupied (floater, clutter)
};

/// Fits the tank's walls to the occupied voxels of the slice at height `z_m` (map frame) and
/// classifies the voxels inside them.
/// @throws ValueError when the slice has fewer than 8 occupied voxels (see fitRectangle).
/// @throws OutOfMapError when z_m is outside the map.
TankMapQuality evaluateTankMap(const OcTree16& map, double z_m, const WallFitOptions& options = {});

}  // namespace sonarmap
