#include "sonarmap/io/view_boxes.hpp"

#include <algorithm>
#include <cmath>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// Order of boxes after downsampling: coarse first, then by key (z, y, x).
std::uint64_t sortKey(const ViewBox& box) {
  return (static_cast<std::uint64_t>(box.depth) << 48) | packKey(box.key);
}

/// `boxes` with every box finer than `level` replaced by its ancestor at `level`, duplicates removed.
std::vector<ViewBox> coarsen(const std::vector<ViewBox>& boxes, int level) {
  const auto mask = static_cast<std::uint16_t>(0xFFFFU << (16 - level));
  std::vector<ViewBox> coarse;
  coarse.reserve(boxes.size());
  for (const ViewBox& box : boxes) {
    if (box.depth <= level) {
      coarse.push_back(box);
      continue;
    }
    ViewBox parent{box.key, level};
    for (std::size_t axis = 0; axis < 3; ++axis) parent.key[axis] = static_cast<std::uint16_t>(box.key[axis] & mask);
    coarse.push_back(parent);
  }
  std::sort(coarse.begin(), coarse.end(), [](const ViewBox& a, const ViewBox& b) { return sortKey(a) < sortKey(b); });
  coarse.erase(std::unique(coarse.begin(), coarse.end(),
                           [](const ViewBox& a, const ViewBox& b) { return a.depth == b.depth && a.key == b.key; }),
               coarse.end());
  return coarse;
}

}  // namespace

ViewBoxes collectViewBoxes(const OcTree16& tree, Occupancy occupancy, std::size_t max_boxes) {
  if (max_boxes == 0) throw ValueError("the cap on the boxes to draw must be at least 1");
  if (occupancy == Occupancy::kUnknown) throw ValueError("only occupied or free leaves are drawn as boxes");
  ViewBoxes result;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    if (tree.model().classify(leaf.log_odds) == occupancy) result.boxes.push_back({leaf.key, leaf.depth});
  });
  result.leaves = result.boxes.size();
  // Each level is made from the one below it: a depth-d ancestor of a depth-(d+1) box is the
  // depth-d ancestor of the leaves that box stands for.
  while (result.boxes.size() > max_boxes && result.level > 0) {
    --result.level;
    result.boxes = coarsen(result.boxes, result.level);
  }
  return result;
}

Eigen::Vector3d boxCorner_m(const OcTree16& tree, const ViewBox& box) {
  const double resolution_m = tree.resolution_m();
  Eigen::Vector3d corner_m;
  for (int axis = 0; axis < 3; ++axis) {
    corner_m[axis] = KeyCoder<16>::cellOf(box.key[static_cast<std::size_t>(axis)]) * resolution_m;
  }
  return corner_m;
}

double boxEdge_m(const OcTree16& tree, const ViewBox& box) {
  return std::ldexp(tree.resolution_m(), 16 - box.depth);
}

}  // namespace sonarmap
