/// @file range_scales.cpp
/// rangeScales, mostUsedRangeScale (see range_scales.hpp).

#include "sonarmap/sonar/range_scales.hpp"

#include <algorithm>

namespace sonarmap {

void countRangeScale(std::vector<RangeScale>& scales, const Beam& beam, std::size_t index) {
  auto scale = std::find_if(scales.begin(), scales.end(),
                            [&](const RangeScale& known) { return known.bin_length_m == beam.bin_length_m; });
  if (scale == scales.end()) scale = scales.insert(scales.end(), RangeScale{beam.bin_length_m, 0.0, 0, index});
  ++scale->beams;
  scale->reach_m = std::max(scale->reach_m, static_cast<double>(beam.intensities.size()) * beam.bin_length_m);
}

std::vector<RangeScale> rangeScales(const SonarLog& log) {
  std::vector<RangeScale> scales;
  for (std::size_t i = 0; i < log.beams.size(); ++i) countRangeScale(scales, log.beams[i], i);
  return scales;
}

const RangeScale* mostUsedRangeScale(const std::vector<RangeScale>& scales) {
  const RangeScale* best = nullptr;
  for (const RangeScale& scale : scales) {
    const bool reaches = scale.reach_m > 0.0;
    if (best == nullptr || (reaches && !(best->reach_m > 0.0)) ||
        (reaches == (best->reach_m > 0.0) && (scale.beams > best->beams ||
                                               (scale.beams == best->beams && scale.first_beam > best->first_beam)))) {
      best = &scale;
    }
  }
  return best;
}

}  // namespace sonarmap
