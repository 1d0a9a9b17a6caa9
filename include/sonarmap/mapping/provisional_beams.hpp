#pragma once
/// @file provisional_beams.hpp
/// The beams live mapping shows before their sweep is final (OnlineMapper with
/// OnlineIntegration::kProvisionalBeams): each beam, already detected, is integrated on its own
/// (SonarMapper::integrateBeams) into a small map of the head's sweep it belongs to. The layer is
/// drawn over the committed map (overlay) and a sweep's beams are dropped once the committed map
/// holds them (dropBefore), so the committed map itself is never touched by a provisional beam.

#include <cstddef>
#include <deque>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/detection/detection.hpp"
#include "sonarmap/mapping/mapper_options.hpp"
#include "sonarmap/mapping/sonar_mapper.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// A finest voxel of the map as shown (the committed map with the provisional layer: overlay)
/// where the layer changes it, and its log-odds there.
struct ShownVoxel {
  OcTree16::KeyType key;
  float log_odds = 0.0F;
};

/// Reads the map as shown in a box without copying it: `map` holds the committed leaves, and
/// `shown` the voxels of the box the provisional layer changes, with their shown log-odds (which
/// replace `map`'s there). Called under the mapper's lock: it must not call the mapper.
using ShownMapVisitor = std::function<void(const OcTree16& map, std::span<const ShownVoxel> shown)>;

class ProvisionalBeams {
 public:
  /// @param options  the committed mapper's options (beam model, sensor model, ...); the layer maps
  ///        at the resolution given to atResolution.
  /// @throws ValueError when `options` is invalid (MapperOptions::validate).
  explicit ProvisionalBeams(const MapperOptions& options);

  /// The committed map's resolution, metres: the layer's from now on (the beams shown so far are
  /// integrated again at it when it changes: the committed map coarsened).
  /// @throws ValueError when it is not finite and > 0.
  void atResolution(double resolution_m);
  std::optional<double> resolution_m() const { return resolution_m_; }

  /// Shows beam `index` (its place in the stream; increasing from call to call): `row` is its polar
  /// row as the detector saw it, `detection` what was found in it, `pose` the sonar in the map frame
  /// (nullopt: no navigation at its time, nothing drawn). `starts_sweep`: the beam begins a new
  /// sweep of the head (SweepSplitter), whose beams are then dropped together.
  /// @throws ValueError before atResolution, for an index not after the previous one, or a row
  ///         that is not one beam.
  void add(std::size_t index, bool starts_sweep, PolarImage row, const BeamDetection& detection,
           const std::optional<Eigen::Isometry3d>& pose);

  /// Drops the beams before `index` (the committed map now holds them); a sweep cut by `index` is
  /// integrated again from its remaining beams.
  void dropBefore(std::size_t index);
  /// Drops every beam.
  void clear() { sweeps_.clear(); }

  /// Beams shown.
  std::size_t size() const;

  /// Adds the layer's log-odds to `map` leaf by leaf, sweep after sweep (each leaf's sum clamped as
  /// an update is), as integrating the shown beams into it would, nearly: a beam's updates are
  /// summed in its sweep's map first. `map` must have the layer's resolution (a layer without beams
  /// changes nothing).
  /// @throws ValueError when the resolutions differ and the layer is not empty.
  void overlay(OcTree16& map) const;
  /// The voxels of the key box [min_key, max_key] the layer changes, with the log-odds overlay()
  /// would give them on `map` (each voxel's value in `map`, 0 where unknown, updated sweep after
  /// sweep with the model's clamping), in no particular order. Cost: the layer's voxels in the box
  /// and one search of `map` each.
  /// @throws ValueError as overlay().
  std::vector<ShownVoxel> shownVoxels(const OcTree16& map, const OcTree16::KeyType& min_key,
                                      const OcTree16::KeyType& max_key) const;

 private:
  struct ShownBeam {
    std::size_t index = 0;
    PolarImage row;
    BeamDetection detection;
    std::optional<Eigen::Isometry3d> pose;
  };
  struct Sweep {
    std::vector<ShownBeam> beams;
    SonarMapper mapper;  ///< the sweep's beams, each integrated on its own
  };
  /// A new sweep at the layer's resolution.
  Sweep emptySweep() const;
  void integrate(Sweep& sweep, const ShownBeam& beam) const;
  /// `sweep` rebuilt from its beams at index `from` and after, at the layer's resolution.
  Sweep rebuilt(const Sweep& sweep, std::size_t from) const;

  MapperOptions options_;
  std::optional<double> resolution_m_;
  std::deque<Sweep> sweeps_;  ///< oldest first
};

}  // namespace sonarmap
