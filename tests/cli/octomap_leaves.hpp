#pragma once
// What OctoMap itself (the test-only dependency, not this project's reader) finds in a .bt the
// tool wrote: the CLI tests check positions in the file's frame with it.

#include <gtest/gtest.h>

#include <octomap/OcTree.h>

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace sonarmap::test {

/// Occupied leaf centres of the .bt at `path`, read by OctoMap (x, y, z in the file's frame).
inline std::vector<Eigen::Vector3d> occupiedCentres(const std::filesystem::path& path) {
  octomap::OcTree tree(0.1);
  if (!tree.readBinary(path.string())) ADD_FAILURE() << "OctoMap cannot read " << path;
  std::vector<Eigen::Vector3d> centres;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (tree.isNodeOccupied(*it)) centres.emplace_back(it.getX(), it.getY(), it.getZ());
  }
  return centres;
}

}  // namespace sonarmap::test
