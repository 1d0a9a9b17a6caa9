/// @file first_returns.cpp
/// A log's first returns and how many a map holds (see first_returns.hpp).

#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/eval/first_returns.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

[[noreturn]] void throwOption(const std::string& what) { throw ValueError("first returns: " + what); }

void requirePositive(double value, const char* what) {
  if (!(std::isfinite(value) && value > 0.0)) throwOption(std::string(what) + " must be a finite number > 0");
}

/// The first return's bin of `beam`, or −1 (see first_returns.hpp).
int firstReturnBin(const Beam& beam, const FirstReturnOptions& options) {
  const auto bins = static_cast<int>(beam.intensities.size());
  if (bins == 0 || !(beam.bin_length_m > 0.0)) return -1;
  const int front = std::max(8, static_cast<int>(std::lround(options.front_m / beam.bin_length_m)));
  const int stay = std::max(2, static_cast<int>(std::lround(options.stay_m / beam.bin_length_m)));
  const double span_db = beam.intensity_span_db.value_or(kDefaultIntensitySpan_db);
  const double rise = countsForDb(options.rise_db, span_db);
  const std::uint8_t* values = beam.intensities.data();
  std::vector<std::uint8_t> window(static_cast<std::size_t>(front));
  for (int c = front; c + stay <= bins; ++c) {
    std::copy(values + c - front, values + c, window.begin());
    const auto q90 = window.begin() + static_cast<std::ptrdiff_t>(std::lround(0.9 * (front - 1)));
    std::nth_element(window.begin(), q90, window.end());
    const double level = *q90 + rise;
    if (values[c] < level || values[c + 1] < level) continue;
    double sum = 0.0;
    for (int k = c; k < c + stay; ++k) sum += values[k];
    if (sum / stay >= level) return c;
  }
  return -1;
}

/// Whether an occupied voxel of `map` lies in the wedge of a beam at `bearing_rad` from
/// `sonar_to_map`, within `tolerance_m` of `range_m` and of the beam's plane.
bool wedgeHoldsOccupied(const OcTree16& map, const Eigen::Isometry3d& sonar_to_map, double bearing_rad, double range_m,
                        double width_rad, double tolerance_m) {
  const double voxel_m = map.resolution_m();
  const double half_width_rad = 0.5 * width_rad;
  const int across = std::max(1, static_cast<int>(std::ceil(width_rad * range_m / (0.5 * voxel_m))));
  const int along = std::max(1, static_cast<int>(std::ceil(2.0 * tolerance_m / (0.5 * voxel_m))));
  const int up = std::max(1, static_cast<int>(std::ceil(2.0 * tolerance_m / (0.5 * voxel_m))));
  for (int a = 0; a <= across; ++a) {
    const double angle = bearing_rad - half_width_rad + width_rad * a / across;
    for (int k = 0; k <= along; ++k) {
      const double r = range_m - tolerance_m + 2.0 * tolerance_m * k / along;
      for (int u = 0; u <= up; ++u) {
        const double z = -tolerance_m + 2.0 * tolerance_m * u / up;
        const Eigen::Vector3d point = sonar_to_map * Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z);
        const std::optional<Key16> key = map.coder().keyOf(point);
        if (key && map.occupancyOf(*key) == Occupancy::kOccupied) return true;
      }
    }
  }
  return false;
}

}  // namespace

void FirstReturnOptions::validate() const {
  requirePositive(rise_db, "the rise (dB)");
  requirePositive(front_m, "the water in front (m)");
  requirePositive(stay_m, "the length a return stays up (m)");
  requirePositive(tolerance_m, "the tolerance (m)");
  if (!(beam_width_rad >= 0.0 && beam_width_rad < std::numbers::pi)) throwOption("the beam width must be in [0, pi) rad");
}

FirstReturnScore findFirstReturns(const SonarLog& log, const FirstReturnOptions& options) {
  options.validate();
  FirstReturnScore score;
  score.beams = log.beams.size();
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    const int bin = firstReturnBin(log.beams[i], options);
    if (bin >= 0) score.returns.push_back(FirstReturn{i, bin * log.beams[i].bin_length_m, false});
  }
  return score;
}

FirstReturnScore firstReturns(const OcTree16& map, const SonarLog& log,
                              const std::vector<std::optional<Eigen::Isometry3d>>& sonar_to_map,
                              const FirstReturnOptions& options) {
  if (!sonar_to_map.empty() && sonar_to_map.size() != log.beams.size()) {
    throw ValueError("first returns: " + std::to_string(sonar_to_map.size()) + " poses for " +
                     std::to_string(log.beams.size()) + " beams");
  }
  FirstReturnScore found = findFirstReturns(log, options);
  FirstReturnScore score;
  const double tolerance_m = std::max(options.tolerance_m, 2.0 * map.resolution_m());
  for (std::size_t i = 0; i < log.beams.size(); ++i) {
    if (sonar_to_map.empty() || sonar_to_map[i]) ++score.beams;
  }
  for (FirstReturn& first : found.returns) {
    if (!sonar_to_map.empty() && !sonar_to_map[first.beam]) continue;
    const Eigen::Isometry3d pose = sonar_to_map.empty() ? staticSonarToMap() : *sonar_to_map[first.beam];
    first.mapped = wedgeHoldsOccupied(map, pose, log.beams[first.beam].bearing_rad, first.range_m, options.beam_width_rad,
                                      tolerance_m);
    score.mapped += first.mapped ? 1 : 0;
    score.returns.push_back(first);
  }
  return score;
}

}  // namespace sonarmap
