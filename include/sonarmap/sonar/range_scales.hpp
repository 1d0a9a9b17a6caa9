#pragma once
/// @file range_scales.hpp
/// The range scales of a log: users change a sonar's range while they watch (a Ping360 also powers
/// on at about 2 m before the user's range takes effect), so one log may hold beams of several bin
/// lengths. Which scale a log mostly used decides what the automatic resolution and the pictures of
/// one sweep follow (mapper_options.hpp, the CLI's polar and Cartesian images).

#include <cstddef>
#include <vector>

#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// The beams of one range scale (one Beam::bin_length_m) in a log.
struct RangeScale {
  double bin_length_m = 0.0;   ///< the scale's bin length, metres
  double reach_m = 0.0;        ///< its longest beam, bins × bin length, metres
  std::size_t beams = 0;       ///< beams of that bin length in the log
  std::size_t first_beam = 0;  ///< index of its first beam
};

/// The range scales of `log`, in order of first use; empty for a log without beams. Beams without
/// bins count for their scale with reach 0.
std::vector<RangeScale> rangeScales(const SonarLog& log);

/// Counts `beam`, the log's beam of index `index`, in its scale among `scales` (rangeScales one
/// beam at a time).
void countRangeScale(std::vector<RangeScale>& scales, const Beam& beam, std::size_t index);

/// The scale most beams use (a tie: the one used last), or nullptr when `scales` is empty. A scale
/// whose reach is 0 (beams without bins) is chosen only when no other is there.
const RangeScale* mostUsedRangeScale(const std::vector<RangeScale>& scales);

}  // namespace sonarmap
