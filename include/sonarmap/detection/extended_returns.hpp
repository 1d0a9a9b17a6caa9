#pragma once
/// @file extended_returns.hpp
/// Weak extended returns from the whole echo: the onset of a seabed, a grazing wall or
/// a soft bank that stays under the obstacle threshold in every bin but lights many of them.
///
/// The obstacle detectors (detectors.hpp) ask whether one echo rises far above the sweep's
/// background B(c) (a low percentile of each range over the bearings, calibration.hpp): 16.9 dB
/// for the Micron's 10⁻⁶ per bin. A seabed met at grazing incidence stands only a few dB above it
/// (+3.5 dB at 4 m under a Micron tilted 25°, sonar_equation.hpp), but over metres of range and
/// many bearings. This file asks instead whether many bins of a window of ranges and neighbouring
/// bearings rise a little above B(c): binary integration, M of N (Skolnik, "Introduction to Radar
/// Systems", 3rd ed. 2001, §2.6; the "double threshold" detector):
///
///  1. A bin is *lit* when it exceeds B(c) by τ, set so that noise alone lights a bin with
///     probability p₀ (`bin_false_alarm`). τ is measured on the sweep: the (1 − p₀) quantile of
///     every bin's excess over its column's B(c), over the columns above the A/D floor (≥ 8 columns
///     and 1,000 bins; right for speckle of any number of looks). Echoes among those bins raise it
///     and lengthen step 2's runs: so the sweep is searched twice, the second pass measuring τ and
///     the looks without the bins of the returns the first pass found and of the obstacles' echoes
///     (a censored estimate, as the censored mean-level CFAR leaves its largest cells out: Rickard
///     & Dillard 1977, IEEE Trans. AES 13(4)). On the Micron's tilted loop, whose seabed lights a
///     third of the bearings, that lowers the lit level at 3 m by 8–13 counts (1.4–2.3 dB) and the
///     bins per look from 3.8–8.9 to 2.5–4.3 (its pulse spans 4 bins). Without 8 such columns τ is
///     one-look speckle's 10 log10(ln p₀ / ln(1 − p)), p the background's percentile. Where the noise lies under the A/D floor (B(c) = 0) the column's own (1 − p₀)
///     quantile over the bearings bounds the lit level from below. B(c) is the noise wherever no
///     surface lights most bearings at that range; where one does (a level head at a constant
///     altitude sees the seabed at one range all round) it is not found, and such a head could not
///     place it anyway (sweep_fan.hpp, appendLevelTrace).
///  2. Speckle is correlated over about a pulse length, and across overlapping beams: lit bins come
///     in runs. The mean run along range over those columns, against 1 / (1 − p₀) for independent
///     bins, gives the bins per look L; the mean run across neighbouring bearings the rows per look.
///  3. A window of `window_looks` looks along range (n·L bins) and the beams within ±
///     `bearing_window_deg` / 2 holds an extended return when enough of its looks are lit: the
///     least count m with which noise alone fires anywhere in a beam (its windows along range)
///     with probability ≤ `false_alarm_per_beam` (binomial tail), as a share of the window's bins. A return
///     s dB over the noise's mean lights a look with p₁ = p₀^(1/(1 + 10^(s/10))): 0.49 at +3.5 dB,
///     0.63 at +6 dB for p₀ = 0.1.
///  4. The return starts at the maximum-likelihood change point from noise to return of the lit
///     bins (the window's rows) over the first window that holds one and the next (Hinkley 1970):
///     that window may begin on a noise bin lit by chance up to a window before the return. It ends
///     at the beam's last lit bin of the run of consecutive windows that go on with it: each holds
///     the lit bins with which noise alone fills one window with probability ≤
///     `false_alarm_per_beam` (the start asks that of all the beam's windows together; a surface
///     found is followed to a slightly weaker echo than it takes to find one, as Canny's two
///     thresholds do).
///
/// Beams the detector found empty get one (BeamDetection::extended_onset_m, extended_end_m), and
/// their echo onset moves to it when that is nearer. A beam with an obstacle gets the run that
/// starts with its obstacle's echo (its first window holding a return begins at the obstacle's bin
/// or before), its echo onset unchanged: the beam-volume model tells a level surface from a face by
/// that run's length (isLevelReturn, sweep_fan.hpp). Only the empty beams' returns are counted.
/// Meant for the beam-volume model, which places such a return on the level surface its onset
/// implies (appendLevelTrace, sweep_fan.hpp); a level head's 2D map has no use for the seabed's ring.

#include <cstddef>
#include <vector>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Options of the extended-return detector (see the file's comment), probabilities and looks.
struct ExtendedReturnOptions {
  double bin_false_alarm = 0.1;         ///< p₀: noise alone lights a bin this often, in (0, 0.5)
  double window_looks = 16.0;           ///< n: looks per window, ≥ 2
  double false_alarm_per_beam = 1e-4;   ///< noise alone finds a return in a beam this often, in (0, 0.5)
  /// The window's extent across bearings, degrees, ≥ 0: the beam and its neighbours within half of
  /// it on each side (0: the beam alone). Neighbouring bearings see the same seabed at nearly the
  /// same ranges; their looks add up.
  double bearing_window_deg = 10.0;

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// What one sweep's calibration measured (see the file's comment).
struct ExtendedReturnCalibration {
  std::vector<float> lit_counts;  ///< per column: a bin above this is lit, counts
  double bins_per_look = 1.0;     ///< L, ≥ 1
  double rows_per_look = 1.0;     ///< neighbouring rows per independent look, ≥ 1
  int half_window_rows = 0;       ///< rows on each side of a beam in its window, ≥ 0
  int window_bins = 1;            ///< n · L rounded, ≥ 1
  int lit_needed = 1;             ///< lit bins a full window (all its rows) needs to start a return
  int lit_to_continue = 1;        ///< lit bins a full window needs to go on with one, ≤ lit_needed
  std::size_t noise_columns = 0;  ///< columns τ and L were measured on
  bool measured = false;          ///< τ measured (else one-look speckle's)
};

/// The bins [begin, end) of one beam that hold a known echo (none when begin ≥ end).
struct EchoBins {
  int begin = 0;
  int end = 0;
};

/// Bins (or rows) per independent look from the runs that lit bins form: L = max(1, (lit / runs)(1 − p)),
/// with `lit` bins in `runs` runs along range (or across bearings) and p the probability that a bin
/// is lit. Independent bins light runs of geometric length, mean 1 / (1 − p): L = 1; speckle
/// correlated over L bins (a pulse longer than a bin: Goodman, "Speckle Phenomena in Optics" 2007,
/// §3; ../shared/docs/echo-model.md) lights runs about L times as long. 1 when there is no run.
double binsPerLookFromRuns(std::size_t lit, std::size_t runs, double lit_probability);

/// Calibrates the sweep `polar` for extended returns from its background (the detection's
/// SweepCalibration::background, percentile `background_percentile`) and its span. `echoes`, empty
/// or one per row: bins left out of the noise's measurement (τ, the bins and rows per look), the
/// echoes a first pass found (censoring, as a censored CFAR leaves its strongest cells out: a
/// seabed lighting a third of the bearings would otherwise raise the lit level over itself).
/// @throws ValueError for invalid options, a span or percentile out of range, a negative minimum
///         range, a background with more columns than the sweep has bins, or `echoes` neither empty
///         nor one per row.
ExtendedReturnCalibration calibrateExtendedReturns(const PolarImage& polar, const std::vector<float>& background_counts,
                                                   double background_percentile, double span_db, double min_range_m,
                                                   const ExtendedReturnOptions& options,
                                                   const std::vector<EchoBins>& echoes = {});

/// Gives each beam of `sweep` without an obstacle its extended return, if any (see the file's
/// comment); returns how many got one. `polar` is the image the sweep was detected on.
/// @throws ValueError as calibrateExtendedReturns, or when the sweep's detections do not number
///         one per row.
std::size_t addExtendedReturns(const PolarImage& polar, double background_percentile, SweepDetection& sweep,
                               const ExtendedReturnOptions& options);

}  // namespace sonarmap
