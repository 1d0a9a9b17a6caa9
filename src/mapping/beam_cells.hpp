#pragma once
/// @file beam_cells.hpp
/// Private to src/mapping: a sweep's beams in the forward model's terms: each beam's power over the
/// water's level in range cells one voxel long (what level_surfaces.hpp pools), and the range up to
/// which it heard water.
///
/// The water's level at each range bin (column) is measured where the beams are water: the bins of
/// the sweep's beams before their first echo (BeamDetection::echo_onset_m, or the obstacle's range,
/// less `tolerance_m`), as the mean power of those bins (intensities are dB, intensitySpan_db:
/// power = 10^(I · span / 2550)); "estimate the water in front of the first return"
/// (../shared/docs/echo-model.md; Rickard & Dillard 1977's censoring). A column with fewer than
/// kMinWaterSamples such bins takes the level of the nearest column that has them. A sweep with no
/// water at all (every beam starts inside an echo) takes the mean power of its quietest quarter of
/// bins.

#include <cstddef>
#include <vector>

#include "sonarmap/detection/detection.hpp"
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// The least water bins a column needs for its own level.
inline constexpr std::size_t kMinWaterSamples = 8;

/// One beam in range cells.
struct CellBeam {
  std::vector<float> cell_power;  ///< power over the water per range cell (mean of its bins), NaN beyond the beam
  double water_range_m = 0.0;     ///< the beam heard water up to here (its first echo less the tolerance)
};

/// The sweep's beams (one per row of `polar`, the image the detector saw) in cells of `cell_m`
/// metres (see the file's comment).
std::vector<CellBeam> cellBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                          double cell_m, double tolerance_m);

}  // namespace sonarmap
