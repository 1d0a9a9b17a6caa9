#pragma once
/// @file change_detection.hpp
/// Which finest voxels changed their occupancy class since a reset (OctoMap's change detection:
/// `enableChangeDetection`, `changedKeysBegin()`, a KeyBoolMap of keys).
///
/// A voxel is recorded when an update creates its leaf (it was unknown space) or moves its value
/// across a threshold (free ↔ unknown ↔ occupied). A voxel whose class returns to the one it had at
/// the reset is dropped again; a created voxel stays recorded, as in OctoMap. OctoMap's bool says
/// "created"; here each record says both whether it was created and its class now.

#include <unordered_map>

#include "sonarmap/core/key.hpp"
#include "sonarmap/core/log_odds.hpp"

namespace sonarmap {

/// One finest voxel whose occupancy class differs from the one it had at the last reset.
struct KeyChange {
  bool created = false;                 ///< the leaf did not exist at the reset (unknown space)
  Occupancy before = Occupancy::kUnknown;  ///< class at the reset (kUnknown when created)
  Occupancy now = Occupancy::kUnknown;     ///< class after the latest update
  /// The "now occupied" flag of OctoMap-style consumers.
  bool occupied() const { return now == Occupancy::kOccupied; }
  friend bool operator==(const KeyChange&, const KeyChange&) = default;
};

/// Changed voxels by key.
template <int Depth>
using ChangedKeys = std::unordered_map<Key<Depth>, KeyChange, KeyHash<Depth>>;

/// Records one applied leaf update in `changes`.
/// @param created     the update created the leaf (it was unknown space before)
/// @param before      the leaf's log-odds before the update (ignored when created)
/// @param after       the leaf's log-odds after the update
template <int Depth>
void recordChange(ChangedKeys<Depth>& changes, const LogOddsModel& model, const Key<Depth>& key, bool created,
                  float before, float after) {
  const Occupancy now = model.classify(after);
  if (auto it = changes.find(key); it != changes.end()) {
    it->second.now = now;
    if (!it->second.created && it->second.before == now) changes.erase(it);
    return;
  }
  const Occupancy was = created ? Occupancy::kUnknown : model.classify(before);
  if (created || was != now) changes.emplace(key, KeyChange{created, was, now});
}

}  // namespace sonarmap
