/// @file volume_inversion.cpp
/// The joint inversion of a window of beams (see volume_inversion.hpp).

#include "sonarmap/mapping/volume_inversion.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>

#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/core/errors.hpp"
#include "../algorithms/on_threads.hpp"
#include "../algorithms/radix_sort.hpp"

namespace sonarmap {

void VolumeInversionOptions::validate() const {
  const auto finite = [](const char* field, double value) {
    if (!std::isfinite(value)) throw ValueError(std::string("volume inversion: ") + field + " must be finite");
  };
  finite("candidate_level_db", candidate_level_db);
  finite("occupied_level_db", occupied_level_db);
  finite("free_pattern_db", free_pattern_db);
  if (free_pattern_db > 0.0) throw ValueError("volume inversion: free_pattern_db must be ≤ 0 dB");
  if (iterations < 1) throw ValueError("volume inversion: iterations must be at least 1");
  if (window_pairs < 1) throw ValueError("volume inversion: window_pairs must be at least 1");
  if (!(std::isfinite(extent_half_widths) && extent_half_widths > 0.0)) {
    throw ValueError("volume inversion: extent_half_widths must be a finite number > 0");
  }
}

namespace {
const VolumeInversionOptions& validated(const VolumeInversionOptions& options) {
  options.validate();
  return options;
}

/// Rays of the aperture grid the level surfaces' energy is computed with, per plane.
constexpr int kLevelRaysAcross = 3, kLevelRaysInElevation = 41;
/// The level model's bins: more than any beam's cells (a beam's energy vector is cut to its cells).
constexpr int kLevelModelCells = 1 << 20;

ForwardModelHead levelHead(const TransducerPattern& pattern, double resolution_m) {
  ForwardModelHead head;
  head.horizontal_width_rad = pattern.horizontal.width_rad;
  head.vertical_width_rad = pattern.vertical.width_rad;
  head.pattern = pattern;
  head.horizontal = ApertureSampling{kLevelRaysAcross, 1.5};
  head.vertical = ApertureSampling{kLevelRaysInElevation, 1.5};
  head.bins = kLevelModelCells;
  head.range_m = kLevelModelCells * resolution_m;
  return head;
}

/// Look flags, in Look::flags.
constexpr std::uint8_t kLoud = 1, kWater = 2;

/// Calls work(i) for i in [0, n) on `threads` threads (each i on one thread; errors rethrown).
template <class Work>
void parallelFor(std::size_t n, unsigned threads, Work&& work) {
  threads = static_cast<unsigned>(std::clamp<std::size_t>(n, 1, threads));
  runOnThreads(threads, [&](unsigned t) {
    for (std::size_t i = t; i < n; i += threads) work(i);
  });
}

/// Sorts `codes` ascending and drops repeats; `scratch` is the sort's working memory.
void sortUnique(std::vector<std::uint64_t>& codes, std::vector<std::uint64_t>& scratch) {
  radixSortHighBits(codes, 0, scratch);
  codes.erase(std::unique(codes.begin(), codes.end()), codes.end());
}

/// The multiplicative Itakura–Saito factor Σ a y/ŷ² / Σ a/ŷ of an unknown from its sums.
double isFactor(double numerator, double denominator) { return denominator > 0.0 ? numerator / denominator : 1.0; }
}  // namespace

struct VolumeInversion::WindowBeam {
  Eigen::Matrix3d beam_to_map;  ///< the sonar's rotation times the bearing's (x along the beam's axis)
  Eigen::Vector3d origin_m;
  std::size_t first_cell = 0;   ///< index of its cell 0 in cell_power_
  std::size_t cells = 0;
  double water_range_m = 0.0;
  std::optional<LevelPlane> seabed, surface;
  std::size_t used_cells = 0;   ///< flush: cells before what its first loud run hides
  std::size_t water_cells = 0;  ///< flush: cells before its first echo
  double free_range_m = 0.0;
  std::size_t free_cells = 0;   ///< flush: cells where it proves water
};

/// One voxel seen in one cell of one beam: the forward model's G_cv.
struct VolumeInversion::Look {
  std::uint64_t code;  ///< the voxel's Morton code
  std::uint32_t cell;  ///< index into cell_power_
  float gain;          ///< G_cv
  std::uint8_t flags;  ///< kLoud, kWater
};

VolumeInversion::VolumeInversion(const TransducerPattern& pattern, double resolution_m,
                                 const VolumeInversionOptions& options, unsigned threads)
    : pattern_(pattern),
      resolution_m_(resolution_m),
      options_(validated(options)),
      threads_(threads),
      level_model_(levelHead(pattern, std::isfinite(resolution_m) && resolution_m > 0.0 ? resolution_m : 1.0)) {
  pattern_.validate();
  if (!(std::isfinite(resolution_m) && resolution_m > 0.0)) {
    throw ValueError("volume inversion: resolution_m must be a finite number > 0, got " + std::to_string(resolution_m));
  }
  if (threads == 0) throw ValueError("volume inversion: needs at least one thread");
}

VolumeInversion::~VolumeInversion() = default;

void VolumeInversion::levelEnergy(const InversionBeam& beam, std::size_t cells) {
  // Each aperture ray meets the nearer of the two planes (the other is hidden behind it).
  std::vector<double>& seabed = seabed_scratch_;
  std::vector<double>& surface = surface_scratch_;
  seabed.assign(cells, 0.0);
  surface.assign(cells, 0.0);
  const Eigen::Vector3d origin = beam.sonar_to_map.translation();
  const double reach_m = static_cast<double>(cells) * resolution_m_;
  for (const ApertureRay& ray : level_model_.rays()) {
    const RayCell cell = BeamForwardModel::rayCell(beam.sonar_to_map.linear(), beam.bearing_rad, ray);
    std::optional<ReflectorHit> hit;
    bool on_seabed = false;
    if (beam.seabed) {
      hit = planeHit(beam.seabed->point_m, beam.seabed->normal, 1.0, origin, cell.direction, reach_m);
      on_seabed = hit.has_value();
    }
    if (beam.surface) {
      const std::optional<ReflectorHit> top = planeHit(beam.surface->point_m, beam.surface->normal, 1.0, origin,
                                                       cell.direction, reach_m);
      if (top && (!hit || top->range_m < hit->range_m)) {
        hit = top;
        on_seabed = false;
      }
    }
    if (!hit) continue;
    level_model_.deposit(hit->range_m, level_model_.footprintSpan_m(hit->range_m, hit->normal, cell),
                         level_model_.directEchoEnergy(ray, *hit, cell), on_seabed ? seabed : surface);
  }
  seabed_energy_.insert(seabed_energy_.end(), seabed.begin(), seabed.end());
  surface_energy_.insert(surface_energy_.end(), surface.begin(), surface.end());
}

void VolumeInversion::addBeam(const InversionBeam& beam, OcTree16& map) {
  const Eigen::Matrix3d bearing = Eigen::AngleAxisd(beam.bearing_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  WindowBeam window_beam{beam.sonar_to_map.linear() * bearing, beam.sonar_to_map.translation(), cell_power_.size(),
                         beam.cell_power.size(), beam.water_range_m, beam.seabed, beam.surface};
  window_beam.free_range_m = std::min(beam.free_range_m, beam.water_range_m);
  cell_power_.insert(cell_power_.end(), beam.cell_power.begin(), beam.cell_power.end());
  levelEnergy(beam, beam.cell_power.size());
  beams_.push_back(window_beam);
  ++stats_.beams;
  // The cone's voxels up to the beam's end: (2H)(2E) r³ / 3 over a voxel's volume.
  const double reach_cells = static_cast<double>(beam.cell_power.size());
  estimated_pairs_ += static_cast<std::size_t>(options_.extent_half_widths * options_.extent_half_widths *
                                               pattern_.horizontal.width_rad * pattern_.vertical.width_rad *
                                               reach_cells * reach_cells * reach_cells / 3.0);
  if (estimated_pairs_ >= options_.window_pairs) flush(map);
}

void VolumeInversion::coneLooks(const WindowBeam& beam, std::size_t cells, const OcTree16& map,
                                std::span<const double> levels, std::vector<Look>& looks) const {
  const double half_h_rad = 0.5 * options_.extent_half_widths * pattern_.horizontal.width_rad;
  const double half_e_rad = 0.5 * options_.extent_half_widths * pattern_.vertical.width_rad;
  const ScattererGain gain_of(pattern_, resolution_m_ * resolution_m_);
  const double core_share = powerOfLevel(options_.free_pattern_db);
  const double loud_share = powerOfLevel(options_.candidate_level_db);
  thread_local std::vector<std::uint64_t> codes;
  codes.clear();
  looks.clear();
  for (std::size_t k = 0; k < cells; ++k) {
    if (std::isnan(cell_power_[beam.first_cell + k])) continue;
    // Where it proves water only the loud core can hear it (and a quiet look there adds little).
    for (const Eigen::Vector3d& offset : (k < beam.free_cells ? cone_core_[k] : cone_[k])) {
      if (const auto key = map.coder().keyOf(beam.origin_m + beam.beam_to_map * offset)) codes.push_back(mortonCode(*key));
    }
  }
  thread_local std::vector<std::uint64_t> scratch;
  sortUnique(codes, scratch);
  const Eigen::Matrix3d map_to_beam = beam.beam_to_map.transpose();
  const double surface_margin_m = resolution_m_;  // the level surfaces' voxels, and beyond
  const auto wet = [&](const std::optional<LevelPlane>& plane, const Eigen::Vector3d& centre) {
    return !plane || plane->normal.dot(centre - plane->point_m) > surface_margin_m;
  };
  for (const std::uint64_t code : codes) {
    const Eigen::Vector3d centre = map.coder().centerOf(keyOfMortonCode<16>(code));
    const Eigen::Vector3d in_beam = map_to_beam * (centre - beam.origin_m);
    const double range_m = in_beam.norm();
    if (!(range_m > 0.0)) continue;
    const auto k = static_cast<std::size_t>(range_m / resolution_m_);
    if (k >= cells) continue;
    const std::size_t cell = beam.first_cell + k;
    const float power = cell_power_[cell];
    if (std::isnan(power)) continue;
    const double e_rad = std::asin(std::clamp(in_beam.z() / range_m, -1.0, 1.0));
    const double h_rad = std::atan2(in_beam.y(), in_beam.x());
    if (std::abs(h_rad) > half_h_rad || std::abs(e_rad) > half_e_rad) continue;
    if (!wet(beam.seabed, centre) || !wet(beam.surface, centre)) continue;  // the level surfaces' or hidden by them
    std::uint8_t flags = 0;
    if (k < beam.water_cells) {  // before the first echo: never loud, whatever the speckle
      if (k < beam.free_cells && gain_of.twoWay(h_rad, e_rad) >= core_share) flags |= kWater;
    } else if (power >= loud_share * levels[cell]) {
      flags |= kLoud;
    }
    looks.push_back({code, static_cast<std::uint32_t>(cell), static_cast<float>(gain_of(h_rad, e_rad, range_m)), flags});
  }
}

void VolumeInversion::flush(OcTree16& map) {
  if (beams_.empty()) return;
  const std::size_t total_cells = cell_power_.size();
  // 1. The level surfaces' scales, fitted with every ρ at 0 (from the last window's, or least squares).
  const auto fitted = [&](const std::vector<double>& energy, double last) {
    if (last > 0.0) return last;
    double yb = 0.0, bb = 0.0, largest = 0.0;
    for (std::size_t c = 0; c < total_cells; ++c) {
      if (std::isnan(cell_power_[c])) continue;
      yb += energy[c] * std::max(0.0, cell_power_[c] - 1.0);
      bb += energy[c] * energy[c];
      largest = std::max(largest, energy[c]);
    }
    if (!(bb > 0.0)) return 0.0;
    return std::max(yb / bb, 1e-3 / largest);
  };
  seabed_scale_ = fitted(seabed_energy_, seabed_scale_);
  surface_scale_ = fitted(surface_energy_, surface_scale_);
  std::vector<double> predicted(total_cells, 1.0);
  const auto predictLevels = [&] {
    for (std::size_t c = 0; c < total_cells; ++c) {
      predicted[c] = 1.0 + seabed_scale_ * seabed_energy_[c] + surface_scale_ * surface_energy_[c];
    }
  };
  const auto updateLevels = [&] {  // s_b, s_s by their multiplicative updates, from `predicted`
    double nb = 0.0, db = 0.0, ns = 0.0, ds = 0.0;
    for (std::size_t c = 0; c < total_cells; ++c) {
      const double y = cell_power_[c];
      if (std::isnan(y)) continue;
      const double inverse = 1.0 / predicted[c];
      nb += seabed_energy_[c] * y * inverse * inverse;
      db += seabed_energy_[c] * inverse;
      ns += surface_energy_[c] * y * inverse * inverse;
      ds += surface_energy_[c] * inverse;
    }
    seabed_scale_ *= isFactor(nb, db);
    surface_scale_ *= isFactor(ns, ds);
  };
  for (int iteration = 0; iteration < 10; ++iteration) {
    predictLevels();
    updateLevels();
  }
  predictLevels();
  // 2. Each beam's cells up to its first loud run's end (through one-cell gaps, and two cells more),
  // those before its first echo and those where it proves water.
  const double loud_share = powerOfLevel(options_.candidate_level_db);
  std::size_t longest = 0;
  for (WindowBeam& beam : beams_) {
    beam.water_cells = std::min(beam.cells, static_cast<std::size_t>(std::max(0.0, beam.water_range_m / resolution_m_)));
    beam.free_cells = std::min(beam.water_cells, static_cast<std::size_t>(std::max(0.0, beam.free_range_m / resolution_m_)));
    std::size_t k = beam.water_cells;
    const auto loud = [&](std::size_t i) {
      const float y = cell_power_[beam.first_cell + i];
      return !std::isnan(y) && y >= loud_share * predicted[beam.first_cell + i];
    };
    while (k < beam.cells && !loud(k)) ++k;
    while (k < beam.cells && (loud(k) || (k + 1 < beam.cells && loud(k + 1)))) ++k;
    beam.used_cells = std::min(beam.cells, k + 2);
    longest = std::max(longest, beam.used_cells);
  }
  // 3. The cone's sample offsets per cell (beam frame), at most 0.7 voxel apart.
  const double half_h_rad = 0.5 * options_.extent_half_widths * pattern_.horizontal.width_rad;
  const double half_e_rad = 0.5 * options_.extent_half_widths * pattern_.vertical.width_rad;
  const ScattererGain core_gain(pattern_, 1.0);
  // The core's samples with a margin of a sample step (a voxel whose centre is in the core).
  const double core_floor = 0.5 * powerOfLevel(options_.free_pattern_db);
  for (std::size_t k = cone_.size(); k < longest; ++k) {
    std::vector<Eigen::Vector3d>& offsets = cone_.emplace_back();
    std::vector<Eigen::Vector3d>& core = cone_core_.emplace_back();
    const double range_m = (static_cast<double>(k) + 0.5) * resolution_m_;
    const double step_rad = 0.7 * resolution_m_ / range_m;
    const int steps_h = static_cast<int>(std::ceil(half_h_rad / step_rad));
    const int steps_e = static_cast<int>(std::ceil(half_e_rad / step_rad));
    for (int i = -steps_h; i <= steps_h; ++i) {
      const double h_rad = std::clamp(i * step_rad, -half_h_rad, half_h_rad);
      for (int j = -steps_e; j <= steps_e; ++j) {
        const double e_rad = std::clamp(j * step_rad, -half_e_rad, half_e_rad);
        offsets.emplace_back(range_m * Eigen::Vector3d(std::cos(e_rad) * std::cos(h_rad),
                                                       std::cos(e_rad) * std::sin(h_rad), std::sin(e_rad)));
        if (core_gain.twoWay(h_rad, e_rad) >= core_floor) core.push_back(offsets.back());
      }
    }
  }
  // 4. Every beam's looks, the beams shared among the threads (`predicted` holds the levels alone).
  std::vector<std::vector<Look>> looks(beams_.size());
  parallelFor(beams_.size(), threads_,
              [&](std::size_t b) { coneLooks(beams_[b], beams_[b].used_cells, map, predicted, looks[b]); });
  // 5. The unknowns: voxels of a loud cell that no beam heard as water.
  std::vector<std::uint64_t> candidates, water;
  for (const std::vector<Look>& beam_looks : looks) {
    for (const Look& look : beam_looks) {
      if (look.flags & kLoud) candidates.push_back(look.code);
      if (look.flags & kWater) water.push_back(look.code);
    }
  }
  std::vector<std::uint64_t> scratch;
  sortUnique(candidates, scratch);
  sortUnique(water, scratch);
  std::vector<std::uint64_t> unknowns;
  std::set_difference(candidates.begin(), candidates.end(), water.begin(), water.end(), std::back_inserter(unknowns));
  // A bitset of the unknowns' hashed codes rejects most looks before the binary search.
  constexpr std::size_t kFilterBits = std::size_t{1} << 22;
  const auto hashed = [](std::uint64_t code) { return (code * 0x9E3779B97F4A7C15ull) >> (64 - 22); };
  std::vector<std::uint64_t> filter(kFilterBits / 64, 0);
  for (const std::uint64_t code : unknowns) filter[hashed(code) >> 6] |= std::uint64_t{1} << (hashed(code) & 63);
  struct Pair {
    std::uint32_t voxel, cell;
    float gain;
  };
  std::vector<Pair> pairs;
  for (std::vector<Look>& beam_looks : looks) {
    for (const Look& look : beam_looks) {
      const std::uint64_t h = hashed(look.code);
      if (!(filter[h >> 6] >> (h & 63) & 1)) continue;
      const auto found = std::lower_bound(unknowns.begin(), unknowns.end(), look.code);
      if (found == unknowns.end() || *found != look.code) continue;
      pairs.push_back({static_cast<std::uint32_t>(found - unknowns.begin()), look.cell, look.gain});
    }
    std::vector<Look>().swap(beam_looks);
  }
  // 6. The multiplicative updates of ρ and the level scales, from every voxel alone explaining the
  // water's level in its loudest look.
  std::vector<double> rho(unknowns.size(), 0.0), best_gain(unknowns.size(), 0.0);
  for (const Pair& pair : pairs) best_gain[pair.voxel] = std::max(best_gain[pair.voxel], double{pair.gain});
  for (std::size_t v = 0; v < rho.size(); ++v) rho[v] = best_gain[v] > 0.0 ? 1.0 / best_gain[v] : 0.0;
  std::vector<double> numerator(rho.size()), denominator(rho.size());
  const auto predict = [&] {
    predictLevels();
    for (const Pair& pair : pairs) predicted[pair.cell] += pair.gain * rho[pair.voxel];
  };
  for (int iteration = 0; iteration < options_.iterations; ++iteration) {
    predict();
    std::fill(numerator.begin(), numerator.end(), 0.0);
    std::fill(denominator.begin(), denominator.end(), 0.0);
    for (const Pair& pair : pairs) {
      const double inverse = 1.0 / predicted[pair.cell];
      numerator[pair.voxel] += pair.gain * cell_power_[pair.cell] * inverse * inverse;
      denominator[pair.voxel] += pair.gain * inverse;
    }
    updateLevels();
    for (std::size_t v = 0; v < rho.size(); ++v) rho[v] *= isFactor(numerator[v], denominator[v]);
  }
  predict();
  // 7. Into the map, in code order: occupied voxels, and free the voxels heard as water.
  const double occupied_power = powerOfLevel(options_.occupied_level_db);
  std::vector<std::uint64_t> occupied;
  for (std::size_t v = 0; v < rho.size(); ++v) {
    if (rho[v] * best_gain[v] >= occupied_power) occupied.push_back(unknowns[v]);
  }
  for (const std::uint64_t code : water) map.updateNode(keyOfMortonCode<16>(code), map.model().miss, true);
  for (const std::uint64_t code : occupied) map.updateNode(keyOfMortonCode<16>(code), map.model().hit, true);
  stats_.free += water.size();
  stats_.occupied += occupied.size();
  stats_.candidates += unknowns.size();
  stats_.pairs += pairs.size();
  ++stats_.windows;
  beams_.clear();
  cell_power_.clear();
  seabed_energy_.clear();
  surface_energy_.clear();
  estimated_pairs_ = 0;
}

}  // namespace sonarmap
