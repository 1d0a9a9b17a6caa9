#pragma once
/// @file progress.hpp
/// How the long library calls (mapping, simulation, evaluation) report their progress.

#include <cstddef>
#include <functional>

namespace sonarmap {

/// Progress callback: (units done, units in total); the unit is the caller's (sweeps, beams,
/// voxels), `done` grows to `total`. An empty function is never called.
using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

}  // namespace sonarmap
