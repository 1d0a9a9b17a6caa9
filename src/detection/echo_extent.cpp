/// @file echo_extent.cpp
/// The reverberation model's loud returns: runs above the local level that line up over enough
/// consecutive beams (see reverberation.hpp and detector_internal.hpp, detectExtendedEchoes).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "column_histogram.hpp"
#include "detector_internal.hpp"

namespace sonarmap::detail {
namespace {

/// A run of one row's bins [begin, end) whose excess over the row's level reaches the threshold.
struct Run {
  int begin = 0;
  int end = 0;
  bool stands = true;  ///< the echo stands out of what follows it (standsOut)
  int left = 1;   ///< beams of the longest chain of overlapping runs ending here, in bearing order
  int right = 1;  ///< beams of the longest chain starting here
};

/// Whether runs `a` and `b` of neighbouring beams overlap within `slack` bins.
bool overlap(const Run& a, const Run& b, int slack) { return a.begin - slack < b.end && b.begin - slack < a.end; }

/// Chains over neighbouring rows: `next[k]` takes from `previous` (the row before it in the
/// direction of the pass) one more beam than the longest chain of a run it overlaps, capped.
void chainOver(const std::vector<Run>& previous, std::vector<Run>& next, int slack, int cap, bool leftward, bool standing_only) {
  std::size_t j = 0;
  for (Run& run : next) {
    if (standing_only && !run.stands) continue;
    int best = 0;
    while (j < previous.size() && previous[j].end + slack <= run.begin) ++j;  // both sorted by begin
    for (std::size_t k = j; k < previous.size() && previous[k].begin - slack < run.end; ++k) {
      if (standing_only && !previous[k].stands) continue;
      if (overlap(run, previous[k], slack)) best = std::max(best, leftward ? previous[k].left : previous[k].right);
    }
    int& length = leftward ? run.left : run.right;
    length = std::max(length, std::min(cap, best + 1));
  }
}

/// Chains in the bearing order of `local`, both ways (around the circle for a whole turn: two passes
/// carry a chain across the seam), each at most as long as the rows: every run's left and right.
void chainRuns(std::vector<std::vector<Run>>& runs, const LocalLevel& local, int slack, bool standing_only) {
  for (auto& row_runs : runs) {
    for (Run& run : row_runs) run.left = run.right = 1;
  }
  const std::vector<int>& order = local.bearingOrder();
  const int positions = static_cast<int>(order.size());
  const int cap = static_cast<int>(runs.size());
  const int passes = local.circular() ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    for (int p = 0; p < positions; ++p) {
      if (p == 0 && !local.circular()) continue;
      const int before = order[static_cast<std::size_t>((p + positions - 1) % positions)];
      chainOver(runs[static_cast<std::size_t>(before)], runs[static_cast<std::size_t>(order[static_cast<std::size_t>(p)])], slack,
                cap, true, standing_only);
    }
    for (int p = positions - 1; p >= 0; --p) {
      if (p == positions - 1 && !local.circular()) continue;
      const int after = order[static_cast<std::size_t>((p + 1) % positions)];
      chainOver(runs[static_cast<std::size_t>(after)], runs[static_cast<std::size_t>(order[static_cast<std::size_t>(p)])], slack,
                cap, false, standing_only);
    }
  }
}

/// The median of the bins [lo, hi) of the rows `rows` (clipped to each row's valid bins and to
/// [min_bin, ...)), or −1 when they hold fewer than `least` bins.
float windowMedian(const PolarImage& polar, const std::vector<int>& rows, int lo, int hi, int min_bin, int least) {
  IntensityHistogram histogram;
  lo = std::max(lo, min_bin);
  for (const int r : rows) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min({hi, polar.valid_bins[static_cast<std::size_t>(r)], polar.cols()});
    for (int c = lo; c < end; ++c) histogram.add(values[c]);
  }
  return static_cast<int>(histogram.total()) >= least ? histogram.percentile(kLocalLevelPercentile) : -1.0f;
}

}  // namespace

int EchoSpanRule::beamsAt(int row, int bin) const {
  if (local_ == nullptr || chance_.empty()) return needed_;
  const int positions = chance_.rows - 1, cols = chance_.cols - 1;
  const int p = std::clamp(local_->positionOf(row), 0, positions - 1);
  const int p0 = std::max(0, p - local_->halfWindowRows()), p1 = std::min(positions, p + local_->halfWindowRows() + 1);
  const int c0 = std::clamp(bin - local_->halfWindowBins(bin), 0, cols), c1 = std::clamp(bin + local_->halfWindowBins(bin) + 1, 0, cols);
  auto boxSum = [&](const cv::Mat& sum) {  // positions [p0, p1), columns [c0, c1)
    return sum.at<double>(p1, c1) - sum.at<double>(p0, c1) - sum.at<double>(p1, c0) + sum.at<double>(p0, c0);
  };
  const double bins = boxSum(searched_);
  if (bins <= 0.0) return needed_;
  const double isolated = boxSum(chance_) / bins;
  double rho = isolated;
  for (int i = 0; i < 2; ++i) {
    const double q = 1.0 - std::exp(-rho * overlap_bins_);
    rho = isolated / std::max(1e-3, (1.0 - q) * (1.0 - q));
  }
  return std::max(needed_, requiredEchoBeams(rho, overlap_bins_, false_alarm_probability_, positions));
}

bool standsOut(const PolarImage& polar, const LocalLevel& local, int row, int begin, int loud_end, int echo_end, int min_bin,
               int slack, float front_level) {
  const int window_bins = std::max(2, 2 * local.halfWindowBins(begin));
  std::vector<int> trio{row};
  for (const int neighbour : local.bearingNeighbours(row)) {
    if (neighbour >= 0) trio.push_back(neighbour);
  }
  const float behind = windowMedian(polar, trio, echo_end + slack, echo_end + slack + window_bins, min_bin, slack);
  if (behind < 0.0f) return true;
  float front = windowMedian(polar, trio, begin - slack - window_bins, begin - slack, min_bin, slack);
  if (front < 0.0f) front = front_level;
  const auto* values = polar.intensities.ptr<std::uint8_t>(row);
  std::vector<std::uint8_t> echo(values + begin, values + std::max(begin + 1, loud_end));
  std::nth_element(echo.begin(), echo.begin() + static_cast<std::ptrdiff_t>(echo.size() / 2), echo.end());
  const auto echo_level = static_cast<float>(echo[echo.size() / 2]);
  return behind <= 0.5f * (echo_level + front);
}

std::vector<BeamDetection> detectExtendedEchoes(const PolarImage& polar, const DetectionContext& context,
                                                const BackgroundOptions& options, const SweepCalibration& calibration,
                                                EchoSpanRule& rule) {
  const int rows = polar.rows(), cols = polar.cols();
  std::vector<BeamDetection> detections(static_cast<std::size_t>(rows));
  if (context.local == nullptr || rows == 0 || cols == 0) return detections;
  const LocalLevel& local = *context.local;
  const RowRingDown ring(polar, calibration);
  const float threshold = context.local_threshold;
  const int echo_bins = binsForLength(options.min_echo_length_m, polar.bin_length_m, 1, std::max(1, cols));
  const int slack = std::max(1, static_cast<int>(std::lround(context.look_bins)));
  // The head's own near field: what returns at one range in most bearings (the sweep's background
  // B(c)) from the minimum range until it first comes down to the water's level. A round wall stands
  // beyond water and is not in it; the ring-down's tail, which leaves every beam at the cut, is.
  std::vector<float> near_field(static_cast<std::size_t>(cols), 0.0f);
  for (int c = context.min_bin; c < cols && c < static_cast<int>(calibration.background.size()); ++c) {
    if (calibration.background[static_cast<std::size_t>(c)] <= calibration.quiet_water_counts) break;
    near_field[static_cast<std::size_t>(c)] = calibration.background[static_cast<std::size_t>(c)];
  }
  auto level = [&](int r, int c) {
    return std::max({context.localLevelAt(r, c), ring.at(r, c), near_field[static_cast<std::size_t>(c)]});
  };
  // Each row's runs above the threshold lasting an echo's length.
  std::vector<std::vector<Run>> runs(static_cast<std::size_t>(rows));
  double bins_searched = 0.0, run_bins = 0.0, run_count = 0.0;
  for (int r = 0; r < rows; ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], cols);
    bins_searched += std::max(0, end - context.min_bin);
    int start = -1;
    for (int c = context.min_bin; c <= end; ++c) {
      const bool lit = c < end && static_cast<float>(values[c]) - level(r, c) >= threshold;
      if (lit && start < 0) start = c;
      if (!lit && start >= 0) {
        if (c - start >= echo_bins) {
          runs[static_cast<std::size_t>(r)].push_back(Run{start, c});
          run_bins += c - start;
          run_count += 1.0;
        }
        start = -1;
      }
    }
  }
  // An obstacle's echo stands out of what follows it (standsOut); it ends where it has fallen back
  // below half the threshold for an echo's length (BeamDetection::echo_end_m's rule).
  for (int r = 0; r < rows; ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], cols);
    for (Run& run : runs[static_cast<std::size_t>(r)]) {
      int echo_end = run.end;
      for (int c = run.end, quiet = 0; c < end && quiet < echo_bins; ++c) {
        if (static_cast<float>(values[c]) - level(r, c) >= 0.5f * threshold) {
          echo_end = c + 1;
          quiet = 0;
        } else {
          ++quiet;
        }
      }
      // Only an echo that returns at its range in most bearings (its median less than the threshold
      // over the sweep's background B(c), the 25th percentile across bearings) must show its shadow:
      // such an echo is the seabed or the surface entering the aperture unless it is a wall around
      // the head (a round tank), which blocks the beam; an echo that stands out of what most
      // bearings return there is judged by its span alone (a wall's multipath behind it is no
      // reverberation).
      std::vector<std::uint8_t> echo(values + run.begin, values + run.end);
      std::nth_element(echo.begin(), echo.begin() + static_cast<std::ptrdiff_t>(echo.size() / 2), echo.end());
      const auto b = static_cast<std::size_t>(run.begin);
      const bool in_most_bearings =
          static_cast<float>(echo[echo.size() / 2]) - calibration.background[b] < calibration.threshold[b];
      run.stands = !in_most_bearings ||
                   standsOut(polar, local, r, run.begin, run.end, echo_end, context.min_bin, slack, level(r, run.begin));
    }
  }
  const std::vector<int>& order = local.bearingOrder();
  const int positions = static_cast<int>(order.size());
  // Chains in bearing order, both ways (around the circle for a whole turn: two passes carry a chain
  // across the seam), each at most `cap` beams long: over every run, for the chance runs' density,
  // then over the runs that stand out, for the obstacles.
  auto chain = [&](bool standing_only) { chainRuns(runs, local, slack, standing_only); };
  chain(false);
  // The span asked of an echo: from the runs that no neighbour's run overlaps (chance runs, most of
  // them; a chance run escapes its two neighbours with probability (1 − q)², so the density is
  // corrected by it, twice).
  double unaligned = 0.0;
  for (const auto& row_runs : runs) {
    for (const Run& run : row_runs) unaligned += run.left == 1 && run.right == 1 ? 1.0 : 0.0;
  }
  const double mean_run_bins = run_count > 0.0 ? run_bins / run_count : 0.0;
  const double overlap_bins = 2.0 * mean_run_bins + 2.0 * slack - 1.0;
  double rho = bins_searched > 0.0 ? unaligned / bins_searched : 0.0;
  const double rho_isolated = rho;
  for (int i = 0; i < 2; ++i) {
    const double q = 1.0 - std::exp(-rho * overlap_bins);
    rho = rho_isolated / std::max(1e-3, (1.0 - q) * (1.0 - q));
  }
  const int needed = context.echo_beams > 0
                         ? std::min(context.echo_beams, rows)
                         : requiredEchoBeams(rho, std::max(0.0, overlap_bins), options.calibration.false_alarm_probability, rows);
  rule = EchoSpanRule(needed);
  if (context.echo_beams <= 0) {
    // Where the reverberation makes more chance runs than the sweep's mean, an echo must span more
    // beams: the same count from the chance runs within the level's window around it (rows in
    // bearing order × range).
    rule.overlap_bins_ = std::max(0.0, overlap_bins);
    rule.false_alarm_probability_ = options.calibration.false_alarm_probability;
    rule.local_ = &local;
    rule.chance_ = cv::Mat::zeros(positions + 1, cols + 1, CV_64FC1);
    rule.searched_ = cv::Mat::zeros(positions + 1, cols + 1, CV_64FC1);
    std::vector<double> starts(static_cast<std::size_t>(cols));
    for (int p = 0; p < positions; ++p) {
      const int r = order[static_cast<std::size_t>(p)];
      const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], cols);
      std::fill(starts.begin(), starts.end(), 0.0);
      for (const Run& run : runs[static_cast<std::size_t>(r)]) starts[static_cast<std::size_t>(run.begin)] += run.left == 1 && run.right == 1 ? 1.0 : 0.0;
      double row_chance = 0.0, row_searched = 0.0;
      for (int c = 0; c < cols; ++c) {
        row_chance += starts[static_cast<std::size_t>(c)];
        row_searched += c >= context.min_bin && c < end ? 1.0 : 0.0;
        rule.chance_.at<double>(p + 1, c + 1) = rule.chance_.at<double>(p, c + 1) + row_chance;
        rule.searched_.at<double>(p + 1, c + 1) = rule.searched_.at<double>(p, c + 1) + row_searched;
      }
    }
  }
  // The water range counts every run a neighbour's overlaps; the obstacles, the standing runs' chains.
  std::vector<std::vector<int>> aligned(static_cast<std::size_t>(rows));
  for (int r = 0; r < rows; ++r) {
    for (const Run& run : runs[static_cast<std::size_t>(r)]) {
      if (run.left + run.right - 1 >= 2) aligned[static_cast<std::size_t>(r)].push_back(run.begin);
    }
  }
  chain(true);
  // Each row's nearest run that spans enough beams, at its leading edge. The beam proves water up to
  // it, or without one up to its first run that a neighbour's run overlaps (an echo other beams heard
  // too: something may stand there), else to its end: a run no neighbour shares is the speckle the
  // level and the threshold expect of the water and the reverberation.
  for (int r = 0; r < rows; ++r) {
    const auto* values = polar.intensities.ptr<std::uint8_t>(r);
    BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], cols);
    int water_end = aligned[static_cast<std::size_t>(r)].empty() ? end : std::min(end, aligned[static_cast<std::size_t>(r)].front());
    for (const Run& run : runs[static_cast<std::size_t>(r)]) {
      if (!run.stands || run.left + run.right - 1 < rule.beamsAt(r, run.begin)) continue;
      detection = leadingEdgeOf(
          polar, r, run.begin, context, [&](int c) { return static_cast<float>(values[c]) - level(r, c); }, threshold,
          options.leading_edge_db);
      break;
    }
    detection.water_range_m = detection.hasObstacle() ? detection.range_m
                                                      : (water_end > context.min_bin ? water_end * polar.bin_length_m : 0.0);
  }
  return detections;
}

std::vector<int> echoSpans(const std::vector<std::pair<int, int>>& echoes, const LocalLevel& local, int slack) {
  std::vector<std::vector<Run>> runs(echoes.size());
  for (std::size_t r = 0; r < echoes.size(); ++r) {
    if (echoes[r].first >= 0 && echoes[r].second > echoes[r].first) runs[r].push_back(Run{echoes[r].first, echoes[r].second});
  }
  chainRuns(runs, local, slack, false);
  std::vector<int> spans(echoes.size(), 0);
  for (std::size_t r = 0; r < echoes.size(); ++r) {
    if (!runs[r].empty()) spans[r] = runs[r].front().left + runs[r].front().right - 1;
  }
  return spans;
}

}  // namespace sonarmap::detail
