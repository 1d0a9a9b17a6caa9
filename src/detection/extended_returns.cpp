/// @file extended_returns.cpp
/// Binary integration of the whole echo against the sweep's background (see extended_returns.hpp).

#include "sonarmap/detection/extended_returns.hpp"

#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/speckle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"

namespace sonarmap {
namespace {

/// P(X ≥ m) for X binomial with n trials of probability p.
double binomialTail(int n, double p, int m) {
  double tail = 0.0;
  for (int k = std::max(m, 0); k <= n; ++k) {
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) + k * std::log(p) +
                     (n - k) * std::log1p(-p));
  }
  return tail;
}

/// Where the return starts within [begin, end): the split s that makes the lit bins of the window's
/// rows likeliest as noise (lit with probability p₀) before s and as one return (its own lit
/// rate, estimated) from s on: the maximum-likelihood change point of a Bernoulli sequence
/// (Hinkley 1970, Biometrika 57, 1). The first window that holds a return may begin up to a
/// window before it, on a noise bin lit by chance.
int changePoint(int begin, int end, const std::vector<int>& rows, const std::vector<std::vector<int>>& lit_before, double p0) {
  const double trials_per_bin = static_cast<double>(rows.size());
  auto lit = [&](int from, int to) {
    int n = 0;
    for (const int j : rows) n += lit_before[static_cast<std::size_t>(j)][to] - lit_before[static_cast<std::size_t>(j)][from];
    return static_cast<double>(n);
  };
  auto logLikelihood = [](double k, double n, double p) {
    return (k > 0.0 ? k * std::log(p) : 0.0) + (n - k > 0.0 ? (n - k) * std::log1p(-p) : 0.0);
  };
  int best = begin;
  double best_ll = -std::numeric_limits<double>::infinity();
  for (int split = begin; split < end; ++split) {
    const double k_noise = lit(begin, split), n_noise = (split - begin) * trials_per_bin;
    const double k_echo = lit(split, end), n_echo = (end - split) * trials_per_bin;
    const double rate = std::clamp(k_echo / n_echo, p0, 1.0 - 1e-12);
    const double ll = logLikelihood(k_noise, n_noise, p0) + logLikelihood(k_echo, n_echo, rate);
    if (ll > best_ll) {
      best_ll = ll;
      best = split;
    }
  }
  return best;
}

/// Half the bearing window, radians (ExtendedReturnOptions::bearing_window_deg).
double halfWindow_rad(const ExtendedReturnOptions& options) { return 0.5 * options.bearing_window_deg * std::numbers::pi / 180.0; }

/// A count of lit bins from a fractional one: rounded up (less 1e-9, so that a product meant to be
/// whole is not raised by its rounding error), at least 1.
int wholeCountOf(double lit_bins) { return std::max(1, static_cast<int>(std::ceil(lit_bins - 1e-9))); }

}  // namespace

double binsPerLookFromRuns(std::size_t lit, std::size_t runs, double lit_probability) {
  if (runs == 0) return 1.0;
  return std::max(1.0, static_cast<double>(lit) / static_cast<double>(runs) * (1.0 - lit_probability));
}

void ExtendedReturnOptions::validate() const {
  if (!(bin_false_alarm > 0.0 && bin_false_alarm < 0.5)) {
    throw ValueError("extended returns: bin_false_alarm must be in (0, 0.5)");
  }
  if (!(window_looks >= 2.0) || !std::isfinite(window_looks)) throw ValueError("extended returns: window_looks must be >= 2");
  if (!(false_alarm_per_beam > 0.0 && false_alarm_per_beam < 0.5)) {
    throw ValueError("extended returns: false_alarm_per_beam must be in (0, 0.5)");
  }
  if (!(bearing_window_deg >= 0.0 && bearing_window_deg <= 360.0)) {
    throw ValueError("extended returns: bearing_window_deg must be in [0, 360]");
  }
}

ExtendedReturnCalibration calibrateExtendedReturns(const PolarImage& polar, const std::vector<float>& background_counts,
                                                   double background_percentile, double span_db, double min_range_m,
                                                   const ExtendedReturnOptions& options,
                                                   const std::vector<EchoBins>& echoes) {
  options.validate();
  if (!echoes.empty() && echoes.size() != static_cast<std::size_t>(polar.rows())) {
    throw ValueError("extended returns: " + std::to_string(echoes.size()) + " echo ranges for " +
                     std::to_string(polar.rows()) + " beams");
  }
  if (!(span_db > 0.0) || !std::isfinite(span_db)) throw ValueError("extended returns: span_db must be > 0");
  if (!(background_percentile > 0.0 && background_percentile < 100.0)) {
    throw ValueError("extended returns: background_percentile must be in (0, 100)");
  }
  if (!(min_range_m >= 0.0)) throw ValueError("extended returns: min_range_m must be >= 0");
  if (background_counts.size() > static_cast<std::size_t>(polar.cols())) {
    throw ValueError("extended returns: the background has more columns than the sweep has bins");
  }
  const double counts_per_db = 255.0 / span_db;
  const double p0 = options.bin_false_alarm;
  const double p = background_percentile / 100.0;
  const std::size_t columns = background_counts.size();
  const auto first = static_cast<std::size_t>(std::max(0.0, std::ceil(min_range_m / polar.bin_length_m - 0.5)));
  // Columns above the A/D floor: their background is the noise's p-quantile (or a surface's, if
  // one lights most bearings at that range: then it is not sought there).
  auto noise_column = [&](std::size_t c) { return background_counts[c] > 0.0F; };
  auto bin = [&](int row, std::size_t c) -> double { return polar.intensities.at<std::uint8_t>(row, static_cast<int>(c)); };
  // A bin the noise is measured on: recorded, and outside the row's known echo.
  auto valid = [&](int row, std::size_t c) {
    if (static_cast<int>(c) >= polar.valid_bins[static_cast<std::size_t>(row)]) return false;
    if (echoes.empty()) return true;
    const EchoBins& echo = echoes[static_cast<std::size_t>(row)];
    return static_cast<int>(c) < echo.begin || static_cast<int>(c) >= echo.end;
  };
  ExtendedReturnCalibration calibration;
  std::vector<double> excess;
  for (std::size_t c = first; c < columns; ++c) {
    if (!noise_column(c)) continue;
    ++calibration.noise_columns;
    for (int row = 0; row < polar.rows(); ++row) {
      if (valid(row, c)) excess.push_back(bin(row, c) - background_counts[c]);
    }
  }
  // One-look speckle's level exceeded with probability p₀ over its background percentile, in counts.
  double tau_counts = levelOfPower(speckleSurvivalQuantile(p0, 1.0) / speckleQuantile(p, 1.0)) * counts_per_db;
  calibration.measured = calibration.noise_columns >= 8 && excess.size() >= 1000;
  if (calibration.measured) tau_counts = percentile(excess, 1.0 - p0);
  calibration.lit_counts.assign(columns, 255.0F);  // nothing is lit before the minimum range
  std::vector<std::size_t> histogram(256);
  for (std::size_t c = first; c < columns; ++c) {
    calibration.lit_counts[c] = static_cast<float>(std::max(0.5, background_counts[c] + tau_counts));
    if (background_counts[c] > 0.0F) continue;
    // Noise under the A/D floor: the column's own (1 − p₀) quantile over the bearings bounds the lit level.
    std::fill(histogram.begin(), histogram.end(), 0);
    std::size_t count = 0;
    for (int row = 0; row < polar.rows(); ++row) {
      if (!valid(row, c)) continue;
      ++histogram[polar.intensities.at<std::uint8_t>(row, static_cast<int>(c))];
      ++count;
    }
    const auto allowed = static_cast<std::size_t>(p0 * static_cast<double>(count));
    std::size_t above = 0;
    int level = 255;
    while (level > 0 && above + histogram[static_cast<std::size_t>(level)] <= allowed) {
      above += histogram[static_cast<std::size_t>(level--)];
    }
    calibration.lit_counts[c] = std::max(calibration.lit_counts[c], static_cast<float>(level) + 0.5F);
  }
  // Bins per look: the mean run of lit bins on the noise columns against 1 / (1 − p₀); rows per
  // look the same across neighbouring bearings (overlapping beams see correlated speckle).
  const int rows = polar.rows();
  std::size_t lit = 0, runs = 0, row_lit = 0, row_runs = 0;
  for (std::size_t c = std::max<std::size_t>(first, 1); c < columns; ++c) {
    if (!noise_column(c)) continue;
    for (int row = 0; row < rows; ++row) {
      if (!valid(row, c)) continue;
      const bool here = bin(row, c) > calibration.lit_counts[c];
      const bool before = valid(row, c - 1) && bin(row, c - 1) > calibration.lit_counts[c - 1];
      const bool previous_row = row > 0 && valid(row - 1, c) && bin(row - 1, c) > calibration.lit_counts[c];
      lit += here ? 1 : 0;
      runs += here && !before ? 1 : 0;
      if (row > 0) {
        row_lit += here ? 1 : 0;
        row_runs += here && !previous_row ? 1 : 0;
      }
    }
  }
  if (calibration.measured) {
    calibration.bins_per_look = binsPerLookFromRuns(lit, runs, p0);
    calibration.rows_per_look = binsPerLookFromRuns(row_lit, row_runs, p0);
  }
  // Rows of the window: the neighbours within bearing_window_deg / 2 at the sweep's median step.
  std::vector<double> steps;
  for (int row = 1; row < rows; ++row) {
    const double d = std::abs(std::remainder(polar.bearing_rad[row] - polar.bearing_rad[row - 1], 2.0 * std::numbers::pi));
    if (d > 0.0) steps.push_back(d);
  }
  const double step_rad = steps.empty() ? 0.0 : percentile(steps, 0.5);
  const double half_window_rad = halfWindow_rad(options);
  calibration.half_window_rows = step_rad > 0.0 ? static_cast<int>(std::floor(half_window_rad / step_rad + 1e-9)) : 0;
  const double window_rows = 2.0 * calibration.half_window_rows + 1.0;
  calibration.window_bins = std::max(1, static_cast<int>(std::lround(options.window_looks * calibration.bins_per_look)));
  const int looks = std::max(1, static_cast<int>(std::lround(options.window_looks * std::max(1.0, window_rows / calibration.rows_per_look))));
  const double windows = std::max(1.0, static_cast<double>(columns) / calibration.window_bins);
  int needed = looks;
  while (needed > 1 && windows * binomialTail(looks, p0, needed - 1) <= options.false_alarm_per_beam) --needed;
  int to_continue = needed;  // the same rate for one window alone
  while (to_continue > 1 && binomialTail(looks, p0, to_continue - 1) <= options.false_alarm_per_beam) --to_continue;
  // Lit bins the window needs: the looks' share of its bins.
  const double bins_in_window = calibration.window_bins * window_rows;
  auto litBins = [&](int lit_looks) { return wholeCountOf(lit_looks * bins_in_window / looks); };
  calibration.lit_needed = litBins(needed);
  calibration.lit_to_continue = litBins(to_continue);
  return calibration;
}

namespace {

/// One pass of steps 3 and 4 (see extended_returns.hpp) over the sweep with `calibration`: gives
/// each beam its extended return in `detections`; returns how many beams without an obstacle got one.
std::size_t detectReturns(const PolarImage& polar, const ExtendedReturnCalibration& calibration,
                          const ExtendedReturnOptions& options, std::vector<BeamDetection>& detections) {
  const int window = calibration.window_bins;
  const int rows = polar.rows();
  const int columns = static_cast<int>(calibration.lit_counts.size());
  // Lit bins before each column, per row.
  std::vector<std::vector<int>> lit_before(static_cast<std::size_t>(rows));
  for (int row = 0; row < rows; ++row) {
    const int bins = std::min<int>(polar.valid_bins[static_cast<std::size_t>(row)], columns);
    const std::uint8_t* intensities = polar.intensities.ptr<std::uint8_t>(row);
    std::vector<int>& before = lit_before[static_cast<std::size_t>(row)];
    before.assign(static_cast<std::size_t>(std::max(bins, 0)) + 1, 0);
    for (int c = 0; c < bins; ++c) {
      before[c + 1] = before[c] + (intensities[c] > calibration.lit_counts[static_cast<std::size_t>(c)] ? 1 : 0);
    }
  }
  const double half_window_rad = halfWindow_rad(options) + 1e-9;
  std::vector<int> neighbours;
  std::size_t found = 0;
  for (int row = 0; row < rows; ++row) {
    BeamDetection& detection = detections[static_cast<std::size_t>(row)];
    // A beam with an obstacle: the run that starts with its obstacle's echo, if any.
    const bool obstacle = detection.hasObstacle();
    const int obstacle_bin = obstacle ? static_cast<int>(detection.range_m / polar.bin_length_m) : 0;
    // The window's rows: this beam and its neighbours in bearing; their common valid bins.
    neighbours.assign(1, row);
    for (int k = 1; k <= calibration.half_window_rows; ++k) {
      for (const int j : {row - k, row + k}) {
        if (j < 0 || j >= rows) continue;
        const double gap = std::abs(std::remainder(polar.bearing_rad[j] - polar.bearing_rad[row], 2.0 * std::numbers::pi));
        if (gap <= half_window_rad) neighbours.push_back(j);
      }
    }
    int bins = static_cast<int>(lit_before[static_cast<std::size_t>(row)].size()) - 1;
    for (const int j : neighbours) bins = std::min(bins, static_cast<int>(lit_before[static_cast<std::size_t>(j)].size()) - 1);
    if (bins < window) continue;
    // The threshold scales with the rows the window has (fewer at a sector's ends).
    const double rows_share = neighbours.size() / (2.0 * calibration.half_window_rows + 1.0);
    auto scaled = [&](int lit) { return wholeCountOf(lit * rows_share); };
    const int needed = scaled(calibration.lit_needed), to_continue = scaled(calibration.lit_to_continue);
    auto count = [&](int c) {
      int n = 0;
      for (const int j : neighbours) n += lit_before[static_cast<std::size_t>(j)][c + window] - lit_before[static_cast<std::size_t>(j)][c];
      return n;
    };
    const std::vector<int>& own = lit_before[static_cast<std::size_t>(row)];
    int c = obstacle ? std::max(0, obstacle_bin - window + 1) : 0;
    while (c + window <= bins && count(c) < needed) ++c;
    if (c + window > bins || (obstacle && c > obstacle_bin)) continue;
    const int start = c;
    while (c + 1 + window <= bins && count(c + 1) >= to_continue) ++c;  // the run of windows that go on with it
    const int onset = changePoint(start, std::min(c + window, start + 2 * window), neighbours, lit_before,
                                  options.bin_false_alarm);
    int last = c + window - 1;
    while (last > onset && own[last + 1] == own[last]) --last;  // its last lit bin
    detection.extended_onset_m = (onset + 0.5) * polar.bin_length_m;
    detection.extended_end_m = (last + 0.5) * polar.bin_length_m;
    if (obstacle) continue;  // its echo onset stays the detector's
    detection.echo_onset_m = std::min(detection.echo_onset_m, detection.extended_onset_m);
    ++found;
  }
  return found;
}

/// The bins of each beam's echo: from its obstacle, or from its extended return's onset, to the
/// farthest of the return's end and where the loud echo falls back; none for a beam with neither.
std::vector<EchoBins> echoBins(const PolarImage& polar, const std::vector<BeamDetection>& detections) {
  std::vector<EchoBins> echoes(detections.size());
  auto binOf = [&](double range_m) { return static_cast<int>(range_m / polar.bin_length_m); };
  for (std::size_t row = 0; row < detections.size(); ++row) {
    const BeamDetection& detection = detections[row];
    const bool obstacle = detection.hasObstacle();
    if (!obstacle && !detection.hasExtendedReturn()) continue;
    const double begin_m = obstacle ? detection.range_m : detection.extended_onset_m;
    double end_m = begin_m;
    if (detection.hasExtendedReturn()) end_m = std::max(end_m, detection.extended_end_m);
    if (obstacle && detection.echo_end_m > end_m) end_m = detection.echo_end_m;
    echoes[row] = {binOf(begin_m), binOf(end_m) + 1};
  }
  return echoes;
}

}  // namespace

std::size_t addExtendedReturns(const PolarImage& polar, double background_percentile, SweepDetection& sweep,
                               const ExtendedReturnOptions& options) {
  if (sweep.detections.size() != static_cast<std::size_t>(polar.rows())) {
    throw ValueError("extended returns: the sweep has " + std::to_string(sweep.detections.size()) +
                     " detections for " + std::to_string(polar.rows()) + " beams");
  }
  const double start_m = std::max(sweep.min_range_m, sweep.calibration.near_field_end_m);
  auto calibrate = [&](const std::vector<EchoBins>& echoes) {
    return calibrateExtendedReturns(polar, sweep.calibration.background, background_percentile, sweep.calibration.span_db,
                                    start_m, options, echoes);
  };
  // A first pass on the whole sweep finds the returns that stand out over its bins; the second
  // measures the noise without them (and without the obstacles' echoes) and looks again.
  std::vector<BeamDetection> first = sweep.detections;
  detectReturns(polar, calibrate({}), options, first);
  return detectReturns(polar, calibrate(echoBins(polar, first)), options, sweep.detections);
}

}  // namespace sonarmap
