#pragma once
/// @file reverberation.hpp
/// What a beam hears where no obstacle stands at the sonar's level, measured around each bin of a
/// sweep, and how many beams an obstacle's echo must span to stand out of it.
///
/// The model (../shared/docs/echo-model.md):
///  - **The diffuse echo is smooth in range and bearing.** The seabed entering the vertical
///    aperture, the water surface and the near field return a level set by the grazing angle, the
///    beam pattern and the spreading (Urick 1983, ch. 8; Lurton 2010, ch. 3), which changes over
///    metres of range and several beam widths of bearing; fully developed speckle rides on it (an
///    exponential power; Goodman 1975; Abraham & Lyons 2002). Its local level R(row, c) is the
///    median of the bins within `bearing_beam_widths` beam widths of the row's bearing and
///    `range_looks` independent looks of its range (a look: the pulse's length, or the water's own
///    runs where they are longer, evidence_detector.cpp), or of twice the beam's footprint across its
///    width, r · w, where that is longer (at 40 m a 3° beam spans 2.1 m: a face's echo at oblique
///    incidence lasts about that). An obstacle's echo is short in range (a
///    pulse at normal incidence, the beam's footprint at oblique incidence) and leaves the median of
///    such a window to what surrounds it; a wall at one range in every bearing (a round tank) is not
///    the level, as it is for a percentile taken across bearings.
///  - **Speckle is independent from beam to beam.** Consecutive pings of an MSIS see the speckle
///    of a new ping (the head has turned and the water moved): on the shared Ping360 basin log the
///    excess over R of adjacent beams (0.9° apart, 2° wide) correlates 0.02–0.12, along range 0.8
///    over one bin. An obstacle returns in every beam whose pattern covers it, at the range of its
///    surface there. So an echo is an obstacle only when it spans `n` consecutive beams, each with a
///    run above the threshold overlapping its neighbour's within a look (M-of-M binary integration
///    across beams: Skolnik, "Introduction to Radar Systems", 3rd ed. 2001, §2.6), `n` the fewest
///    beams for which chance alignments of the sweep's own unaligned runs stay under the
///    false-alarm probability (requiredEchoBeams). Quiet water makes no unaligned runs and n = 1;
///    a seabed's reverberation makes many, and an echo must span several beams.
///
/// The rows of a polar image are beams in recording order; the window runs over them in bearing
/// order, around the circle for a whole turn, clipped at a sector's ends.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// The percentile of a window's bins that is its level R: the median (one-look speckle's median lies
/// 1.6 dB under its mean power, 3.8 dB over its 25th percentile).
inline constexpr double kLocalLevelPercentile = 50.0;

/// Options of the local reverberation level (see the file's comment).
struct ReverberationOptions {
  /// Whether the evidence detector judges each bin by the level around it (true) or each range by
  /// a percentile across the sweep's bearings (false, the default: calibration.hpp's background).
  /// Off by default: docs/accuracy.md, "Local reverberation level", measures what it gains on a
  /// seabed's reverberation (the labelled Ping360 basin) and what it costs in a reverberant tank
  /// (the CRAS log's multipath behind its walls) and on the simulated heads.
  bool enabled = false;
  /// Half the window along range, in independent looks, > 0: 12 looks each side (the shared
  /// Ping360 basin log at 10 m: 4 cm pulses, ±0.48 m).
  double range_looks = 12.0;
  /// Half the window across bearing, in horizontal beam widths, > 0 (at least one beam each side).
  double bearing_beam_widths = 2.5;

  /// @throws ValueError naming the option when it is not finite and > 0.
  void validate() const;
};

/// The local level R(row, c) of one sweep's polar image, intensity counts (see the file's comment).
/// Measured at every `step` bins of range and interpolated linearly between; 0 before the first
/// measured bin and beyond a row's valid bins. Memory: one byte per bin.
class LocalLevel {
 public:
  LocalLevel() = default;
  /// Measures R on `polar` from column `min_bin` on (the nearer bins, the head's near field, are
  /// neither measured nor counted).
  /// @param look_bins        bins per independent look along range, ≥ 1
  /// @param beam_width_rad   the horizontal −3 dB width, radians, ≥ 0 (0: one beam each side)
  /// @throws ValueError for invalid options, an image that is not CV_8UC1 with one valid_bins and
  ///         one bearing per row, or look_bins < 1.
  LocalLevel(const PolarImage& polar, int min_bin, double look_bins, double beam_width_rad, const ReverberationOptions& options);

  /// The level of `kept` (a whole sweep's) at the bearing of each row of `rows` (a sweep in
  /// progress: one beam holds too little to measure its own), as rows × columns of `rows`.
  /// @throws ValueError when `rows` has not one bearing per row.
  static LocalLevel atBearingsOf(const LocalLevel& kept, const PolarImage& rows);

  bool empty() const { return level_.empty(); }
  /// R at row `row`, column `c`, intensity counts (rows as the polar image it was measured on).
  float at(int row, int c) const { return level_.at<std::uint8_t>(row, c); }
  /// The rows in bearing order (bearings increasing in [0, 2π)).
  const std::vector<int>& bearingOrder() const { return order_; }
  /// The rows beside row `row` in bearing order, before and after it (−1 where a sector ends).
  std::array<int, 2> bearingNeighbours(int row) const;
  /// Row `row`'s place in bearingOrder() (0 for a row outside the image).
  int positionOf(int row) const {
    return row >= 0 && row < static_cast<int>(position_.size()) ? position_[static_cast<std::size_t>(row)] : 0;
  }
  /// Whether the rows close a circle (a whole turn): the first and last of bearingOrder() neighbour.
  bool circular() const { return circular_; }
  /// The level of the row nearest `bearing_rad` at column `c`: a beam of a sweep in progress
  /// (detectRows) judged by the last whole sweep; 0 when empty or `c` is outside the image.
  float atBearing(double bearing_rad, int c) const;
  /// Half the window along range at column `c`, bins: ReverberationOptions::range_looks looks, or
  /// twice the beam's footprint across its width at that range (r · w) where that is longer.
  int halfWindowBins(int c) const {
    return std::max(half_bins_, static_cast<int>(footprint_bins_per_bin_ * (std::max(c, 0) + 0.5)));
  }
  /// Half the window across bearing, rows (beams) each side (ReverberationOptions::bearing_beam_widths).
  int halfWindowRows() const { return half_rows_; }
  /// Bytes held.
  std::size_t memoryBytes() const { return level_.total() + order_.size() * sizeof(int) + bearings_.size() * sizeof(double); }

 private:
  /// Sets order_ and bearings_ from the rows of `polar`.
  void sortByBearing(const PolarImage& polar);
  /// The level over `polar` from `min_bin` on, rows × cols.
  cv::Mat measure(const PolarImage& polar, int min_bin) const;

  cv::Mat level_;                ///< CV_8UC1, rows × cols
  std::vector<int> order_;       ///< rows in bearing order
  std::vector<int> position_;    ///< each row's place in order_
  std::vector<double> bearings_; ///< bearing of each position of order_, radians in [0, 2π)
  bool circular_ = false;
  int half_bins_ = 0;                ///< the looks' part of the half window, bins
  double footprint_bins_per_bin_ = 0.0;  ///< twice the beam width, radians: the footprint's part per bin of range
  int half_rows_ = 0;
};

/// The fewest consecutive beams an echo must span so that runs of the reverberation's speckle line
/// up so by chance no more often than `false_alarm_probability` per bin: the smallest n ≥ 1 with
/// ρ · n · qⁿ⁻¹ ≤ P_fa, q = 1 − exp(−ρ · overlap_bins) the chance that a neighbouring beam holds a
/// run within reach (runs scattered as a Poisson process of ρ per bin; n places for the run in the
/// chain). 1 when ρ ≤ P_fa; at most `max_beams`.
/// @param unaligned_runs_per_bin  ρ, the sweep's runs above the threshold that no neighbour's run
///        overlaps, per bin searched, ≥ 0
/// @param overlap_bins            the bins of a neighbouring beam within reach of a run, ≥ 0
/// @throws ValueError when an argument is outside its range or P_fa is not in (0, 1).
int requiredEchoBeams(double unaligned_runs_per_bin, double overlap_bins, double false_alarm_probability, int max_beams);

}  // namespace sonarmap
