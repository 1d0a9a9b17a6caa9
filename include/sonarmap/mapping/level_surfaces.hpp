#pragma once
/// @file level_surfaces.hpp
/// Level surfaces (the seabed, the water surface) mapped as surfaces: the evidence of every beam
/// whose range cells meet a level surface pooled per map column, where the surface is.
///
/// A level surface is a plane in the map frame (the water surface at a depth sensor's 0; the seabed
/// as fitted across all views so far, SeabedSlope::fitAround in seabed_slope.hpp). A beam's range
/// cell k (ranges [k, k + 1) voxels) meets it where the cell's shell, r_k = (k + ½) · voxel, crosses
/// the plane inside the beam: for each direction φ across the beam's width, the elevation e with
///     r_k · (u(φ, e) · n) = −D,    u(φ, e) = R (cos e cos φ, cos e sin φ, sin e),
/// n the plane's unit normal towards the head, D the head's height over it along n and R the
/// sonar-to-map rotation; solved in closed form (A cos e + B sin e = c), kept for |e| within half
/// the vertical aperture. The crossing's map column (x, y) at the voxel size receives the cell's
/// power over the water, y (beam_cells: 1 = water).
///
/// A column is heard by a sequential test of every look it gets (Wald's SPRT, "Sequential
/// Analysis", 1947): a look's cell is the mean of m bins (its beam's `bins_per_cell`), each
/// exponential about its mean (speckle), so against water (mean 1) a surface heard `level_db` over
/// it (mean μ = 1 + 10^(level/10)) gives the look the log-likelihood ratio
///     λ = m · (y (1 − 1/μ) − ln μ)  nats,
/// summed over the column's looks from every beam and sweep. The column is heard once the sum
/// reaches ln(1 / α), α = `false_alarm`: the likelihood ratio of water is a martingale, so water
/// reaches it with probability at most α however many looks come (Ville's inequality). A grazing
/// seabed, 0–6 dB over the water in each of its 2–7 looks, is heard by their sum where no single
/// bin is (Skolnik 2001, integration of pulses). A heard column's voxel is the plane's height at the
/// look that completed the test.

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap {

/// A level surface: a plane through `point_m` with unit normal `normal` (map frame, pointing
/// towards the water the head is in: up for the seabed, down for the water surface).
struct LevelPlane {
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// The pooled evidence of one level surface (see the file's comment).
class LevelSurfaceEvidence {
 public:
  /// `resolution_m`: the map's voxel edge (the columns' size and the cells' length), > 0;
  /// `level_db`: the surface's level over the water the test is for, dB, finite; `false_alarm`: α,
  /// in (0, 0.5).
  /// @throws ValueError for a value out of range.
  explicit LevelSurfaceEvidence(double resolution_m, double level_db = 0.0, double false_alarm = 1e-3);

  /// Adds the looks of one beam at `plane`: the head at `sonar_to_map`, the beam at `bearing_rad`
  /// (sonar frame, clockwise from ahead) of horizontal width `width_rad` and vertical aperture
  /// `aperture_rad` (−3 dB, radians), its cells' power over the water (NaN: not measured) and the
  /// bins each cell averages (m of the file's comment: the cell's length over the beam's bin length,
  /// at least 1).
  /// @throws ValueError when bins_per_cell is not a finite number ≥ 1.
  void addBeam(const Eigen::Isometry3d& sonar_to_map, double bearing_rad, double width_rad, double aperture_rad,
               std::span<const float> cell_power, double bins_per_cell, const LevelPlane& plane);

  /// Calls visit(point_m) once for every column heard since the last call, at the plane's height
  /// where it was heard (map frame, the column's centre).
  template <class Visit>
  void drainHeard(Visit&& visit) {
    for (const std::uint64_t column : newly_heard_) visit(columns_.at(column).point_m);
    newly_heard_.clear();
  }

  /// Columns with at least one look, and of those heard.
  std::size_t columns() const { return columns_.size(); }
  std::size_t heardColumns() const { return heard_; }

 private:
  struct Column {
    double evidence = 0.0;  ///< Σ λ, nats
    bool heard = false;
    Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  ///< the last look's crossing, map frame
  };
  /// The column holding `point_m`'s x and y.
  std::uint64_t columnOf(const Eigen::Vector3d& point_m) const;
  /// One look of a cell, its log-likelihood ratio λ, at the column holding `point_m`, unless the
  /// cell already looked at it (`looked`: the columns this cell has looked at).
  void addLook(const Eigen::Vector3d& point_m, double evidence_nats, std::vector<std::uint64_t>& looked);

  double resolution_m_;
  double surface_mean_;    ///< μ
  double heard_evidence_;  ///< ln(1/α)
  std::unordered_map<std::uint64_t, Column> columns_;
  std::vector<std::uint64_t> newly_heard_;
  std::vector<std::uint64_t> looked_;  ///< addBeam: the columns the current cell looked at
  std::size_t heard_ = 0;
};

}  // namespace sonarmap
