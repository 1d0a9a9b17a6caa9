#pragma once
// The surface voxels of a scene inside a box of keys: the finest voxels whose probe point, their
// centre moved towards the voxel's lower corner by 10⁻⁶ res on every axis, lies within half a voxel
// (res / 2) of a scene surface (sim/scene.hpp, distanceToSurface). The nudge decides the tie of a
// surface lying exactly on the face between two voxels (a plane at z = 0): it counts in the voxel
// whose half-open key interval [k res, (k + 1) res) holds it, not in both or neither as the
// rounding of the centres' distances would decide. Internal to the
// library (eval/ground_truth.cpp's recall and erosion); the brute-force version is the reference
// the tests hold the fast one to.

#include <vector>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/key_coder.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap::detail {

/// Every key k of the inclusive box [lo, hi] (no key when lo > hi on some axis) whose probe point p
/// has distanceToSurface(scene, p) ≤ coder.resolution_m() / 2, found by testing every
/// key of the box (cost: box voxels × primitives). Ordered z, then y, then x, ascending.
std::vector<Key<16>> surfaceVoxelsBruteForce(const KeyCoder<16>& coder, const Scene& scene, const Key<16>& lo,
                                              const Key<16>& hi);

/// The same keys, found hierarchically: the box is halved recursively (along every axis longer than
/// one voxel); a sub-box and a primitive are dropped together when the primitive's distance from
/// the sub-box's centre exceeds the half-diagonal between the sub-box's extreme voxel centres plus
/// res / 2 (and the probe's nudge, and 1 µm against rounding): distanceToSurface is 1-Lipschitz, so no voxel centre of the
/// sub-box is within res / 2 of that primitive. A sub-box no primitive is left for is skipped; the
/// voxels of the smallest sub-boxes (≤ 2 voxels per axis) are tested as in the brute force, against
/// the primitives left, and kept under the identical condition. Cost grows with the surface area in
/// the box (about surface voxels × primitives × log of the box's size), not with its volume.
/// Ordered as the recursion visits them (sort to compare with the brute force).
std::vector<Key<16>> surfaceVoxels(const KeyCoder<16>& coder, const Scene& scene, const Key<16>& lo,
                                   const Key<16>& hi);

}  // namespace sonarmap::detail
