/// @file reverberation.cpp
/// The local level of a sweep's diffuse echo and the echo span it asks of an obstacle (see
/// reverberation.hpp).

#include "sonarmap/detection/reverberation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "column_histogram.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Each row's level is measured at every (half window) / kStepsPerHalfWindow bins of range and
/// interpolated between: R changes over the window's length, not from bin to bin.
constexpr int kStepsPerHalfWindow = 4;

void requirePositive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw ValueError(std::string("reverberation options: ") + what + " must be finite and > 0");
  }
}

}  // namespace

void ReverberationOptions::validate() const {
  requirePositive(range_looks, "the range window (looks)");
  requirePositive(bearing_beam_widths, "the bearing window (beam widths)");
}

LocalLevel::LocalLevel(const PolarImage& polar, int min_bin, double look_bins, double beam_width_rad,
                       const ReverberationOptions& options) {
  options.validate();
  if (polar.intensities.type() != CV_8UC1) throw ValueError("local level: the polar image must be CV_8UC1");
  const int rows = polar.rows(), cols = polar.cols();
  if (polar.valid_bins.size() != static_cast<std::size_t>(rows) || polar.bearing_rad.size() != static_cast<std::size_t>(rows)) {
    throw ValueError("local level: the polar image needs one valid_bins entry and one bearing per row");
  }
  if (!(look_bins >= 1.0) || !std::isfinite(look_bins)) throw ValueError("local level: look_bins must be >= 1");
  if (!(beam_width_rad >= 0.0)) throw ValueError("local level: the beam width must be >= 0");
  level_ = cv::Mat::zeros(rows, cols, CV_8UC1);
  if (rows == 0 || cols == 0) return;
  // The rows in bearing order, and whether they close a circle.
  sortByBearing(polar);
  const double spacing_rad = beamSpacing_rad(polar);
  if (rows > 2 && spacing_rad > 0.0) {
    const double gap_across_zero_rad = kTwoPi - (bearings_.back() - bearings_.front());
    circular_ = gap_across_zero_rad <= 1.5 * spacing_rad;
  }
  half_rows_ = rowsForAngle(options.bearing_beam_widths * beam_width_rad, spacing_rad, 1, std::max(1, (rows - 1) / 2));
  half_bins_ = std::max(2, static_cast<int>(std::lround(options.range_looks * look_bins)));
  footprint_bins_per_bin_ = 2.0 * beam_width_rad;
  min_bin = std::clamp(min_bin, 0, cols);
  level_ = measure(polar, min_bin);
}

cv::Mat LocalLevel::measure(const PolarImage& polar, int min_bin) const {
  const int rows = polar.rows(), cols = polar.cols();
  cv::Mat level = cv::Mat::zeros(rows, cols, CV_8UC1);
  const int half_rows = half_rows_;
  const int step = std::max(1, half_bins_ / kStepsPerHalfWindow);
  const cv::Mat& image = polar.intensities;
  std::vector<int> window;  // the window's rows
  std::vector<float> measured;
  detail::IntensityHistogram histogram;
  for (int p = 0; p < rows; ++p) {
    window.clear();
    for (int k = -half_rows; k <= half_rows; ++k) {
      int q = p + k;
      if (circular_) {
        q = (q % rows + rows) % rows;
      } else if (q < 0 || q >= rows) {
        continue;
      }
      if (std::find(window.begin(), window.end(), order_[static_cast<std::size_t>(q)]) == window.end()) {
        window.push_back(order_[static_cast<std::size_t>(q)]);
      }
    }
    const int row = order_[static_cast<std::size_t>(p)];
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(row)], cols);
    if (end <= min_bin) continue;
    // Slide the window [centre − half, centre + half] along range in steps (both ends move outwards:
    // the half window grows by at most 2w < 1 bin a bin), adding the columns that enter and removing
    // those that leave, each over the window's rows.
    histogram.clear();
    measured.clear();
    int lo = min_bin, hi = min_bin;  // columns [lo, hi) are in the histogram
    auto addColumn = [&](int c, bool add) {
      for (const int r : window) {
        if (c >= std::min(polar.valid_bins[static_cast<std::size_t>(r)], cols)) continue;
        const std::uint8_t v = image.at<std::uint8_t>(r, c);
        if (add) {
          histogram.add(v);
        } else {
          histogram.remove(v);
        }
      }
    };
    for (int centre = min_bin; centre < end + step - 1; centre += step) {
      const int c = std::min(centre, end - 1);
      const int half = halfWindowBins(c);
      const int want_lo = std::max(min_bin, c - half), want_hi = std::min(cols, c + half + 1);
      for (; hi < want_hi; ++hi) addColumn(hi, true);
      for (; lo < want_lo; ++lo) addColumn(lo, false);
      measured.push_back(histogram.total() > 0 ? histogram.percentile(kLocalLevelPercentile) : 0.0f);
      if (c == end - 1) break;
    }
    // Linear interpolation between the measured columns min_bin + j·step.
    auto* out = level.ptr<std::uint8_t>(row);
    for (int c = min_bin; c < end; ++c) {
      const double at = static_cast<double>(c - min_bin) / step;
      const auto j = static_cast<std::size_t>(at);
      const double t = at - static_cast<double>(j);
      const float a = measured[std::min(j, measured.size() - 1)];
      const float b = measured[std::min(j + 1, measured.size() - 1)];
      out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(a + (b - a) * t, 0.0, 255.0)));
    }
  }
  return level;
}

void LocalLevel::sortByBearing(const PolarImage& polar) {
  auto wrapped = [&](int r) {
    const double b = std::fmod(polar.bearing_rad[static_cast<std::size_t>(r)], kTwoPi);
    return b < 0.0 ? b + kTwoPi : b;
  };
  order_.resize(static_cast<std::size_t>(polar.rows()));
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return wrapped(a) < wrapped(b); });
  bearings_.resize(order_.size());
  position_.assign(order_.size(), 0);
  for (std::size_t i = 0; i < order_.size(); ++i) {
    bearings_[i] = wrapped(order_[i]);
    position_[static_cast<std::size_t>(order_[i])] = static_cast<int>(i);
  }
}

std::array<int, 2> LocalLevel::bearingNeighbours(int row) const {
  const int n = static_cast<int>(order_.size());
  if (row < 0 || row >= n) return {-1, -1};
  const int p = position_[static_cast<std::size_t>(row)];
  auto at = [&](int q) {
    if (q >= 0 && q < n) return order_[static_cast<std::size_t>(q)];
    return circular_ && n > 2 ? order_[static_cast<std::size_t>((q + n) % n)] : -1;
  };
  return {at(p - 1), at(p + 1)};
}

LocalLevel LocalLevel::atBearingsOf(const LocalLevel& kept, const PolarImage& rows) {
  if (rows.bearing_rad.size() != static_cast<std::size_t>(rows.rows())) {
    throw ValueError("local level: the rows need one bearing each");
  }
  LocalLevel out;
  out.level_ = cv::Mat::zeros(rows.rows(), rows.cols(), CV_8UC1);
  for (int r = 0; r < rows.rows(); ++r) {
    auto* level = out.level_.ptr<std::uint8_t>(r);
    for (int c = 0; c < rows.cols(); ++c) {
      level[c] = static_cast<std::uint8_t>(kept.atBearing(rows.bearing_rad[static_cast<std::size_t>(r)], c));
    }
  }
  out.sortByBearing(rows);
  out.half_bins_ = kept.half_bins_;
  out.footprint_bins_per_bin_ = kept.footprint_bins_per_bin_;
  out.half_rows_ = kept.half_rows_;
  return out;
}

float LocalLevel::atBearing(double bearing_rad, int c) const {
  if (empty() || c < 0 || c >= level_.cols || !std::isfinite(bearing_rad)) return 0.0f;
  double b = std::fmod(bearing_rad, kTwoPi);
  if (b < 0.0) b += kTwoPi;
  const auto upper = std::lower_bound(bearings_.begin(), bearings_.end(), b);
  std::size_t best = upper == bearings_.end() ? bearings_.size() - 1 : static_cast<std::size_t>(upper - bearings_.begin());
  auto gap = [&](std::size_t i) { return std::abs(std::remainder(bearings_[i] - b, kTwoPi)); };
  if (best > 0 && gap(best - 1) < gap(best)) best -= 1;
  if (circular_ && gap(0) < gap(best)) best = 0;
  if (circular_ && gap(bearings_.size() - 1) < gap(best)) best = bearings_.size() - 1;
  return level_.at<std::uint8_t>(order_[best], c);
}

int requiredEchoBeams(double unaligned_runs_per_bin, double overlap_bins, double false_alarm_probability, int max_beams) {
  if (!(std::isfinite(unaligned_runs_per_bin) && unaligned_runs_per_bin >= 0.0)) {
    throw ValueError("echo span: the run density must be finite and >= 0");
  }
  if (!(std::isfinite(overlap_bins) && overlap_bins >= 0.0)) throw ValueError("echo span: the overlap must be finite and >= 0");
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0)) {
    throw ValueError("echo span: the false-alarm probability must be in (0, 1)");
  }
  if (max_beams < 1) throw ValueError("echo span: max_beams must be >= 1");
  const double rho = unaligned_runs_per_bin;
  const double q = 1.0 - std::exp(-rho * overlap_bins);
  for (int n = 1; n < max_beams; ++n) {
    if (rho * n * std::pow(q, n - 1) <= false_alarm_probability) return n;
  }
  return max_beams;
}

}  // namespace sonarmap
