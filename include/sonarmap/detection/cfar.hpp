#pragma once
/// @file cfar.hpp
/// Constant-false-alarm-rate (CFAR) detection along one beam.
///
/// Sources: M. A. Richards, "Fundamentals of Radar Signal Processing", McGraw-Hill, ch. 6, CFAR
/// detection: cell-averaging CFAR, its greatest-of and smallest-of variants and their behaviour
/// at clutter edges and with interfering targets. H. Rohling, "Radar CFAR Thresholding in Clutter
/// and Multiple Target Situations", IEEE Trans. Aerospace and Electronic Systems AES-19(4), 1983:
/// ordered-statistic CFAR.
///
/// Along a beam (one row of a PolarImage) the bins are the cells. For the cell under test c:
///   - guard cells: the `guard_bins` bins on each side of c, never used (they hold the target's
///     own spread, e.g. from smoothing);
///   - training cells: the lagging window [c − G − T, c − G) and the leading window
///     [c + G + 1, c + G + T + 1), with G = guard_bins and T = training_bins;
///   - noise estimate Z by the variant (CfarVariant) from the windows that lie completely inside
///     the beam's valid bins: near either end only the complete window is used (with the same
///     scale, so the false-alarm rate there is that of T cells instead of 2T: higher), and a cell
///     with neither window complete gets no estimate (it is never detected);
///   - the cell passes when I[c] > scale × Z (OS: Z is the k-th smallest of the n training cells
///     used, k = round(os_rank × n) clamped to [1, n]).
/// The threshold scales with the local noise level, so in homogeneous noise the probability that a
/// noise cell passes does not depend on that level (hence "constant false-alarm rate").

#include <cstdint>
#include <span>
#include <vector>

namespace sonarmap {

/// How the training cells of both windows become the noise estimate Z.
enum class CfarVariant {
  kCellAveraging,     ///< CA (Richards ch. 6): mean of all training cells; best in homogeneous noise
  kSmallestOf,        ///< SO: smaller of the two window means; keeps a target whose other window holds
                      ///< clutter or another target, but fires on the high side of a clutter edge
  kGreatestOf,        ///< GO: greater of the two window means; quiet at clutter edges, but masks a
                      ///< target next to a brighter region
  kOrderedStatistic,  ///< OS (Rohling 1983): k-th smallest training cell, k = round(os_rank × n);
                      ///< robust to up to n − k interfering targets in the training cells
};

/// CFAR detection along a beam in cells (bins), as the functions below use it. The detector's
/// options in physical units (CfarOptions, detectors.hpp) are converted into these for each image.
///
/// Scale: the exponential-noise formulas (caCfarScale(), osCfarScale()) give α for square-law
/// detected, independent samples; MSIS intensities are log-compressed and correlated over the
/// pulse, so on sonar images α is a design ratio, not a false-alarm rate.
struct CfarCells {
  CfarVariant variant = CfarVariant::kCellAveraging;
  int training_bins = 48;     ///< training cells per side, 1…65535
  int guard_bins = 24;        ///< guard cells per side between the cell under test and its training, 0…65535
  double scale = 1.25;        ///< threshold multiplier α on the noise estimate, finite and > 0
  double os_rank = 0.75;      ///< OS only: k as a share of the n training cells used, in (0, 1] (Rohling: ≈3/4)
  int min_intensity = 0;      ///< intensity floor: a detected cell also has I ≥ min_intensity, 0…255
  int min_run_bins = 1;       ///< consecutive passing cells that make an obstacle, ≥ 1
  /// @throws ValueError  naming the field, when an option is outside its documented range.
  void validate() const;
};

/// The CFAR threshold scale × Z of every cell of `beam` (before the intensity floor).
///
/// @param beam     intensities of the beam's valid bins, bin 0 nearest (0…255).
/// @param options  window layout, variant and scale (the floor and run are not used here).
/// @return         beam.size() thresholds in intensity units; +infinity where neither training window
///                 fits inside the beam. Cost: O(bins) for CA/SO/GO (prefix sums), O(bins × T) for
///                 OS (std::nth_element over the ≤ 2T training cells of each cell).
/// @throws ValueError  when `options` is invalid (CfarCells::validate).
std::vector<float> cfarThresholds(std::span<const std::uint8_t> beam, const CfarCells& options);

/// The first obstacle along one beam: the first bin c ≥ min_bin that starts `min_run_bins`
/// consecutive bins each with I > scale × Z and I ≥ the floor (floor[c] when `floor` is given, one
/// value per bin; else min_intensity).
///
/// @param beam     intensities of the beam's valid bins, bin 0 nearest (0…255).
/// @param min_bin  first bin that may be reported, ≥ 0 (bins before it still serve as training).
/// @param options  CFAR cells.
/// @param floor    empty, or at least beam.size() per-bin floors in intensity counts.
/// @return         the bin index, or −1 when there is none. Stops at the first obstacle: the cost is
///                 that of cfarThresholds() over the bins searched.
/// @throws ValueError  when `options` is invalid, min_bin < 0, or `floor` is shorter than the beam.
int firstCfarBin(std::span<const std::uint8_t> beam, int min_bin, const CfarCells& options,
                 std::span<const float> floor = {});

/// CA-CFAR scale for a design false-alarm probability, square-law detected (exponential) noise and
/// N training cells (Richards ch. 6, CA-CFAR analysis): Pfa = (1 + α/N)^(−N), so α = N (Pfa^(−1/N) − 1).
/// @param false_alarm_probability  in (0, 1).
/// @param training_cells           N ≥ 1, both windows together (2 × training_bins).
/// @throws ValueError  when an argument is outside its range.
double caCfarScale(double false_alarm_probability, int training_cells);

/// OS-CFAR scale for a design false-alarm probability, exponential noise, N training cells and the
/// k-th smallest as estimate (Rohling 1983): Pfa = ∏_{i=0}^{k−1} (N − i) / (N − i + α),
/// solved for α by bisection (Pfa falls monotonically with α).
/// @param false_alarm_probability  in (0, 1).
/// @param training_cells           N ≥ 1.
/// @param rank                     k in [1, N].
/// @throws ValueError  when an argument is outside its range.
double osCfarScale(double false_alarm_probability, int training_cells, int rank);

/// CFAR detection in physical units (the detector's options; converted to CfarCells with each
/// image's bin length and intensity scale). A detected cell must also rise above the sweep's
/// calibrated background by its threshold (calibration.hpp) or min_contrast_db, whichever is more:
/// the floor is what keeps CFAR off the constant-range ring, which is locally brighter than its
/// neighbours in every beam, and off noise where the local windows are quiet (clipped water).
/// Defaults: the windows that worked on the CRAS log (guard 24 and training 48 bins of 1.25 cm
/// there), now in metres.
/// Limits: a beam shorter than guard + training + one bin has no complete training window and no
/// detection.
struct CfarOptions {
  CfarVariant variant = CfarVariant::kCellAveraging;
  double training_m = 0.6;        ///< training window per side, metres, > 0 (≥ 1 bin)
  double guard_m = 0.3;           ///< guard window per side, metres, ≥ 0
  double scale = 1.25;            ///< α, the threshold's ratio to the noise estimate, finite and > 0
  double os_rank = 0.75;          ///< OS only: k as a share of the training cells, in (0, 1]
  double min_contrast_db = 0.0;   ///< a detected cell also rises this much above the background, dB, ≥ 0
  /// Consecutive passing cells that make an obstacle, metres, ≥ 0 (≥ 1 bin); never more than the
  /// log's pulse where it records one (Beam::pulse_length_m).
  double min_echo_length_m = 0.04;

  /// The cells for bins of `bin_length_m` (the floor is applied per bin by the detector).
  /// @throws ValueError  when an option is outside its documented range or the bin length is not > 0.
  CfarCells cells(double bin_length_m) const;
  /// @throws ValueError  naming the option, when it is outside its documented range.
  void validate() const;
};

}  // namespace sonarmap
