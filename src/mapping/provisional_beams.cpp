/// @file provisional_beams.cpp
/// ProvisionalBeams (provisional_beams.hpp).

#include "sonarmap/mapping/provisional_beams.hpp"

#include <algorithm>
#include <unordered_map>

#include <cmath>
#include <string>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

ProvisionalBeams::ProvisionalBeams(const MapperOptions& options) : options_(options) { options_.validate(); }

void ProvisionalBeams::atResolution(double resolution_m) {
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    throw ValueError("provisional beams: resolution " + std::to_string(resolution_m) + " m is not > 0");
  }
  if (resolution_m_ == resolution_m) return;
  resolution_m_ = resolution_m;
  for (Sweep& sweep : sweeps_) sweep = rebuilt(sweep, 0);
}

ProvisionalBeams::Sweep ProvisionalBeams::emptySweep() const {
  MapperOptions options = options_;
  options.resolution_m = resolution_m_;
  return Sweep{{}, SonarMapper(options)};
}

void ProvisionalBeams::integrate(Sweep& sweep, const ShownBeam& beam) const {
  sweep.mapper.integrateBeams(beam.row, {beam.detection}, {beam.pose});
}

ProvisionalBeams::Sweep ProvisionalBeams::rebuilt(const Sweep& sweep, std::size_t from) const {
  Sweep out = emptySweep();
  for (const ShownBeam& beam : sweep.beams) {
    if (beam.index < from) continue;
    integrate(out, beam);
    out.beams.push_back(beam);
  }
  return out;
}

void ProvisionalBeams::add(std::size_t index, bool starts_sweep, PolarImage row, const BeamDetection& detection,
                           const std::optional<Eigen::Isometry3d>& pose) {
  if (!resolution_m_) throw ValueError("provisional beams: a beam before the layer's resolution is known");
  if (row.rows() != 1) throw ValueError("provisional beams: a row of " + std::to_string(row.rows()) + " beams, not 1");
  if (!sweeps_.empty() && !sweeps_.back().beams.empty() && index <= sweeps_.back().beams.back().index) {
    throw ValueError("provisional beams: beam " + std::to_string(index) + " is not after the last one shown");
  }
  if (starts_sweep || sweeps_.empty()) sweeps_.push_back(emptySweep());
  ShownBeam beam{index, std::move(row), detection, pose};
  integrate(sweeps_.back(), beam);
  sweeps_.back().beams.push_back(std::move(beam));
}

void ProvisionalBeams::dropBefore(std::size_t index) {
  while (!sweeps_.empty() && (sweeps_.front().beams.empty() || sweeps_.front().beams.back().index < index)) {
    sweeps_.pop_front();
  }
  if (!sweeps_.empty() && sweeps_.front().beams.front().index < index) {
    sweeps_.front() = rebuilt(sweeps_.front(), index);
  }
}

std::size_t ProvisionalBeams::size() const {
  std::size_t beams = 0;
  for (const Sweep& sweep : sweeps_) beams += sweep.beams.size();
  return beams;
}

void ProvisionalBeams::overlay(OcTree16& map) const {
  if (size() == 0) return;
  if (map.resolution_m() != *resolution_m_) {
    throw ValueError("provisional beams: a map at " + std::to_string(map.resolution_m()) + " m, the layer at " +
                     std::to_string(*resolution_m_) + " m");
  }
  for (const Sweep& sweep : sweeps_) {
    sweep.mapper.map().forEachLeaf([&map](const LeafView<16>& leaf) {
      if (leaf.depth == OcTree16::kDepth) {
        map.updateNode(leaf.key, leaf.log_odds, true);
      } else {
        map.updateCube(leaf.key, leaf.depth, leaf.log_odds);
      }
    });
  }
  map.updateDirtyInnerOccupancy();
}

std::vector<ShownVoxel> ProvisionalBeams::shownVoxels(const OcTree16& map, const OcTree16::KeyType& min_key,
                                                      const OcTree16::KeyType& max_key) const {
  std::vector<ShownVoxel> shown;
  if (size() == 0) return shown;
  if (map.resolution_m() != *resolution_m_) {
    throw ValueError("provisional beams: a map at " + std::to_string(map.resolution_m()) + " m, the layer at " +
                     std::to_string(*resolution_m_) + " m");
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (min_key[axis] > max_key[axis]) return shown;
  }
  const LogOddsModel& model = map.model();
  // Calls at(x, y, z) for each voxel of `leaf` inside the box.
  const auto forEachVoxelInBox = [&](const LeafView<16>& leaf, auto&& at) {
    const auto edge = static_cast<unsigned>(leaf.edgeVoxels());
    unsigned lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = std::max<unsigned>(leaf.key[axis], min_key[axis]);
      hi[axis] = std::min<unsigned>(leaf.key[axis] + edge - 1, max_key[axis]);
    }
    for (unsigned z = lo[2]; z <= hi[2]; ++z) {
      for (unsigned y = lo[1]; y <= hi[1]; ++y) {
        for (unsigned x = lo[0]; x <= hi[0]; ++x) at(x, y, z);
      }
    }
  };
  const std::size_t nx = max_key[0] - min_key[0] + 1U, ny = max_key[1] - min_key[1] + 1U, nz = max_key[2] - min_key[2] + 1U;
  constexpr std::size_t kDenseVoxels = std::size_t{1} << 20;
  if (nx * ny * nz <= kDenseVoxels) {
    // A small box (a map tile): the map's values and the layer's sums in arrays over the box.
    const auto at = [&](unsigned x, unsigned y, unsigned z) {
      return ((z - min_key[2]) * ny + (y - min_key[1])) * nx + (x - min_key[0]);
    };
    std::vector<float> value(nx * ny * nz, 0.0F);  // unknown: 0, as an update of a new voxel starts
    std::vector<std::uint8_t> changed(value.size(), 0);
    map.forEachLeafInBox(min_key, max_key, [&](const LeafView<16>& leaf) {
      forEachVoxelInBox(leaf, [&](unsigned x, unsigned y, unsigned z) { value[at(x, y, z)] = leaf.log_odds; });
    });
    for (const Sweep& sweep : sweeps_) {
      sweep.mapper.map().forEachLeafInBox(min_key, max_key, [&](const LeafView<16>& leaf) {
        forEachVoxelInBox(leaf, [&](unsigned x, unsigned y, unsigned z) {
          const std::size_t i = at(x, y, z);
          value[i] = model.update(value[i], leaf.log_odds);
          changed[i] = 1;
        });
      });
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (!changed[i]) continue;
      const auto x = static_cast<std::uint16_t>(min_key[0] + i % nx);
      const auto y = static_cast<std::uint16_t>(min_key[1] + (i / nx) % ny);
      const auto z = static_cast<std::uint16_t>(min_key[2] + i / (nx * ny));
      shown.push_back({OcTree16::KeyType{{x, y, z}}, value[i]});
    }
    return shown;
  }
  std::unordered_map<OcTree16::KeyType, std::size_t, KeyHash<16>> index;  // key → its place in `shown`
  for (const Sweep& sweep : sweeps_) {
    sweep.mapper.map().forEachLeafInBox(min_key, max_key, [&](const LeafView<16>& leaf) {
      forEachVoxelInBox(leaf, [&](unsigned x, unsigned y, unsigned z) {
        const OcTree16::KeyType key{{static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), static_cast<std::uint16_t>(z)}};
        const auto [it, fresh] = index.try_emplace(key, shown.size());
        if (fresh) shown.push_back({key, map.search(key).value_or(0.0F)});
        ShownVoxel& voxel = shown[it->second];
        voxel.log_odds = model.update(voxel.log_odds, leaf.log_odds);
      });
    });
  }
  return shown;
}

}  // namespace sonarmap
