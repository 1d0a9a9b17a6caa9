#pragma once
/// @file occupancy_octree.hpp
/// Probabilistic occupancy octree (paper §3.3, §5; Hornung et al. 2013, "OctoMap").
///
/// A tree of depth `Depth` over cubic voxels of `resolution_m`. Leaves carry clamped log-odds
/// updated with eq. (1) of the paper; inner nodes hold the max (default) or mean of their
/// children. Identical leaf siblings are pruned into their parent. With `lazy` set, updates touch
/// leaves only and `updateInnerOccupancy()` fixes every inner value and prunes in one pass (§5.5).
/// Depth 16 uses OctoMap's key layout, so `.bt`/`.ot` files interoperate. Optional change
/// detection records the finest voxels whose occupancy class changed (change_detection.hpp).

#include <array>
#include <cstddef>
#include <optional>

#include <Eigen/Core>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/key_coder.hpp"
#include "sonarmap/core/log_odds.hpp"
#include "sonarmap/octree/change_detection.hpp"
#include "sonarmap/octree/node_pool.hpp"

namespace sonarmap {

/// Behaviour of an OccupancyOctree; defaults are OctoMap's.
struct OctreeOptions {
  OccupancyParams occupancy{};                             ///< sensor model and thresholds (§5.2)
  InnerAggregation aggregation = InnerAggregation::kMax;  ///< inner-node value (§5.3.1)
  bool prune = true;             ///< collapse 8 equal leaf siblings into their parent (§5.4)
  bool lazy = false;             ///< leaves only until updateInnerOccupancy() (§5.5)
  bool stability_check = true;   ///< skip updates of leaves clamped in the update's direction (§5.3)
};

/// Number of nodes of each kind.
struct NodeCounts {
  std::size_t nodes = 0;
  std::size_t inner = 0;
  std::size_t leaves = 0;
};

/// One leaf as seen by forEachLeaf: a finest voxel (depth == Depth) or a pruned node above it.
template <int Depth>
struct LeafView {
  Key<Depth> key;   ///< key of the leaf's lowest corner voxel
  int depth;        ///< 0 (root) … Depth (finest)
  float log_odds;   ///< the leaf's log-odds
  /// Number of finest voxels along one edge of the leaf: 2^(Depth − depth).
  double edgeVoxels() const { return std::ldexp(1.0, Depth - depth); }
  /// Calls visit(key) for every finest voxel of the leaf (edgeVoxels()³ of a pruned one), x fastest,
  /// then y, then z, each key as a Key<Depth>.
  template <class Visit>
  void forEachVoxel(Visit&& visit) const {
    const auto edge = static_cast<unsigned>(edgeVoxels());
    for (unsigned dz = 0; dz < edge; ++dz) {
      for (unsigned dy = 0; dy < edge; ++dy) {
        for (unsigned dx = 0; dx < edge; ++dx) {
          visit(Key<Depth>{{static_cast<std::uint16_t>(key[0] + dx), static_cast<std::uint16_t>(key[1] + dy),
                            static_cast<std::uint16_t>(key[2] + dz)}});
        }
      }
    }
  }
};

template <int Depth = 16>
class OccupancyOctree {
 public:
  using KeyType = Key<Depth>;
  static constexpr int kDepth = Depth;

  /// @param resolution_m edge of a finest voxel in metres.
  /// @throws ValueError if the resolution is not finite and positive or the occupancy parameters
  ///         are invalid (see OccupancyParams::validate).
  explicit OccupancyOctree(double resolution_m, const OctreeOptions& options = {})
      : coder_(resolution_m), options_(options), model_(LogOddsModel::from(options.occupancy)) {}

  // --- updates -------------------------------------------------------------------------------

  /// Adds `delta_log_odds` to the leaf at `key` (creating it, or expanding a pruned parent),
  /// clamps it, and — unless lazy — updates the inner nodes above it and prunes.
  /// @return false when the update was skipped: zero, or the leaf already clamped in the
  ///         update's direction and `stability_check` is on (§5.3); true otherwise.
  bool updateNode(const KeyType& key, float delta_log_odds) { return updateNode(key, delta_log_odds, false); }

  /// As above; with `lazy_eval` the update touches the leaf only even in an eager tree (OctoMap's
  /// `updateNode(key, delta, lazy_eval)`): inner nodes stay stale, and no pruning happens, until
  /// updateInnerOccupancy() or updateDirtyInnerOccupancy(). A lazy tree is lazy either way.
  bool updateNode(const KeyType& key, float delta_log_odds, bool lazy_eval);

  /// Adds `delta_log_odds` to every finest voxel of the node at `depth` (0 … Depth) that contains
  /// `key`, with the result of updateNode(voxel, delta, lazy_eval = true) on each voxel followed by
  /// the inner-node synchronisation: unknown space inside the cube becomes one leaf per largest
  /// unknown node (the leaves pruning would have merged), existing leaves are updated in place.
  /// Leaves only: inner nodes stay stale until updateInnerOccupancy() / updateDirtyInnerOccupancy().
  /// Cost: one descent plus the existing nodes inside the cube. With pruning off or change
  /// detection on it updates voxel by voxel. Used by point-cloud insertion for whole 2³ and 4³
  /// blocks of free space.
  /// @throws ValueError for a voxel-by-voxel cube of more than 2^10 voxels per edge.
  void updateCube(const KeyType& key, int depth, float delta_log_odds);

  /// updateCube for a set of voxels of one brick, the 4 × 4 × 4 voxels of the node at depth
  /// Depth − 2 containing `corner`: bit b of `voxels` is the voxel whose child index is b & 7 at
  /// the finest level and b >> 3 one level up (Morton order). A brick in unknown space is built
  /// at once, its arrays at their final size. Same result and bookkeeping as updateCube.
  void updateBrick(const KeyType& corner, std::uint64_t voxels, float delta_log_odds);

  /// A hit (`occupied`) or miss at `key`, with the sensor model's log-odds.
  bool integrate(const KeyType& key, bool occupied, bool lazy_eval = false) {
    return updateNode(key, occupied ? model_.hit : model_.miss, lazy_eval);
  }

  /// Recomputes inner nodes from their children and prunes (when enabled), in one post-order
  /// pass: the synchronisation of lazy evaluation (§5.5). A lazy tree visits only the subtrees
  /// changed since the last call; an eager tree visits every node (OctoMap's behaviour).
  void updateInnerOccupancy();

  /// Like updateInnerOccupancy(), but visits only subtrees changed by lazy updates in any tree:
  /// enough after updateNode(…, lazy_eval = true) when nothing else edited nodes directly.
  void updateDirtyInnerOccupancy();

  /// Removes every node and every recorded change.
  void clear() {
    pool_.clear();
    changes_.clear();
    cached_levels_ = -1;
  }

  // --- change detection (OctoMap's enableChangeDetection / changedKeys) ----------------------

  /// Starts or stops recording changed voxels. Recorded changes are kept when stopping. Off by
  /// default; when off, an update pays one predictable branch.
  void enableChangeDetection(bool enable) { detect_changes_ = enable; }
  bool isChangeDetectionEnabled() const { return detect_changes_; }
  /// Forgets every recorded change: the current classes become the reference.
  void resetChangeDetection() { changes_.clear(); }
  /// Finest voxels created, or whose occupancy class changed, by updateNode since the last reset
  /// while detection was on. Raw node edits (setLogOdds, file readers) are not recorded.
  const ChangedKeys<Depth>& changedKeys() const { return changes_; }
  std::size_t numChangesDetected() const { return changes_.size(); }

  // --- queries -------------------------------------------------------------------------------

  /// Log-odds of the node containing `key` at `depth` (or of the pruned leaf above it), or
  /// nullopt when that space is unknown. @param depth 0 … Depth.
  std::optional<float> search(const KeyType& key, int depth = Depth) const;

  /// Occupancy of the finest voxel `key`, kUnknown when never observed.
  Occupancy occupancyOf(const KeyType& key) const;

  /// Occupancy at a point in metres (map frame).
  /// @throws OutOfMapError when the point is outside the map or not finite.
  Occupancy occupancyAt(const Eigen::Vector3d& point_m) const { return occupancyOf(coder_.keyOfChecked(point_m)); }

  /// Calls `visit(const LeafView<Depth>&)` for every leaf, in depth-first order (child 0 … 7).
  template <class Visitor>
  void forEachLeaf(Visitor&& visit) const;

  /// Calls `visit(const LeafView<Depth>&)` for every leaf that intersects the box of finest keys
  /// [min_key, max_key] (inclusive on each axis), in depth-first order; subtrees outside the box
  /// are skipped. A pruned leaf that overlaps the box is visited whole (it may extend past it).
  /// Visits nothing when min_key > max_key on some axis (OctoMap's leaf_bbx_iterator).
  template <class Visitor>
  void forEachLeafInBox(const KeyType& min_key, const KeyType& max_key, Visitor&& visit) const;

  /// The same for the box between two points in metres (map frame), corners included.
  /// @throws OutOfMapError when a corner is outside the map or not finite.
  template <class Visitor>
  void forEachLeafInBox(const Eigen::Vector3d& min_point_m, const Eigen::Vector3d& max_point_m, Visitor&& visit) const {
    forEachLeafInBox(coder_.keyOfChecked(min_point_m), coder_.keyOfChecked(max_point_m), visit);
  }

  /// Nodes, inner nodes and leaves, counted by one traversal.
  NodeCounts counts() const;

  /// Makes room for `slots` more node slots (8 bytes each: nodes and children-array headers)
  /// without moving the node pool: one allocation instead of repeated growth and copies before a
  /// large update into unknown space (point-cloud insertion reserves one slot per distinct
  /// voxel it will update, about what dense free space costs). Does not change the tree;
  /// memoryBytes() is unchanged, memoryBytesAllocated() grows. @throws std::bad_alloc.
  void reserve(std::size_t slots) { pool_.reserve(slots); }

  /// Bytes the tree's nodes occupy: 8 bytes per slot in use (the root, and per inner node one
  /// header plus its children array's capacity of 1, 2, 4 or 8 nodes; node_pool.hpp), plus the
  /// tree object. Comparable to OctoMap's `memoryUsage()` (16 B per node, 64 B per inner node).
  std::size_t memoryBytes() const { return pool_.bytesInUse() + sizeof(*this); }
  /// Bytes allocated by the tree, including capacity kept for growth and freed arrays.
  std::size_t memoryBytesAllocated() const { return pool_.bytesAllocated() + sizeof(*this); }
  /// Gives back freed arrays and spare capacity by rewriting the nodes into a fresh vector, depth
  /// first. Done automatically by updateInnerOccupancy() / updateDirtyInnerOccupancy() when more
  /// than four fifths of the slots are free (e.g. after a lazy sync pruned most of the tree).
  /// Invalidates every NodeRef but the root's.
  void shrinkToFit() {
    cached_levels_ = -1;
    pool_.compact();
  }

  bool empty() const { return !pool_.at(kRootRef).exists(); }
  double resolution_m() const { return coder_.resolution_m(); }
  const KeyCoder<Depth>& coder() const { return coder_; }
  const LogOddsModel& model() const { return model_; }
  const OctreeOptions& options() const { return options_; }

  // --- raw node access, for file readers and writers ----------------------------------------

  const OcTreeNode& node(NodeRef ref) const { return pool_.at(ref); }
  /// Reference of child `index` (0…7) of `parent`; kNoNodeRef, a node that does not exist, when
  /// there is no such child.
  NodeRef childRef(const OcTreeNode& parent, unsigned index) const { return pool_.childRef(parent, index); }
  /// Bit i set when child i of `parent` exists.
  unsigned childMask(const OcTreeNode& parent) const { return pool_.childMask(parent); }
  /// Sets an existing node's log-odds, or the root's to create it (NaN removes nothing).
  /// @throws ValueError for kNoNodeRef.
  void setLogOdds(NodeRef ref, float log_odds) {
    if (ref == kNoNodeRef) throw ValueError("setLogOdds on a child that does not exist");
    pool_.at(ref).log_odds = log_odds;
  }
  /// Gives an existing childless node the children in `mask` (bit i: child i), with log-odds 0
  /// and no children. Invalidates C++ references to nodes, not NodeRefs.
  /// @throws ValueError when `ref` is kNoNodeRef or already has children.
  void createChildren(NodeRef ref, unsigned mask);
  /// Inner value of a node from its existing children, by the configured aggregation.
  float aggregateChildren(const OcTreeNode& parent) const;

 private:
  /// What the children of a node say about it, in one pass over them.
  struct ChildSummary {
    float aggregate;    ///< max or mean of the existing children (0 if none exists)
    bool prunable;      ///< all 8 exist, none has children, all have the same log-odds
  };
  ChildSummary summarize(const OcTreeNode& parent) const;
  /// Prunes the inner node `ref` if its children allow it, else sets its aggregate. Clears its
  /// dirty bit unless `keep_dirty` (an eager update through a subtree other lazy updates dirtied).
  /// @return true when it was pruned.
  bool refreshInner(NodeRef ref, bool keep_dirty = false);
  static constexpr int kMaxVoxelwiseCubeLevels = 10;
  int cachedLevels(const KeyType& key) const;
  /// Fills path_ from the root towards `key` through existing nodes, at most to level `target`;
  /// returns the level reached. Creates the root (setting `fresh_from` to 0) when it is missing.
  int descend(const KeyType& key, int target, int& fresh_from);
  /// Creates (or expands pruned leaves into) path_[level + 1 … target]; `fresh_from` becomes the
  /// first level created from unknown space.
  void createPath(const KeyType& key, int level, int target, int& fresh_from);
  /// The update helpers below return whether any value or node changed, and mark dirty only
  /// the inner nodes below which something did.
  bool coveredByStableLeaf(int level, int fresh_from, float delta_log_odds) const;
  bool updateSubtree(NodeRef ref, float delta_log_odds);
  bool updateLeaf(NodeRef leaf, float delta_log_odds);
  void buildFreshBrick(NodeRef brick, std::uint64_t voxels, float log_odds);
  bool mergeBrick(NodeRef brick, std::uint64_t voxels, float delta_log_odds, float fresh);
  bool mergeOctet(NodeRef node, unsigned bits, float delta_log_odds, float fresh);
  /// Key of bit `bit` of the brick holding `corner` (updateBrick's bit order).
  static KeyType brickKey(const KeyType& corner, unsigned bit);
  template <class Visitor>
  void forEachVoxelOfCube(const KeyType& key, int depth, Visitor&& visit);
  void updateAncestors(int fresh_from);
  /// Marks path_[0 … below − 1] dirty.
  void markPathDirty(int below);
  void syncSubtree(NodeRef ref, bool all);
  void shrinkIfMostlyFree();
  template <class Visitor>
  void visitLeavesInBox(NodeRef ref, const KeyType& key, int depth, const KeyType& lo, const KeyType& hi,
                        Visitor& visit) const;
  /// Adds the nodes below `ref`, which has children, and `ref` itself as an inner node.
  void countSubtree(NodeRef ref, NodeCounts& counts) const;

  KeyCoder<Depth> coder_;
  OctreeOptions options_;
  LogOddsModel model_;
  NodePool pool_;
  // Path of the last update (paper §5.3's search, reused): consecutive keys along a ray share
  // their ancestors, so the next descent starts at the deepest common one.
  std::array<NodeRef, Depth + 1> path_{};
  KeyType cached_key_{};
  int cached_levels_ = -1;  ///< levels of path_ valid for cached_key_, −1 = none
  bool detect_changes_ = false;
  ChangedKeys<Depth> changes_;
};

using OcTree16 = OccupancyOctree<16>;
extern template class OccupancyOctree<16>;  // instantiated once, in src/octree/occupancy_octree.cpp

}  // namespace sonarmap

#include "sonarmap/octree/occupancy_octree_impl.hpp"
