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

/// Options of CFAR detection along a beam (see the file comment for the cell layout).
///
/// Scale: set directly, not from a design false-alarm probability. The Micron's 0…255 intensities
/// are log-compressed and, after the default 11 × 11 Gaussian, strongly correlated between bins, so
/// the exponential-noise formulas (caCfarScale(), osCfarScale()) do not give the rate on such data;
/// use them for square-law detected, independent samples.
///
/// Defaults, chosen on the CRAS tank log after the default preprocessing (removeSelfReflection
/// 0.3 m, Gaussian 11 × 11), pooled over its 28 sweeps (checked by tests/detection/test_cfar.cpp; the
/// share is that of detections within 0.15 m of the rectangle evaluateWalls() fits to them):
///   - guard 24 bins (0.30 m) per side: longer than the smoothed leading edge and the wall's own
///     echo, so at a wall's first bin the leading window lies behind the wall instead of on it.
///     With 4 guard bins the wall masks itself for GO and OS: 4853 and 4514 of 5600 beams detect,
///     0.815 and 0.756 on the walls (CA and SO are hardly affected);
///   - training 48 bins (0.60 m) per side: a steady estimate across the tank's dark interior;
///   - scale 1.25, floor 70, runs of 6 bins (7.5 cm). The floor is what removes the ≈1.56 m
///     floor/surface ring: CFAR alone (floor 0) puts 25 % of its detections on it, since the ring
///     is locally brighter than its neighbours in every beam.
///   Result: CA 5600 detections, 0.835 on the walls; SO 5600, 0.816; GO 5572, 0.858; OS 5499,
///   0.857; none on the ring (the background-subtracted detector: 5600, 0.816, none). CA is the
///   default: it detects in every beam and loses less of the floater inside the tank than GO and OS
///   (283 detections in its region against 258 and 255). A floor of 60 keeps more of the floater
///   (385, as many as the background detector) for about the same share (CA 0.838), but one sweep
///   in 28 then drops to 0.76.
/// Limits: a beam shorter than guard + training + 1 = 73 bins has no complete training window and
/// no detection; the floor is in the sonar's intensity units, so another gain needs another floor.
struct CfarOptions {
  CfarVariant variant = CfarVariant::kCellAveraging;
  int training_bins = 48;     ///< training cells per side, 1…65535
  int guard_bins = 24;        ///< guard cells per side between the cell under test and its training, 0…65535
  double scale = 1.25;        ///< threshold multiplier α on the noise estimate, finite and > 0
  double os_rank = 0.75;      ///< OS only: k as a share of the n training cells used, in (0, 1] (Rohling: ≈3/4)
  int min_intensity = 70;     ///< intensity floor: a detected cell also has I ≥ min_intensity, 0…255
  int min_run_bins = 6;       ///< consecutive passing cells that make an obstacle, ≥ 1

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
/// @throws ValueError  when `options` is invalid (CfarOptions::validate).
std::vector<float> cfarThresholds(std::span<const std::uint8_t> beam, const CfarOptions& options);

/// The first obstacle along one beam: the first bin c ≥ min_bin that starts `min_run_bins`
/// consecutive bins each with I > scale × Z and I ≥ min_intensity.
///
/// @param beam     intensities of the beam's valid bins, bin 0 nearest (0…255).
/// @param min_bin  first bin that may be reported, ≥ 0 (bins before it still serve as training).
/// @param options  CFAR options.
/// @return         the bin index, or −1 when there is none. Stops at the first obstacle: the cost is
///                 that of cfarThresholds() over the bins searched.
/// @throws ValueError  when `options` is invalid or min_bin < 0.
int firstCfarBin(std::span<const std::uint8_t> beam, int min_bin, const CfarOptions& options);

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

}  // namespace sonarmap
