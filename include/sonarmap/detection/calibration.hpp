#pragma once
/// @file calibration.hpp
/// Self-calibration of one sweep: what the sonar records where there is no obstacle, measured on
/// the sweep itself, so that thresholds follow each log's gain, noise level and range scale
/// instead of fixed intensities.
///
/// On a polar image of one sweep (rows = beams, columns = bins):
///  - Background B(c): the `background_percentile` (default the 25th) of column c over the rows
///    (all bearings at that range). What returns at the same range in most bearings — the
///    transducer's ringing, the surface or seabed entering the vertical aperture (the CRAS log's
///    ring at 1.56 m), the near-field reverberation of a high-gain head, the noise floor the TVG
///    raises with range — is background, not an obstacle. The background detector measures it
///    again over the beams still in water at each range (detectors.hpp), so that what lies behind
///    the nearer walls does not count.
///  - Threshold T(c) on the residual I − B(c), intensity counts: the level that noise alone exceeds
///    with probability `false_alarm_probability` per bin, from the statistics of fully developed
///    speckle: the echo power of a scattering background is exponentially distributed (Rayleigh
///    amplitude; Goodman 1975, "Statistical properties of laser speckle patterns"; for sonar
///    reverberation: Abraham & Lyons 2002, IEEE J. Oceanic Eng. 27(4)): its p-quantile is
///    −ln(1 − p) times its mean, so the tail of probability Pfa lies
///    T_dB = 10 log10(ln(Pfa) / ln(1 − p)) dB above the background percentile p: 16.9 dB above the
///    25th percentile at Pfa 10⁻⁶ (the default), 15.6 dB at 3.2 × 10⁻⁵. MSIS intensities are
///    log-compressed, so a ratio in dB is a difference in counts: T = T_dB × 255 / span, with the log's dB span (SeaNet's ADspan) or
///    kDefaultIntensitySpan_db. One look is the worst case: a head that averages samples, or a
///    pulse longer than a bin, narrows the spread and only lowers the false alarms (and the
///    sensitivity: a weak echo within ≈ T_dB of the noise floor is not reported; raise
///    false_alarm_probability to see weaker targets). Heavier-tailed clutter (non-Rayleigh seabed,
///    fish) is what the required echo length and min_contrast_db guard against. (Estimating T from
///    the spread the noise shows instead was tried: the simulated heads' noise has a heavier tail
///    than its quartiles suggest, (Q99.99 − Q25) / (Q50 − Q25) ≈ 5 where one-look speckle gives 3.95,
///    and it fired up to 275 times a sweep in open water; docs/accuracy.md.)
///  - Near field: the self-reflection band ends where the median profile (median of each column)
///    falls below half-way between its peak within the first quarter of the range and the median
///    of the far half (no band when that peak is not T above the quietest range after it), at most
///    max_near_field_m out: where the scene's reverberation fills most bearings near the head (the
///    shared Ping360 basin log's floor entering the aperture), the median falls with the scene, not
///    with the head (3.0–4.3 m there). Each beam's own part of what the cut leaves is the
///    detector's: a beam still in an echo at the minimum range has no return at its edge
///    (detectors.hpp, the floor).
///  - Housing: the head's housing and the transducer's ring-down return at the same ranges in
///    nearly every beam whatever the bearing, while the scene's echoes move with bearing. The
///    persistence P(c) is the share of the rows (beams) whose level at column c stands above the
///    water's level W: the median of the bins of the quietest quarter of the columns (lowest
///    medians) raised by the ratio of one-look speckle's (1 − clutter_share) quantile to its median
///    (5.2 dB at 10 %), the level water alone exceeds in about clutter_share of its bins. The
///    housing's band is present when P peaks, within max_near_field_m and the first quarter of the
///    range, at ≥ 1 − clutter_share (nearly every beam) and more than clutter_share above the
///    scene's persistence (the median of P over the columns beyond); it ends where P falls under
///    1 − clutter_share or under half-way from that peak to the scene's (for a sharp band, its
///    outer edge). A faint housing (the shared pool bag's Micron: 40–90 counts over black water) is
///    found though the median rule, which needs T, misses it.
///    The near-field clutter then extends, contiguous with the band or the housing (gaps shorter
///    than max_gap_m bridged), over the ranges where at least `clutter_share` of the bearings rise
///    clutterLevelDb() above the background (the (1 − clutter_share) quantile of the column minus
///    B(c)): the vehicle's own body and fixtures seen in many bearings at short range. Measured per
///    sweep (lowest–highest minimum range over a log): the CRAS log's band ends at 0.26 m, its
///    housing at 0.30 m, and the vehicle's returns behind it take the near field to 0.58–0.61 m;
///    the pool bag's band rule finds nothing and its housing ends at 0.60–0.80 m; the SeaNet sector
///    log's ring-down, in every beam of the sector, at 0.70–1.41 m; the Ping360 logs' near fields
///    run from 0.27 m (a harbour log's 60 m scale) to the 2 m bound (the basin's 10 and 20 m
///    sweeps, saturated to about 2 m in every beam; their median band rule reaches 4.3 m, bounded
///    to 2 m).
///  - Rings: beyond the near field, the columns where B(c) stands T or more over its own median
///    within ±ring_window_pulses pulse lengths in range form rings (the window shrunk symmetrically
///    at its ends, so that a background rising or falling monotonically — the ring-down's tail, the
///    seabed entering the aperture — makes none; a rise under T, the percentile's own scatter from
///    range to range, makes none). A ring that most beams hear through (an echo a pulse long
///    standing T over the background behind it: the water surface entering the aperture blocks
///    nothing) stays the background. A ring that blocks the beams — a wall at one range at every
///    bearing, a head centred in a round tank — is a structure: B there is that median, and the
///    detector measures the wall over the water's level around it in range.
///  - Ring-down: the transducer's ring is a level in dB falling with range, alike in every beam but
///    louder or quieter from ping to ping (the shared Ping360 logs at 60 m and gain 0: a 5–6 dB
///    spread beyond speckle's), so the near field, which ends where most beams have come down,
///    leaves the louder pings' tails. Its shape is the median profile from its peak within the band
///    or the housing (none without one) while it stands above the water's level W, and beyond along
///    the line fitted to its unsaturated decline (counts are dB); each beam's ring is that shape
///    plus the beam's median excess over it on the decline (detector_internal.hpp, RowRingDown).
///    Both outward passes measure a beam's excess over the larger of the water's level and its own
///    ring.

#include <cstddef>
#include <limits>
#include <vector>

#include "sonarmap/detection/reverberation.hpp"
#include "sonarmap/detection/water_evidence.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Options of the per-sweep calibration (see the file's comment for each definition).
struct CalibrationOptions {
  double background_percentile = 25.0;  ///< percentile in [0, 100] of each column over the rows
  /// Probability, per bin, that noise alone rises above the threshold, in (0, 0.5). 10⁻⁶: a sweep
  /// of 200 beams × 400 bins of one-look speckle then gives a false obstacle once in ≈ 12 sweeps.
  double false_alarm_probability = 1e-6;
  /// Least rise of an echo above the background, dB, ≥ 0, whatever the false-alarm probability.
  double min_contrast_db = 0.0;
  double clutter_share = 0.10;  ///< share of bearings that makes a range near-field clutter, (0, 0.5]
  double max_gap_m = 0.10;      ///< clutter-free stretch that ends the near field, metres, ≥ 0
  /// Farthest the near-field clutter reaches from the head, metres, ≥ 0 (+∞ allowed): the vehicle's
  /// own body and fixtures, within 2 m of the head on the small AUVs and ROVs that carry MSIS
  /// (a BlueROV2 is 0.46 m long, the CRAS vehicle's returns end at 0.26 m). Farther, what rises in
  /// many bearings is the scene (the shared Ping360 basin log's floor, seen down a slope in a third
  /// of the bearings from 2 to 9 m, made near fields of 7–10 m on a 10 m scale and an empty map);
  /// the self-reflection band, measured on the median, is bounded by it too.
  double max_near_field_m = 2.0;
  /// Half-width, in pulse lengths (c·τ/2, or bins when the log does not record the pulse), of the
  /// window in range of the background's own median beyond the near field: a ring that returns in
  /// most bearings over less than this, stands T over that median and blocks the beams (a round
  /// tank's wall around the head) is a structure, not the water's level (see "Rings" above). ≥ 1.
  double ring_window_pulses = 12.0;

  /// @throws ValueError naming the option when it is outside its range or not finite.
  void validate() const;
};

/// One sweep's calibration (see the file's comment). Vectors hold one value per column.
struct SweepCalibration {
  std::vector<float> background;  ///< B(c), intensity counts
  std::vector<float> threshold;   ///< T at each column, intensity counts above B(c)
  /// The most B(c) may be where a ring at every bearing was removed from it (see "Rings"), +∞
  /// elsewhere; the detectors' outward passes, which measure B again over the beams still in water,
  /// cap it by this. Empty: no cap.
  std::vector<float> background_cap;
  /// background_cap at column `c`, +∞ outside it.
  float backgroundCap(int c) const {
    return c >= 0 && static_cast<std::size_t>(c) < background_cap.size() ? background_cap[static_cast<std::size_t>(c)]
                                                                          : std::numeric_limits<float>::infinity();
  }
  double span_db = 0.0;           ///< dB span of the intensity scale used
  double threshold_db = 0.0;      ///< T in dB
  double band_end_m = 0.0;        ///< end of the self-reflection band, metres
  double housing_end_m = 0.0;     ///< outer edge of the housing's band (0: none found), metres
  double near_field_end_m = 0.0;  ///< end of the near-field clutter (≥ band_end_m, housing_end_m), metres
  /// The water's level W, intensity counts: the level water alone exceeds in about clutter_share of
  /// its bins (the housing's rule above). A beam whose level along it has come down to W is in water.
  float quiet_water_counts = 0.0f;
  /// The evidence detector's water at each column, measured over a whole sweep (water_evidence.hpp:
  /// the band of water ending at that range); empty when not measured (other detectors). Rows of a
  /// sweep in progress (detectRows) are judged against it: one beam holds too little water to
  /// measure its own. About 2 KB a column.
  std::vector<WaterEvidence> water_evidence;
  /// The level that water's excess is counted from at each column (intensity counts: the evidence
  /// detector's percentile of the rows in water), with water_evidence; empty when not measured.
  std::vector<float> water_level;
  /// The water's bins per independent look along range as the evidence detector counts them (≥ 1:
  /// the pulse's length in bins, or the water's own runs where they are longer; evidence_detector.cpp,
  /// evidenceWeight), with water_evidence; 0 when not measured.
  double water_bins_per_look = 0.0;
  /// The transducer's ring-down by column up to the near field's bound, intensity counts (empty
  /// without a self-reflection band or a housing rising a threshold over the water): from the
  /// band's peak, the median over the bearings while it
  /// stands above the water's level, then carried on along the straight line fitted to its
  /// unsaturated decline beyond the self-reflection band (a level in dB falling linearly with range;
  /// counts are dB), below 0 too. Every ping rings with this shape, louder or quieter by its own
  /// offset, measured per beam on the columns [ring_fit_begin, ring_fit_end).
  std::vector<float> ring_down;
  int ring_fit_begin = 0;  ///< first column of the ring's unsaturated decline
  int ring_fit_end = 0;    ///< one past its last
  /// The local level of the sweep's diffuse echo (reverberation.hpp), when the evidence detector
  /// measured it (ReverberationOptions::enabled); empty otherwise. Rows of a sweep in progress
  /// (detectRows) are judged by it at their bearing. One byte per bin.
  LocalLevel local_level;
  /// The threshold over the local level, dB: thresholdDb() at its percentile (the median), 13.0 dB at
  /// 10⁻⁶; 0 without a local level.
  double local_threshold_db = 0.0;
  /// The fewest consecutive beams a loud echo had to span (requiredEchoBeams), with local_level; 0
  /// otherwise.
  int echo_beams = 0;
};

/// The level above the background percentile that makes a range near-field clutter when the
/// (1 − clutter_share) quantile of its bearings reaches it, dB: the level one-look speckle exceeds
/// with probability clutter_share / 4 (11.1 dB for 10 % above the 25th percentile), so the
/// noise of open water is never clutter, however high the gain.
/// @throws ValueError when the options are invalid.
double clutterLevelDb(const CalibrationOptions& options);

/// Calibrates one sweep over all its rows. `span_db`: the dB span of the intensities
/// (intensitySpan_db of the image, or an override). Cost: O(rows × cols + 256 × cols) (a
/// histogram per column).
/// @throws ValueError for invalid options, an image that is not CV_8UC1 with bin_length_m > 0 and
///         one valid_bins entry per row, or a span that is not finite and > 0.
SweepCalibration calibrateSweep(const PolarImage& polar, const CalibrationOptions& options, double span_db);

/// The threshold in dB above the background percentile for `options`: max(min_contrast_db,
/// 10 log10(ln(Pfa) / ln(1 − p))) (see the file's comment).
/// @throws ValueError when the options are invalid.
double thresholdDb(const CalibrationOptions& options);

/// The threshold in dB above the `percentile` (0…100) of one-look speckle that it exceeds with
/// `options.false_alarm_probability`: max(min_contrast_db, 10 log10(ln(Pfa) / ln(1 − p/100))).
/// @throws ValueError when the options are invalid or the percentile is not in (0, 100).
double thresholdDb(const CalibrationOptions& options, double percentile);

}  // namespace sonarmap
