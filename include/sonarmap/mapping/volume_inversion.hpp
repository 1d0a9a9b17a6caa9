#pragma once
/// @file volume_inversion.hpp
/// What stands in the water, by inverting the forward model jointly over many beams, once the level
/// surfaces' echoes are explained.
///
/// Each beam's echo is cut into range cells one voxel long; y_c is a cell's mean power over the
/// water's level (1 = water; beam_cells in src/mapping). The forward model explains it as
///     ŷ_c = 1 + s_b B_c + s_s S_c + Σ_v G_cv ρ_v,
/// - B_c, S_c: the energy the seabed plane and the water surface plane return into cell c
///   (BeamForwardModel: the aperture's rays weighted by the two-way pattern, Lambert backscatter,
///   spreading, each ray's echo spread over its footprint's ranges; the nearer plane occludes the
///   farther along each ray), scaled by s_b, s_s ≥ 0 fitted per window (the head's source level,
///   gain and the surfaces' reflectivity are unknown);
/// - G_cv = p_h(h)² p_v(e)² · res² / (r² Ω) (ScattererGain): voxel v's echo in cell c, (h, e) its
///   centre's direction from the beam's axis, ρ_v ≥ 0 its reflectivity (one for every look).
/// Speckle makes a cell's power exponential about its mean, so the maximum-likelihood s and ρ
/// minimise the Itakura–Saito divergence Σ_c y_c/ŷ_c − ln(y_c/ŷ_c) − 1; the multiplicative update
/// of Févotte & Idier (2011, Neural Computation 23(9), β = 0), for each unknown x with gains a_c,
///     x ← x · Σ_c a_c y_c / ŷ_c² / Σ_c a_c / ŷ_c,
/// keeps every unknown ≥ 0 and lowers the divergence. It is the joint inversion of Westman,
/// Gkioulekas and Kaess (ICRA 2020) for an MSIS beam.
///
/// Unknowns of a beam (the voxels v with a G_cv): the voxels whose centre lies in the beam's cone
/// (± `extent_half_widths` half −3 dB widths per plane) in a cell up to the end of its first loud
/// run (from its first echo on, the first cells at least `candidate_level_db` over
/// 1 + s_b B_c + s_s S_c, through gaps of one cell, and two cells more: what lies behind the first
/// surface the beam met is hidden from it), on the water's side of both level planes by more than a voxel (what lies under the
/// seabed or above the water surface, or on them, is the level surfaces', level_surfaces.hpp), and
/// not heard as water by any beam of the window. A voxel is heard as water where it lies in a cell
/// of a beam where the beam proves water (InversionBeam::free_range_m: before its first echo, and
/// nowhere for a beam that heard no echo) and its two-way pattern there is at least
/// `free_pattern_db` (the loud core); there a beam's cone is enumerated in that core only. Only
/// voxels in some loud cell are inverted (others have no echo to explain; the update keeps a 0 at 0).
///
/// The cone is enumerated from sample directions precomputed per range cell in the beam's frame (at
/// most 0.7 voxel apart), turned by each beam's pose; a beam's voxels are sorted by Morton code and
/// joined to the window's unknowns by binary search behind a bitset filter (flat arrays, no hash
/// map).
///
/// After the updates a voxel is occupied (the map's hit) when its echo in its loudest look,
/// ρ_v max_c G_cv, is at least `occupied_level_db` over the water; voxels heard as water are free
/// (the map's miss). The window holds beams until their cone's voxel-look pairs may reach
/// `window_pairs` (bounded memory), then is inverted. Deterministic for any thread count: windows
/// close at the same beams, each beam's cone is enumerated alone (the threads share the beams),
/// and every sum runs in one fixed order.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/acoustics/beam_pattern.hpp"
#include "sonarmap/acoustics/forward_model.hpp"
#include "sonarmap/mapping/level_surfaces.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// The inversion's parameters, in physical units.
struct VolumeInversionOptions {
  /// A cell at least this much over its expected level (water and level surfaces), dB, is loud: its
  /// voxels are inverted, and a beam's first loud run hides what lies behind it.
  double candidate_level_db = 3.0;
  /// A voxel is occupied when its echo in its loudest look is at least this over the water, dB.
  double occupied_level_db = 0.0;
  /// A quiet cell before the beam's first echo hears water where the two-way pattern is at least
  /// this (dB, ≤ 0; −1.5: the loud core of a Gaussian beam).
  double free_pattern_db = -1.5;
  /// Multiplicative updates per window, ≥ 1.
  int iterations = 30;
  /// Voxel-look pairs a window's cones may hold before it is inverted (≈ 16 bytes each), ≥ 1.
  std::size_t window_pairs = std::size_t{1} << 24;
  /// The cone's extent around the axis the voxels are sought in, in half −3 dB widths of each plane, > 0.
  double extent_half_widths = 1.25;

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// What the inversion did so far.
struct VolumeInversionStats {
  std::size_t beams = 0;       ///< beams added
  std::size_t windows = 0;     ///< windows inverted
  std::size_t candidates = 0;  ///< voxels inverted, summed over the windows
  std::size_t pairs = 0;       ///< voxel-look pairs of the candidates, summed over the windows
  std::size_t occupied = 0;    ///< voxels written occupied
  std::size_t free = 0;        ///< voxels written free
};

/// One beam as the inversion takes it.
struct InversionBeam {
  Eigen::Isometry3d sonar_to_map = Eigen::Isometry3d::Identity();  ///< the head's pose
  double bearing_rad = 0.0;            ///< sonar frame, clockwise from ahead
  std::span<const float> cell_power;   ///< power over the water per range cell of one voxel (NaN: not measured)
  double water_range_m = 0.0;          ///< no echo before here (its first echo less the tolerance): no cell is loud
  /// The beam proves water up to here, ≤ water_range_m: 0 for a beam that heard no echo at all (in
  /// 3D silence is no proof of water: a seabed met at grazing incidence returns 1–3 dB over the
  /// noise, below every threshold; docs/mapping.md, "Free space").
  double free_range_m = 0.0;
  std::optional<LevelPlane> seabed;    ///< the seabed as fitted so far, if any
  std::optional<LevelPlane> surface;   ///< the water surface, if its depth is known
};

/// The joint inversion of one head's beams into an octree (see the file's comment).
class VolumeInversion {
 public:
  /// `pattern`: the head's one-way patterns (its −3 dB widths); `resolution_m`: the map's voxel
  /// edge, which is also the range cell's length; `threads`: how many enumerate the cones (≥ 1;
  /// the result does not depend on it).
  /// @throws ValueError for an invalid pattern or options, a resolution not > 0 and finite, or no thread.
  VolumeInversion(const TransducerPattern& pattern, double resolution_m, const VolumeInversionOptions& options,
                  unsigned threads = 1);
  ~VolumeInversion();

  /// Adds one beam; inverts the window into `map` when it is full.
  void addBeam(const InversionBeam& beam, OcTree16& map);
  /// Inverts the beams added since the last window into `map` (nothing when there are none).
  void flush(OcTree16& map);

  const VolumeInversionStats& stats() const { return stats_; }

 private:
  struct WindowBeam;
  struct Look;
  /// The voxels of `beam`'s cone in its cells [0, cells) with their looks, into `looks` (cleared first);
  /// `levels`: each window cell's expected power from the water and the level surfaces alone.
  void coneLooks(const WindowBeam& beam, std::size_t cells, const OcTree16& map, std::span<const double> levels,
                 std::vector<Look>& looks) const;
  /// The level surfaces' energy per cell of a beam (B_c, S_c of the file's comment), appended.
  void levelEnergy(const InversionBeam& beam, std::size_t cells);

  TransducerPattern pattern_;
  double resolution_m_;
  VolumeInversionOptions options_;
  unsigned threads_;
  BeamForwardModel level_model_;   ///< the forward model the level surfaces' energy comes from
  std::vector<WindowBeam> beams_;
  std::vector<float> cell_power_;  ///< every window beam's cells, one after the other
  std::vector<double> seabed_energy_, surface_energy_;  ///< B_c and S_c, as cell_power_
  std::vector<double> seabed_scratch_, surface_scratch_;  ///< levelEnergy's per-beam energy
  std::size_t estimated_pairs_ = 0;
  double seabed_scale_ = -1.0, surface_scale_ = -1.0;  ///< s_b, s_s of the last window (< 0: none yet)
  std::vector<std::vector<Eigen::Vector3d>> cone_;  ///< per cell index: the cone's sample offsets, beam frame
  std::vector<std::vector<Eigen::Vector3d>> cone_core_;  ///< per cell index: those of the loud core (and a margin)
  VolumeInversionStats stats_;
};

}  // namespace sonarmap
