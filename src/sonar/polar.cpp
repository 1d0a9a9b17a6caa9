/// @file polar.cpp
/// makePolarImage and makeCartesianImage (see polar.hpp).

#include "sonarmap/sonar/polar.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxCartesianSide_px = 20000;

/// Angle wrapped to [0, 2π).
double wrapPositive(double angle_rad) {
  double a = std::fmod(angle_rad, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a >= kTwoPi ? 0.0 : a;
}

void checkPolarRange(const std::vector<Beam>& beams, std::size_t first, std::size_t last_exclusive) {
  if (first >= last_exclusive || last_exclusive > beams.size()) {
    throw ValueError("polar image: beam range [" + std::to_string(first) + ", " +
                     std::to_string(last_exclusive) + ") is empty or beyond the " +
                     std::to_string(beams.size()) + " beams");
  }
  const double bin_length_m = beams[first].bin_length_m;
  for (std::size_t i = first; i < last_exclusive; ++i) {
    if (beams[i].intensities.empty()) {
      throw ValueError("polar image: beam " + std::to_string(i) + " has no bins");
    }
    if (beams[i].bin_length_m != bin_length_m) {
      throw ValueError("polar image: beam " + std::to_string(i) + " has bin length " +
                       std::to_string(beams[i].bin_length_m) + " m, beam " + std::to_string(first) +
                       " has " + std::to_string(bin_length_m) + " m (one image needs one bin length)");
    }
  }
  if (!(bin_length_m > 0.0)) throw ValueError("polar image: bin length must be > 0 m");
}

/// Rows of a polar image ordered by bearing in [0, 2π), for the angular lookup.
struct BearingIndex {
  std::vector<double> bearing_rad;  ///< sorted, wrapped to [0, 2π)
  std::vector<int> row;             ///< the polar image row of each entry
};

BearingIndex sortByBearing(const PolarImage& polar) {
  std::vector<std::pair<double, int>> entries;
  for (int r = 0; r < polar.rows(); ++r) entries.emplace_back(wrapPositive(polar.bearing_rad[r]), r);
  std::sort(entries.begin(), entries.end());
  BearingIndex index;
  for (const auto& [bearing, row] : entries) {
    index.bearing_rad.push_back(bearing);
    index.row.push_back(row);
  }
  return index;
}

/// Intensity of pixel at bearing `theta` (wrapped) and bin `bin`, by angle interpolation.
double interpolateInAngle(const PolarImage& polar, const BearingIndex& index, double theta, int bin,
                          double beam_width_rad) {
  const auto& b = index.bearing_rad;
  const std::size_t n = b.size();
  const std::size_t upper = static_cast<std::size_t>(std::upper_bound(b.begin(), b.end(), theta) - b.begin());
  const std::size_t next = upper % n;            // first bearing > theta, circularly
  const std::size_t prev = (upper + n - 1) % n;  // last bearing ≤ theta, circularly
  const auto value = [&](std::size_t k) {
    return static_cast<double>(polar.intensities.at<std::uint8_t>(index.row[k], bin));
  };
  const double gap = n == 1 ? 0.0 : wrapPositive(b[next] - b[prev]);
  const double from_prev = wrapPositive(theta - b[prev]);
  if (gap > 0.0 && gap <= beam_width_rad) {
    const double w = from_prev / gap;
    return (1.0 - w) * value(prev) + w * value(next);
  }
  if (from_prev <= 0.5 * beam_width_rad) return value(prev);
  if (wrapPositive(b[next] - theta) <= 0.5 * beam_width_rad) return value(next);
  return 0.0;
}

void checkCartesianArguments(const PolarImage& polar, double pixel_size_m, double beam_width_rad) {
  if (polar.intensities.empty() || polar.intensities.type() != CV_8UC1 ||
      static_cast<int>(polar.bearing_rad.size()) != polar.rows()) {
    throw ValueError("Cartesian image: the polar image is empty, not CV_8UC1, or lacks bearings");
  }
  if (!(polar.bin_length_m > 0.0) || !std::isfinite(polar.bin_length_m)) {
    throw ValueError("Cartesian image: bin_length_m must be > 0 m");
  }
  if (!(pixel_size_m > 0.0) || !std::isfinite(pixel_size_m)) {
    throw ValueError("Cartesian image: pixel_size_m must be > 0 m, got " + std::to_string(pixel_size_m));
  }
  if (!(beam_width_rad > 0.0) || beam_width_rad > kTwoPi) {
    throw ValueError("Cartesian image: beam_width_rad must be in (0, 2π], got " +
                     std::to_string(beam_width_rad));
  }
}

}  // namespace

PolarImage makePolarImage(const std::vector<Beam>& beams, std::size_t first, std::size_t last_exclusive) {
  checkPolarRange(beams, first, last_exclusive);
  std::size_t cols = 0;
  for (std::size_t i = first; i < last_exclusive; ++i) cols = std::max(cols, beams[i].intensities.size());
  PolarImage polar;
  polar.bin_length_m = beams[first].bin_length_m;
  polar.intensity_span_db = beams[first].intensity_span_db;
  for (std::size_t i = first; i < last_exclusive; ++i) {
    const std::optional<double>& pulse_m = beams[i].pulse_length_m;
    if (pulse_m && (!polar.pulse_length_m || *pulse_m < *polar.pulse_length_m)) polar.pulse_length_m = pulse_m;
  }
  polar.intensities = cv::Mat::zeros(static_cast<int>(last_exclusive - first), static_cast<int>(cols), CV_8UC1);
  for (std::size_t i = first; i < last_exclusive; ++i) {
    const Beam& beam = beams[i];
    std::copy(beam.intensities.begin(), beam.intensities.end(),
              polar.intensities.ptr<std::uint8_t>(static_cast<int>(i - first)));
    polar.valid_bins.push_back(static_cast<int>(beam.intensities.size()));
    polar.bearing_rad.push_back(beam.bearing_rad);
    polar.time_s.push_back(beam.time_s);
  }
  return polar;
}

cv::Mat makeCartesianImage(const PolarImage& polar, double pixel_size_m, double beam_width_rad) {
  checkCartesianArguments(polar, pixel_size_m, beam_width_rad);
  const double max_range_m = polar.cols() * polar.bin_length_m;
  const double half_side = std::ceil(max_range_m / pixel_size_m);
  if (2.0 * half_side + 1.0 > kMaxCartesianSide_px) {
    throw ValueError("Cartesian image: the image would exceed " + std::to_string(kMaxCartesianSide_px) +
                     " pixels a side; use a larger pixel_size_m");
  }
  const int centre = static_cast<int>(half_side);
  const int side = 2 * centre + 1;
  const BearingIndex index = sortByBearing(polar);
  cv::Mat image = cv::Mat::zeros(side, side, CV_8UC1);
  for (int v = 0; v < side; ++v) {
    auto* out = image.ptr<std::uint8_t>(v);
    const double x = (centre - v) * pixel_size_m;  // sonar +x (ahead) up
    for (int u = 0; u < side; ++u) {
      const double y = (u - centre) * pixel_size_m;  // sonar +y (starboard) right: seen from above
      const int bin = static_cast<int>(std::floor(std::hypot(x, y) / polar.bin_length_m));
      if (bin >= polar.cols()) continue;
      const double theta = wrapPositive(std::atan2(y, x));
      out[u] = cv::saturate_cast<std::uint8_t>(interpolateInAngle(polar, index, theta, bin, beam_width_rad));
    }
  }
  return image;
}

}  // namespace sonarmap
