/// @file ring_down.cpp
/// Each row's own ring-down (see detector_internal.hpp, RowRingDown).

#include <algorithm>
#include <vector>

#include "detector_internal.hpp"

namespace sonarmap::detail {

RowRingDown::RowRingDown(const PolarImage& polar, const SweepCalibration& calibration)
    : ring_(calibration.ring_down), offset_(static_cast<std::size_t>(polar.rows()), 0.0f) {
  if (ring_.empty()) return;
  std::vector<float> excess;
  for (int r = 0; r < polar.rows(); ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min({calibration.ring_fit_end, polar.valid_bins[static_cast<std::size_t>(r)], polar.cols(),
                              static_cast<int>(ring_.size())});
    excess.clear();
    for (int c = calibration.ring_fit_begin; c < end; ++c) excess.push_back(static_cast<float>(values[c]) - ring_[static_cast<std::size_t>(c)]);
    if (excess.empty()) continue;
    const auto middle = excess.begin() + static_cast<std::ptrdiff_t>(excess.size() / 2);
    std::nth_element(excess.begin(), middle, excess.end());
    offset_[static_cast<std::size_t>(r)] = *middle;
  }
}

}  // namespace sonarmap::detail
