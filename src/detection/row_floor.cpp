/// @file row_floor.cpp
/// Each row's floor: the level it is in where the minimum range cuts it, until it comes down to the
/// water (see detector_internal.hpp, RowFloor).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "detector_internal.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap::detail {

RowFloor::RowFloor(const PolarImage& polar, int min_bin, double water_band_m, float water_counts)
    : floor_(cv::Mat::zeros(polar.rows(), polar.cols(), CV_32FC1)) {
  const double look_bins = 1.0 / evidenceWeight(polar, 1.0);
  const int first_bins = binsForLength(water_band_m, polar.bin_length_m, 8, std::max(8, polar.cols()));
  const int band_bins = std::max(first_bins, static_cast<int>(std::ceil(kLooks * look_bins)));
  min_bin = std::max(0, min_bin);
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    auto* floor = floor_.ptr<float>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    if (end <= min_bin) continue;
    // The first water band's mean (or all the row has): the level the row starts at.
    const int first_end = std::min(end, min_bin + first_bins);
    double sum = 0.0;
    for (int c = min_bin; c < first_end; ++c) sum += values[c];
    float lowest = static_cast<float>(sum / (first_end - min_bin));
    for (int c = min_bin; c < end && lowest > water_counts; ++c) {
      if (c >= first_end) {  // the bins since the minimum range ending at c, at most a band of them
        sum += values[c];
        if (c - band_bins >= min_bin) sum -= values[c - band_bins];
        lowest = std::min(lowest, static_cast<float>(sum / std::min(band_bins, c - min_bin + 1)));
      }
      if (lowest > water_counts) floor[c] = lowest;  // in water from here on: no floor of its own
    }
  }
}

}  // namespace sonarmap::detail
