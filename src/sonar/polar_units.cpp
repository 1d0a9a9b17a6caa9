/// @file polar_units.cpp
/// Metres, radians and dB on a polar image (see polar_units.hpp).

#include "sonarmap/sonar/polar_units.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void checkBinLength(double bin_length_m, const char* function) {
  if (!(std::isfinite(bin_length_m) && bin_length_m > 0.0)) {
    throw ValueError(std::string(function) + ": the bin length must be a finite number of metres > 0, got " +
                     std::to_string(bin_length_m));
  }
}

/// round(value) clamped to [lo, hi] without converting an out-of-range double to int.
int roundClamped(double value, int lo, int hi) {
  if (!(value >= lo)) return lo;  // also NaN
  if (value >= hi) return hi;
  return std::clamp(static_cast<int>(std::lround(value)), lo, hi);
}

}  // namespace

int binsForLength(double length_m, double bin_length_m, int min_bins, int max_bins) {
  checkBinLength(bin_length_m, "binsForLength");
  if (!(length_m >= 0.0)) throw ValueError("the length must be >= 0 m, got " + std::to_string(length_m));
  if (min_bins > max_bins) throw ValueError("min_bins exceeds max_bins");
  return roundClamped(length_m / bin_length_m, min_bins, max_bins);
}

int firstBinAtOrBeyond(double range_m, double bin_length_m, int max_bin) {
  checkBinLength(bin_length_m, "firstBinAtOrBeyond");
  if (!(range_m >= 0.0)) throw ValueError("the range must be >= 0 m, got " + std::to_string(range_m));
  const double limit = std::ceil(range_m / bin_length_m - 0.5);  // centres (i + 0.5) L >= range
  if (limit >= max_bin) return std::max(0, max_bin);
  return std::clamp(static_cast<int>(limit), 0, std::max(0, max_bin));
}

double beamSpacing_rad(const PolarImage& polar) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < polar.bearing_rad.size(); ++i) {
    const double step = std::abs(std::remainder(polar.bearing_rad[i] - polar.bearing_rad[i - 1], 2.0 * std::numbers::pi));
    if (step > 0.0) steps.push_back(step);
  }
  if (steps.empty()) return 0.0;
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

int rowsForAngle(double angle_rad, double spacing_rad, int min_rows, int max_rows) {
  if (!(angle_rad >= 0.0)) throw ValueError("the angle must be >= 0, got " + std::to_string(angle_rad));
  if (min_rows > max_rows) throw ValueError("min_rows exceeds max_rows");
  if (!(spacing_rad > 0.0)) return min_rows;
  return roundClamped(angle_rad / spacing_rad, min_rows, max_rows);
}

double intensitySpan_db(const PolarImage& polar) {
  return polar.intensity_span_db.value_or(kDefaultIntensitySpan_db);
}

double countsForDb(double level_db, double span_db) {
  if (!(level_db >= 0.0)) throw ValueError("the level must be >= 0 dB, got " + std::to_string(level_db));
  if (!(std::isfinite(span_db) && span_db > 0.0)) {
    throw ValueError("the intensity span must be a finite number of dB > 0, got " + std::to_string(span_db));
  }
  return level_db * 255.0 / span_db;
}

}  // namespace sonarmap
