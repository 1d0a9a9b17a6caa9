/// @file calibration.cpp
/// Per-sweep background, threshold and near field (see calibration.hpp).

#include "sonarmap/detection/calibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "column_histogram.hpp"
#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/speckle.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

[[noreturn]] void throwOption(const std::string& what) { throw ValueError("calibration: " + what); }

/// Per column: the percentiles the calibration needs, over all rows whose valid bins cover it.
struct ColumnProfile {
  std::vector<float> background, median, clutter;
};

ColumnProfile profileColumns(const PolarImage& polar, const CalibrationOptions& options) {
  const auto cols = static_cast<std::size_t>(polar.cols());
  ColumnProfile profile{std::vector<float>(cols), std::vector<float>(cols), std::vector<float>(cols)};
  const cv::Mat columns = polar.intensities.t();  // row c: column c's values, contiguous
  const bool all_valid = std::all_of(polar.valid_bins.begin(), polar.valid_bins.end(),
                                     [&](int valid) { return valid >= polar.cols(); });
  // The three percentiles in ascending order, remembering which is which.
  std::array<double, 3> wanted{options.background_percentile, 50.0, 100.0 * (1.0 - options.clutter_share)};
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return wanted[a] < wanted[b]; });
  const std::array<double, 3> sorted{wanted[order[0]], wanted[order[1]], wanted[order[2]]};
  detail::IntensityHistogram histogram;
  for (std::size_t c = 0; c < cols; ++c) {
    histogram.clear();
    const auto* values = columns.ptr<std::uint8_t>(static_cast<int>(c));
    for (int r = 0; r < polar.rows(); ++r) {
      if (all_valid || static_cast<int>(c) < polar.valid_bins[static_cast<std::size_t>(r)]) histogram.add(values[r]);
    }
    if (histogram.total() == 0) continue;
    const std::array<float, 3> found = histogram.percentiles(sorted);
    std::array<float, 3> by_wanted{};
    for (int k = 0; k < 3; ++k) by_wanted[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = found[static_cast<std::size_t>(k)];
    profile.background[c] = by_wanted[0];
    profile.median[c] = by_wanted[1];
    profile.clutter[c] = by_wanted[2];
  }
  return profile;
}

/// Whether most rows of `polar` hear an echo behind columns [begin, end): a run of `look` bins, from
/// `end` plus the ring's own length on, standing `threshold` over `background` (the ring left out).
bool heardThrough(const PolarImage& polar, const std::vector<float>& background, int begin, int end, int look,
                  float threshold) {
  const int from = end + (end - begin);
  int hearing = 0;
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    const int valid = std::min(polar.valid_bins[static_cast<std::size_t>(r)], static_cast<int>(background.size()));
    for (int c = from, run = 0; c < valid; ++c) {
      run = static_cast<float>(values[c]) - background[static_cast<std::size_t>(c)] >= threshold ? run + 1 : 0;
      if (run >= look) {
        ++hearing;
        break;
      }
    }
  }
  return 2 * hearing > polar.rows();
}

/// The background beyond the near field without the walls around the head: the columns c ≥ `first`
/// where B(c) stands `threshold` or more over the median of B within `half_window` columns of c
/// (the window shrunk symmetrically at the edges and at `first`, so that a profile that rises or
/// falls monotonically, as the ring-down's tail and the seabed entering the aperture do, is kept as
/// it is) form rings. A ring that most beams hear through (an echo behind it: the water surface or
/// the seabed entering the aperture, which blocks nothing) stays the background; one that blocks the
/// beams (a round tank's wall at every bearing) is a structure, and B there is that median.
void removeWalls(const PolarImage& polar, std::vector<float>& background, int first, int half_window, int look,
                 float threshold) {
  const auto cols = static_cast<int>(background.size());
  std::vector<float> around(background.size(), -1.0f);  // the median where the column is a ring's
  std::vector<float> window;
  for (int c = std::max(0, first); c < cols; ++c) {
    const int half = std::min({half_window, c - first, cols - 1 - c});
    if (half < 1) continue;
    window.assign(background.begin() + (c - half), background.begin() + (c + half + 1));
    std::nth_element(window.begin(), window.begin() + half, window.end());
    const float median = window[static_cast<std::size_t>(half)];
    if (background[static_cast<std::size_t>(c)] - median >= threshold) around[static_cast<std::size_t>(c)] = median;
  }
  std::vector<float> without_rings = background;
  for (int c = 0; c < cols; ++c) {
    if (around[static_cast<std::size_t>(c)] >= 0.0f) without_rings[static_cast<std::size_t>(c)] = around[static_cast<std::size_t>(c)];
  }
  for (int begin = 0; begin < cols;) {
    if (around[static_cast<std::size_t>(begin)] < 0.0f) {
      ++begin;
      continue;
    }
    int end = begin;
    while (end < cols && around[static_cast<std::size_t>(end)] >= 0.0f) ++end;
    if (!heardThrough(polar, without_rings, begin, end, look, threshold)) {
      std::copy(without_rings.begin() + begin, without_rings.begin() + end, background.begin() + begin);
    }
    begin = end;
  }
}

/// First column after the median profile's near peak where it falls half-way to the far level; 0
/// when the peak does not rise `significant` counts above the quietest range after it (no band).
int bandEnd(const ColumnProfile& profile, float significant) {
  const auto cols = static_cast<int>(profile.median.size());
  if (cols == 0) return 0;
  const int search = std::max(1, cols / 4);
  const auto peak = std::max_element(profile.median.begin(), profile.median.begin() + search);
  std::vector<float> far(profile.median.begin() + cols / 2, profile.median.end());
  std::nth_element(far.begin(), far.begin() + static_cast<std::ptrdiff_t>(far.size() / 2), far.end());
  const float quietest = *std::min_element(peak, profile.median.end());
  if (*peak - quietest < significant) return 0;
  const float half = 0.5f * (*peak + far[far.size() / 2]);
  int c = static_cast<int>(peak - profile.median.begin());
  while (c < cols && profile.median[static_cast<std::size_t>(c)] > half) ++c;
  return c;
}

/// End of the clutter contiguous with the band: the last column, reached through gaps of at most
/// gap_bins, where the clutter quantile rises `level` counts above the background.
int nearFieldEnd(const ColumnProfile& profile, float level, int band_end, int gap_bins) {
  const auto cols = static_cast<int>(profile.median.size());
  int last = band_end;
  for (int c = band_end; c < cols && c - last <= gap_bins; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (profile.clutter[i] - profile.background[i] >= level) last = c + 1;
  }
  return last;
}

/// The water's level, intensity counts: the median of the bins of the quietest quarter of the
/// columns (lowest medians), raised by the ratio of one-look speckle's (1 − clutter_share) quantile
/// to its median (5.2 dB at 10 %): the level water alone exceeds in about clutter_share of its bins.
/// A median of the quietest ranges is water's even where the scene's echoes fill more than
/// clutter_share of the bearings at every range (a basin on a 2 m scale).
float waterLevel(const PolarImage& polar, const ColumnProfile& profile, double clutter_share, double span_db) {
  const auto cols = static_cast<int>(profile.median.size());
  std::vector<int> order(static_cast<std::size_t>(cols));
  for (int c = 0; c < cols; ++c) order[static_cast<std::size_t>(c)] = c;
  const auto quiet = static_cast<std::ptrdiff_t>(std::max(1, cols / 4));
  std::nth_element(order.begin(), order.begin() + (quiet - 1), order.end(), [&](int a, int b) {
    return profile.median[static_cast<std::size_t>(a)] < profile.median[static_cast<std::size_t>(b)];
  });
  detail::IntensityHistogram histogram;
  for (std::ptrdiff_t k = 0; k < quiet; ++k) {
    const int c = order[static_cast<std::size_t>(k)];
    for (int r = 0; r < polar.rows(); ++r) {
      if (c < polar.valid_bins[static_cast<std::size_t>(r)]) histogram.add(polar.intensities.at<std::uint8_t>(r, c));
    }
  }
  const double median = histogram.total() == 0 ? 0.0 : histogram.percentile(50.0);
  const double spread_db = levelOfPower(speckleQuantile(1.0 - clutter_share, 1.0) / speckleQuantile(0.5, 1.0));
  return static_cast<float>(median + countsForDb(spread_db, span_db));
}

/// Per column: the share of the rows covering it whose level is above `level` counts (0 where no
/// row covers it).
std::vector<double> echoPersistence(const PolarImage& polar, float level) {
  const auto cols = static_cast<std::size_t>(polar.cols());
  // Whole counts per column (the rows above the level, the rows covering it), divided at the end.
  std::vector<int> rows_above(cols, 0), rows_covering(cols, 0);
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int valid = std::min(polar.cols(), polar.valid_bins[static_cast<std::size_t>(r)]);
    for (int c = 0; c < valid; ++c) {
      const auto i = static_cast<std::size_t>(c);
      ++rows_covering[i];
      rows_above[i] += static_cast<float>(row[c]) > level ? 1 : 0;
    }
  }
  std::vector<double> persistence(cols, 0.0);
  for (std::size_t c = 0; c < cols; ++c) {
    if (rows_covering[c] > 0) persistence[c] = static_cast<double>(rows_above[c]) / rows_covering[c];
  }
  return persistence;
}

/// The housing's outer edge, in bins: the first column after the persistence's peak within
/// [0, near_bins) where it falls under 1 − clutter_share (no longer nearly every beam) or under
/// half-way from the peak to the scene's (its median over the columns from near_bins on); 0 when
/// the peak is under 1 − clutter_share or not clutter_share above the scene's.
int housingEnd(const std::vector<double>& persistence, int near_bins, double clutter_share) {
  const auto cols = static_cast<int>(persistence.size());
  near_bins = std::clamp(near_bins, 0, cols);
  if (near_bins == 0) return 0;
  const auto first = persistence.begin();
  const auto peak = std::max_element(first, first + near_bins);
  std::vector<double> scene(first + near_bins, persistence.end());
  double scene_share = 0.0;
  if (!scene.empty()) {
    const auto middle = scene.begin() + static_cast<std::ptrdiff_t>(scene.size() / 2);
    std::nth_element(scene.begin(), middle, scene.end());
    scene_share = *middle;
  }
  // A housing is in nearly every beam, and in more of them than the scene's echoes are.
  if (*peak < 1.0 - clutter_share || *peak - scene_share <= clutter_share) return 0;
  const double edge = std::max(1.0 - clutter_share, 0.5 * (*peak + scene_share));
  int c = static_cast<int>(peak - first);
  while (c < near_bins && persistence[static_cast<std::size_t>(c)] >= edge) ++c;
  return c;
}

/// The ring-down (SweepCalibration::ring_down): the median profile from its peak within the head's
/// own band [0, head_end) (the self-reflection band or the housing's) while it stands above `water`,
/// its unsaturated part (under 250 counts) beyond `band_end` fitted by a least-squares line and
/// carried on along it up to near_bins; none without a band or a housing, when the peak is not
/// `significant` over the water, or when the decline has fewer than 3 such columns or does not fall.
void fitRingDown(const ColumnProfile& profile, float water, float significant, int band_end, int head_end, int near_bins,
                 SweepCalibration& calibration) {
  const auto cols = static_cast<int>(profile.median.size());
  near_bins = std::clamp(near_bins, 0, cols);
  head_end = std::min(head_end, near_bins);
  if (head_end <= 0) return;
  const auto first = profile.median.begin();
  const int peak = static_cast<int>(std::max_element(first, first + head_end) - first);
  if (profile.median[static_cast<std::size_t>(peak)] - water < significant) return;
  constexpr float kSaturated = 250.0f;
  int begin = -1, end = peak;
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (; end < near_bins && profile.median[static_cast<std::size_t>(end)] > water; ++end) {
    const float y = profile.median[static_cast<std::size_t>(end)];
    if (y >= kSaturated || end < band_end) continue;
    if (begin < 0) begin = end;
    n += 1.0, sx += end, sy += y, sxx += static_cast<double>(end) * end, sxy += static_cast<double>(end) * y;
  }
  if (n < 3.0) return;
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  if (!(slope < 0.0)) return;
  const double intercept = (sy - slope * sx) / n;
  calibration.ring_down.resize(static_cast<std::size_t>(near_bins));
  for (int c = 0; c < near_bins; ++c) {
    const auto i = static_cast<std::size_t>(c);
    calibration.ring_down[i] = c < end ? profile.median[i] : static_cast<float>(intercept + slope * c);
  }
  calibration.ring_fit_begin = begin;
  calibration.ring_fit_end = end;
}

}  // namespace

void CalibrationOptions::validate() const {
  if (!(background_percentile >= 0.0 && background_percentile <= 100.0)) {
    throwOption("the background percentile must be in [0, 100]");
  }
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 0.5)) {
    throwOption("the false-alarm probability must be in (0, 0.5)");
  }
  if (!(std::isfinite(min_contrast_db) && min_contrast_db >= 0.0)) throwOption("the minimum contrast must be >= 0 dB");
  if (!(clutter_share > 0.0 && clutter_share <= 0.5)) throwOption("the clutter share must be in (0, 0.5]");
  if (!(std::isfinite(max_gap_m) && max_gap_m >= 0.0)) throwOption("the near-field gap must be >= 0 m");
  if (!(max_near_field_m >= 0.0)) throwOption("the near field's largest extent must be >= 0 m");
  if (!(std::isfinite(ring_window_pulses) && ring_window_pulses >= 1.0)) throwOption("the ring window must be >= 1 pulse length");
}

namespace {
/// The level of one-look speckle (exponential power, acoustics/speckle.hpp) that the background
/// percentile stands for, relative to the mean power (at least 10⁻³ of it: a 0th percentile).
double backgroundQuantile(const CalibrationOptions& options) {
  return std::max(speckleQuantile(options.background_percentile / 100.0, 1.0), 1e-3);
}
}  // namespace

double clutterLevelDb(const CalibrationOptions& options) {
  options.validate();
  // The level speckle exceeds with a quarter of the clutter share's probability.
  return levelOfPower(speckleSurvivalQuantile(0.25 * options.clutter_share, 1.0) / backgroundQuantile(options));
}

double thresholdDb(const CalibrationOptions& options) {
  options.validate();
  // The level one-look speckle exceeds with probability Pfa over its background percentile, in dB.
  const double speckle_db =
      levelOfPower(speckleSurvivalQuantile(options.false_alarm_probability, 1.0) / backgroundQuantile(options));
  return std::max(options.min_contrast_db, speckle_db);
}

double thresholdDb(const CalibrationOptions& options, double percentile) {
  CalibrationOptions at = options;
  at.background_percentile = percentile;
  if (!(percentile > 0.0 && percentile < 100.0)) throwOption("the level's percentile must be in (0, 100)");
  return thresholdDb(at);
}

SweepCalibration calibrateSweep(const PolarImage& polar, const CalibrationOptions& options, double span_db) {
  if (polar.intensities.type() != CV_8UC1) throwOption("the polar image must be CV_8UC1");
  if (!(polar.bin_length_m > 0.0) || !std::isfinite(polar.bin_length_m)) throwOption("bin_length_m must be > 0 m");
  if (static_cast<int>(polar.valid_bins.size()) != polar.rows()) throwOption("valid_bins must hold one entry per row");
  SweepCalibration calibration;
  calibration.span_db = span_db;
  calibration.threshold_db = thresholdDb(options);
  const auto threshold = static_cast<float>(countsForDb(calibration.threshold_db, span_db));
  const ColumnProfile profile = profileColumns(polar, options);
  calibration.background = profile.background;
  calibration.threshold.resize(calibration.background.size());
  for (std::size_t c = 0; c < calibration.threshold.size(); ++c) {
    calibration.threshold[c] = threshold;
  }
  const int band = bandEnd(profile, threshold);
  const int gap = binsForLength(options.max_gap_m, polar.bin_length_m, 1, std::max(1, polar.cols()));
  const auto clutter_level = static_cast<float>(countsForDb(clutterLevelDb(options), span_db));
  // The vehicle's own body lies within max_near_field_m of the head: what returns in many bearings
  // farther out (a basin's floor seen down a slope) is the scene, and is left to the detector.
  const int near_limit = binsForLength(options.max_near_field_m, polar.bin_length_m, 0, std::max(0, polar.cols()));
  const int max_near_field = near_limit;
  const float water = waterLevel(polar, profile, options.clutter_share, span_db);
  calibration.quiet_water_counts = water;
  const int housing =
      housingEnd(echoPersistence(polar, water), std::min(near_limit, polar.cols() / 4), options.clutter_share);
  const int near_start = std::max(band, housing);
  const int near_field = std::min(nearFieldEnd(profile, clutter_level, near_start, gap), max_near_field);
  fitRingDown(profile, water, threshold, band, near_start, max_near_field, calibration);
  calibration.band_end_m = std::min(band, max_near_field) * polar.bin_length_m;
  calibration.housing_end_m = housing * polar.bin_length_m;
  calibration.near_field_end_m = near_field * polar.bin_length_m;
  // Beyond the near field, a ring in B(c) that blocks the beams is a wall around the head.
  const double look_m = polar.pulse_length_m ? std::max(*polar.pulse_length_m, polar.bin_length_m) : polar.bin_length_m;
  const int ring_window = binsForLength(options.ring_window_pulses * look_m, polar.bin_length_m, 1, std::max(1, polar.cols()));
  const std::vector<float> with_rings = calibration.background;
  const int look_bins = binsForLength(look_m, polar.bin_length_m, 1, std::max(1, polar.cols()));
  removeWalls(polar, calibration.background, near_field, ring_window, look_bins, threshold);
  calibration.background_cap.assign(with_rings.size(), std::numeric_limits<float>::infinity());
  for (std::size_t c = 0; c < with_rings.size(); ++c) {
    if (calibration.background[c] < with_rings[c]) calibration.background_cap[c] = calibration.background[c];
  }
  return calibration;
}

}  // namespace sonarmap
