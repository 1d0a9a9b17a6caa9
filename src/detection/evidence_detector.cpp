/// @file evidence_detector.cpp
/// The evidence detector: one outward pass over the ranges that measures the water where it is
/// water (water_evidence.hpp) and adds each bin's evidence of a return along its beam until the
/// beam's first return is certain (see detectors.hpp, EvidenceOptions).

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <vector>

#include "column_histogram.hpp"
#include "detector_internal.hpp"
#include "sonarmap/acoustics/speckle.hpp"
#include "sonarmap/detection/extended_returns.hpp"
#include "sonarmap/detection/water_evidence.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap::detail {
namespace {

/// A range's level needs this share of the rows (and at least 3) still in water there; beyond, the
/// last range that had them is used (as the background detector's outward pass).
constexpr double kMinWaterShare = 0.3;
/// Water samples a band needs before its evidence is used (the first bands of a sweep wait for it).
constexpr std::uint64_t kMinBandSamples = 64;

/// Share of the water's bins counted lit when its runs are measured (waterBinsPerLook): those beyond
/// its 90th percentile, where WaterEvidence's measured body ends and its tail begins.
constexpr double kLitShare = 0.1;
/// Water bins a sweep needs before its runs are measured (extended_returns.cpp asks the same).
constexpr std::size_t kMinLookSamples = 1000;

using ExcessHistogram = std::array<std::uint32_t, WaterEvidence::kExcessValues>;

/// The excess of `value` over `level` (both in 0…255) to the nearest count, halves up: the sum is
/// positive, so truncation floors it, without a library call per sample.
int excessOf(std::uint8_t value, float level) { return static_cast<int>(static_cast<float>(value) - level + 256.5f) - 256; }

/// Replaces the band's oldest column (`oldest`: its samples' histogram indices) in `band_counts` by
/// column `c`'s excess over `level` on the rows in water outside any return (their evidence sum at
/// 0); `band_samples` follows the band's total.
template <class Level>
void addToBand(std::vector<std::uint16_t>& oldest, ExcessHistogram& band_counts, std::uint64_t& band_samples,
               const std::vector<int>& in_water, const std::vector<double>& sum, const PolarImage& polar,
               const std::uint8_t* column, int c, Level&& level) {
  for (const std::uint16_t e : oldest) --band_counts[e];
  band_samples -= oldest.size();
  oldest.clear();
  for (const int r : in_water) {
    const auto row = static_cast<std::size_t>(r);
    if (c < polar.valid_bins[row] && sum[row] == 0.0) oldest.push_back(static_cast<std::uint16_t>(excessOf(column[r], level(r)) + 255));
  }
  for (const std::uint16_t e : oldest) ++band_counts[e];
  band_samples += oldest.size();
}

/// Where the return `found` of `row` is loud: the first bin from its start on, up to where it became
/// certain and then as long as the echo stays above half the per-bin threshold, whose excess reaches
/// the threshold; −1 when the
/// return has no loud part (a step into reverberation). Evidence of a slowly rising echo (a face at
/// oblique incidence, lit first by the beam pattern's skirt) adds up before its peak, and its
/// leading edge is sought from the peak's level (leadingEdgeAt).
int loudPartOf(const PolarImage& polar, int row, const EvidenceReturn& found, const SweepCalibration& water) {
  const auto* values = polar.intensities.ptr<std::uint8_t>(row);
  const int end = std::min(polar.valid_bins[static_cast<std::size_t>(row)], polar.cols());
  for (int c = found.start_bin; c < end; ++c) {
    const auto i = static_cast<std::size_t>(c);
    const float excess = static_cast<float>(values[c]) - water.background[i];
    if (excess >= water.threshold[i]) return c;
    if (excess < 0.5f * water.threshold[i] && c > found.certain_bin) break;
  }
  return -1;
}

/// The leading edge of a return of `row` with no loud part, found by its evidence (`found`): as a
/// loud echo's (leadingEdgeAt), the first bin from where its evidence started to add up whose echo
/// comes within `edge_db` of the echo's level, and at least half of it over the water. A weak
/// echo's bins are speckle: its level at a bin is the mean excess over a look centred on it (the
/// pulse, at least 3 bins), and the echo's level the median of those from where the return became
/// certain to a peak window beyond (a plateau's median is its level; a speckled plateau's highest
/// look would lie above it and move a step's edge behind the step). A step into reverberation
/// reaches its level at once: the edge is the step. A face at oblique incidence is lit first by the
/// skirt of the beam pattern and its echo rises over the range spread across the beam (two-way
/// pattern, in dB quadratic in the angle off the axis): the edge lies where the echo has risen, as a
/// loud face's, not where its first weak bins began to add evidence.
BeamDetection weakLeadingEdge(const PolarImage& polar, int row, const EvidenceReturn& found, const DetectionContext& context,
                              const SweepCalibration& water, double edge_db) {
  const auto* values = polar.intensities.ptr<std::uint8_t>(row);
  const int end = std::min(polar.valid_bins[static_cast<std::size_t>(row)], polar.cols());
  const int look = polar.pulse_length_m ? static_cast<int>(std::lround(*polar.pulse_length_m / polar.bin_length_m)) : 1;
  const int half = std::max(1, (std::max(3, look) - 1) / 2);
  auto level = [&](int c) {  // the mean excess over the look centred on c, from the return's start on
    double total = 0.0;
    int n = 0;
    for (int k = std::max(found.start_bin, c - half); k <= std::min(end - 1, c + half); ++k, ++n) {
      total += static_cast<double>(values[k]) - water.background[static_cast<std::size_t>(k)];
    }
    return n > 0 ? total / n : 0.0;
  };
  const int window_end =
      std::min(end, found.certain_bin + 1 + binsForLength(kPeakWindow_m, polar.bin_length_m, 2, std::max(2, end)));
  std::vector<double> levels;
  int peak_bin = found.certain_bin;
  for (int c = found.certain_bin; c < window_end; ++c) {
    levels.push_back(level(c));
    if (levels.back() > levels[static_cast<std::size_t>(peak_bin - found.certain_bin)]) peak_bin = c;
  }
  std::nth_element(levels.begin(), levels.begin() + static_cast<std::ptrdiff_t>(levels.size() / 2), levels.end());
  const double echo = levels[levels.size() / 2];  // certain_bin < window_end: one at least
  const double edge = std::max(echo - countsForDb(edge_db, context.span_db), 0.5 * echo);
  int first = found.start_bin;
  while (first < found.certain_bin && level(first) < edge) ++first;
  BeamDetection detection = detectionAt(polar, row, first);
  detection.rise_m = std::max(0, peak_bin - first) * polar.bin_length_m;
  return detection;
}

/// Whether the weak return of `row` at `range_m` is a loud return of another beam within a beam
/// width of it, heard in this beam's pattern skirt: that beam's obstacle lies within its echo's rise
/// plus the leading edge's peak window (kPeakWindow_m: a pulse or two) of `range_m`. Such a return
/// is explained by the surface the louder beam met and adds no surface of its own (it would draw
/// the surface's arc a beam width beside it).
bool heardInTheSkirt(const PolarImage& polar, int row, double range_m, const std::vector<BeamDetection>& loud,
                     double beam_width_rad) {
  for (int k = 0; k < polar.rows(); ++k) {
    const BeamDetection& other = loud[static_cast<std::size_t>(k)];
    if (k == row || !other.hasObstacle()) continue;
    const double gap_rad = std::abs(std::remainder(polar.bearing_rad[static_cast<std::size_t>(k)] -
                                                       polar.bearing_rad[static_cast<std::size_t>(row)],
                                                   2.0 * std::numbers::pi));
    if (gap_rad <= beam_width_rad && std::abs(other.range_m - range_m) <= kPeakWindow_m + other.rise_m) return true;
  }
  return false;
}

/// Whether the weak return `found` of `row` stands out of what follows it (standsOut): its echo runs
/// from where its evidence started to where the mean excess over the row's level (the water's, its
/// floor), over a look, falls below half the echo's median excess up to where it became certain.
bool weakReturnStands(const PolarImage& polar, int row, const EvidenceReturn& found, const DetectionContext& context,
                      const SweepCalibration& water) {
  const auto* values = polar.intensities.ptr<std::uint8_t>(row);
  const int end = std::min(polar.valid_bins[static_cast<std::size_t>(row)], polar.cols());
  auto excess = [&](int c) {
    return static_cast<float>(values[c]) - std::max(water.background[static_cast<std::size_t>(c)], context.floorAt(row, c));
  };
  std::vector<float> echo;
  for (int c = found.start_bin; c <= found.certain_bin; ++c) echo.push_back(excess(c));
  std::nth_element(echo.begin(), echo.begin() + static_cast<std::ptrdiff_t>(echo.size() / 2), echo.end());
  const float half = 0.5f * std::max(0.0f, echo[echo.size() / 2]);
  const int look = std::max(1, static_cast<int>(std::lround(context.look_bins)));
  int echo_end = found.certain_bin + 1;
  double sum = 0.0;
  for (int c = found.certain_bin + 1; c < end; ++c) {
    sum += excess(c);
    if (c - look > found.certain_bin) sum -= excess(c - look);
    echo_end = c + 1;
    if (c - found.certain_bin >= look && sum / look < half) break;
  }
  // An echo that lasts longer than the local level's window is the diffuse echo that level is
  // measured over (reverberation.hpp), not a surface's.
  if (echo_end - found.start_bin > 2 * context.local->halfWindowBins(found.start_bin)) return false;
  // A weak echo is a surface only where its shadow can be seen: half the level's window behind it.
  if (end - echo_end < look + context.local->halfWindowBins(echo_end)) return false;
  return standsOut(polar, *context.local, row, found.start_bin, found.certain_bin + 1, echo_end, context.min_bin, look,
                   std::max(water.background[static_cast<std::size_t>(found.start_bin)], context.floorAt(row, found.start_bin)));
}

}  // namespace

/// The water's bins per look along range, measured on the runs of its loudest bins (see
/// evidenceWeight): each row's bins from the minimum range to a peak window short of its loud return
/// (or its end), their excess over `background` (counts); a bin is lit beyond the (1 − kLitShare)
/// quantile of that excess, and L follows from the runs the lit bins form (binsPerLookFromRuns, with
/// the measured lit share: water clipped at the receiver's floor lights fewer than kLitShare). 1 with
/// fewer than kMinLookSamples bins.
double waterBinsPerLook(const PolarImage& polar, int min_bin, const std::vector<BeamDetection>& loud,
                        const std::vector<float>& background) {
  const int window = binsForLength(kPeakWindow_m, polar.bin_length_m, 2, std::max(2, polar.cols()));
  auto waterEnd = [&](int r) {
    const auto row = static_cast<std::size_t>(r);
    const int end = std::min(polar.valid_bins[row], polar.cols());
    return loud[row].hasObstacle() ? std::min(end, loud[row].obstacle_bin - window) : end;
  };
  auto excessAt = [&](int r, int c) {
    return excessOf(polar.intensities.at<std::uint8_t>(r, c), background[static_cast<std::size_t>(c)]);
  };
  ExcessHistogram counts{};
  std::size_t samples = 0;
  for (int r = 0; r < polar.rows(); ++r) {
    for (int c = min_bin; c < waterEnd(r); ++c, ++samples) ++counts[static_cast<std::size_t>(excessAt(r, c) + 255)];
  }
  if (samples < kMinLookSamples) return 1.0;
  // The lit level: the (1 − kLitShare) quantile of the excess (nearest rank).
  const auto rank = static_cast<std::size_t>(std::llround((1.0 - kLitShare) * static_cast<double>(samples - 1)));
  std::size_t seen = 0;
  int lit_above = -255;
  for (; lit_above < 255; ++lit_above) {
    seen += counts[static_cast<std::size_t>(lit_above + 255)];
    if (seen > rank) break;
  }
  std::size_t lit = 0, runs = 0;
  for (int r = 0; r < polar.rows(); ++r) {
    bool before = false;
    for (int c = min_bin; c < waterEnd(r); ++c) {
      const bool here = excessAt(r, c) > lit_above;
      lit += here ? 1 : 0;
      runs += here && !before ? 1 : 0;
      before = here;
    }
  }
  return binsPerLookFromRuns(lit, runs, static_cast<double>(lit) / static_cast<double>(samples));
}

double evidenceWeight(const PolarImage& polar, double water_bins_per_look) {
  // Bins closer than a pulse length share their speckle: each adds only its share of a look.
  if (!polar.pulse_length_m || *polar.pulse_length_m <= 0.0) return 1.0;
  const double pulse_bins = *polar.pulse_length_m / polar.bin_length_m;
  return 1.0 / std::max({1.0, pulse_bins, water_bins_per_look});
}

std::vector<EvidenceReturn> evidencePass(const PolarImage& polar, const DetectionContext& context, const BackgroundOptions& options,
                              SweepCalibration& water) {
  const int rows = polar.rows(), cols = polar.cols();
  const CalibrationOptions& calibration = options.calibration;
  const auto min_water = static_cast<std::uint32_t>(std::max(3.0, std::ceil(kMinWaterShare * rows)));
  const int band = binsForLength(options.water_band_m, polar.bin_length_m, 8, std::max(8, cols));
  const double decision = -std::log(calibration.false_alarm_probability);
  const double weight = evidenceWeight(polar, water.water_bins_per_look);
  std::vector<EvidenceReturn> first(static_cast<std::size_t>(rows));
  std::vector<int> start(static_cast<std::size_t>(rows), -1);
  std::vector<int> loud(static_cast<std::size_t>(rows), 0);  // bins in a row above the per-bin threshold
  std::vector<double> sum(static_cast<std::size_t>(rows), 0.0);
  std::vector<int> in_water;
  for (int r = 0; r < rows; ++r) in_water.push_back(r);
  std::vector<std::vector<std::uint16_t>> ring(static_cast<std::size_t>(band));  // the band's columns, oldest overwritten
  ExcessHistogram band_counts{};
  std::uint64_t band_samples = 0;
  // The least tail water can have: fully developed speckle's beyond the body's end (the 90th percentile).
  const double least_tail_counts = countsForDb(speckleTailMeanExcess_db(0.1), context.span_db);
  WaterEvidence evidence{std::span<const std::uint32_t>(band_counts), least_tail_counts};
  IntensityHistogram levels;
  std::deque<float> upcoming;  // the levels of this range and the next ones (−1: too few rows)
  std::deque<std::uint32_t> upcoming_rows;  // the rows in water they were measured on
  const cv::Mat columns = polar.intensities.t();  // row c: column c's values, contiguous
  // Rows of a sweep in progress: the water a whole sweep measured at each range (one beam holds
  // too little water to measure its own).
  const bool kept_water = !context.measure_background && water.water_evidence.size() == static_cast<std::size_t>(cols) &&
                          water.water_level.size() == static_cast<std::size_t>(cols);
  if (kept_water) water.background = water.water_level;  // the level the kept evidence was counted from
  if (context.measure_background) {  // one per column, the nearer ones the empty band's
    water.water_evidence.clear();
    water.water_evidence.reserve(static_cast<std::size_t>(cols));
    water.water_evidence.resize(static_cast<std::size_t>(std::min(context.min_bin, cols)), evidence);
  }
  const WaterEvidence* judged_by = &evidence;  // the water this column's bins are judged against
  const RowRingDown own_ring(polar, water);
  for (int c = context.min_bin; c < cols && !in_water.empty(); ++c) {
    const auto i = static_cast<std::size_t>(c);
    const auto* column = columns.ptr<std::uint8_t>(c);
    if (kept_water) judged_by = &water.water_evidence[i];
    // The level: the background percentile of the rows in water outside a loud run, at this range and
    // the next `ahead` bins, the highest of them: a level surface entering the cone (the water
    // surface of the CRAS tank at 1.5 m) reaches the bearings within a few bins of each other, and
    // the level must rise with the first of them, not after a quarter of the bearings have passed.
    // A wall seen by fewer than (100 − percentile) % of the bearings at one range never raises it.
    const int ahead = std::min(band / 2, cols - 1 - c);
    for (int k = c + static_cast<int>(upcoming.size()); k <= c + ahead; ++k) {
      levels.clear();
      const auto* values = columns.ptr<std::uint8_t>(k);
      for (const int r : in_water) {
        if (k < polar.valid_bins[static_cast<std::size_t>(r)] && loud[static_cast<std::size_t>(r)] == 0) levels.add(values[r]);
      }
      upcoming.push_back(levels.total() >= 3 ? levels.percentile(calibration.background_percentile) : -1.0f);
      upcoming_rows.push_back(levels.total());
    }
    const float measured = std::min(*std::max_element(upcoming.begin(), upcoming.end()), water.backgroundCap(c));
    const std::uint32_t rows_in_water = upcoming_rows.front();
    upcoming.pop_front();
    upcoming_rows.pop_front();
    // The level follows the rows in water however few remain (a level surface lies beyond the walls
    // of most bearings as well); the water's shape needs kMinWaterShare of the rows, and where fewer
    // remain (mostly those about to meet their return) the last band that had them is kept.
    if (context.measure_background) {
      if (measured >= 0.0f) {
        water.background[i] = measured;
      } else if (c > context.min_bin) {
        water.background[i] = water.background[i - 1];
      }
    }
    if (!kept_water && rows_in_water >= min_water) {
      // The water's excess over the level, from the rows in water outside any return, over the band
      // ending at this range (a band that also led it would hold the returns of the rows about to
      // meet them, as a CFAR's leading window does: measured, it hid a third of the shared pool
      // log's first returns; docs/accuracy.md).
      addToBand(ring[static_cast<std::size_t>((c - context.min_bin) % band)], band_counts, band_samples, in_water, sum,
                polar, column, c, [&](int) { return water.background[i]; });
      if (band_samples >= kMinBandSamples) evidence = WaterEvidence{std::span<const std::uint32_t>(band_counts), least_tail_counts};
    }
    if (context.measure_background) water.water_evidence.push_back(evidence);
    // Each row adds its bin's evidence (a CUSUM: a run starts where the sum leaves 0); a row whose
    // sum reaches the decision level has met its first return, where its run started.
    std::erase_if(in_water, [&](int r) {
      const auto row = static_cast<std::size_t>(r);
      if (c >= polar.valid_bins[row]) return true;
      // The water, or the row's own ring, or the level the row has come down to.
      const float level = std::max({water.background[i], own_ring.at(r, c), context.floorAt(r, c)});
      const float excess = static_cast<float>(column[r]) - level;
      loud[row] = excess >= water.threshold[i] ? loud[row] + 1 : 0;
      const double next = sum[row] + weight * judged_by->logLikelihoodRatio(excessOf(column[r], level));
      if (next <= 0.0) {
        sum[row] = 0.0;
        start[row] = -1;
        return false;
      }
      if (start[row] < 0) start[row] = c;
      sum[row] = next;
      if (next < decision) return false;
      first[row] = EvidenceReturn{start[row], c};
      return true;
    });
  }
  if (context.measure_background) {  // the columns beyond the last row's return: the last water
    water.water_evidence.resize(static_cast<std::size_t>(cols), evidence);
  }
  return first;
}

std::vector<BeamDetection> detectEvidence(const PolarImage& polar, const DetectionContext& context,
                                          const BackgroundOptions& options, SweepCalibration& water) {
  // The loud returns first: a surface in the beam's loud core, whatever weaker return comes before it
  // (a surface met by the cone's edge, the CRAS tank's water surface at 1.5 m, a floater above the
  // plane); `water` leaves with the calibration they were found with.
  SweepCalibration measured = water;
  EchoSpanRule span_rule;
  std::vector<BeamDetection> detections = context.local ? detectExtendedEchoes(polar, context, options, water, span_rule)
                                                        : detectBackgroundSubtracted(polar, context, options, water);
  water.echo_beams = context.local ? span_rule.sweepBeams() : 0;
  if ((context.measure_background && polar.rows() < options.min_beams) || polar.cols() == 0) return detections;
  // The water's looks: measured on a whole sweep, in front of its loud returns; a sweep in progress
  // keeps the whole sweep's.
  if (context.measure_background) {
    measured.water_bins_per_look = waterBinsPerLook(polar, context.min_bin, detections, measured.background);
  }
  water.water_bins_per_look = measured.water_bins_per_look;
  // A beam whose echo is never loud: its first return certain by the evidence of its bins.
  const std::vector<EvidenceReturn> first = evidencePass(polar, context, options, measured);
  water.water_evidence = std::move(measured.water_evidence);  // kept with the calibration returned
  if (context.measure_background) water.water_level = measured.background;  // still used below
  const std::vector<BeamDetection> loud_returns = detections;
  // Under the reverberation model a weak return, as a loud one, must span the beams the sweep asks
  // of an echo (reverberation.hpp): its evidence run [start, certain] chained with the other beams'
  // weak returns and loud echoes.
  std::vector<int> spans;
  if (context.local != nullptr) {
    std::vector<std::pair<int, int>> echoes(static_cast<std::size_t>(polar.rows()), {-1, -1});
    for (int r = 0; r < polar.rows(); ++r) {
      const BeamDetection& loud = detections[static_cast<std::size_t>(r)];
      const EvidenceReturn& found = first[static_cast<std::size_t>(r)];
      if (loud.hasObstacle()) {
        echoes[static_cast<std::size_t>(r)] = {loud.obstacle_bin, loud.obstacle_bin + 1 + static_cast<int>(std::lround(loud.rise_m / polar.bin_length_m))};
      } else if (found.start_bin >= 0) {
        echoes[static_cast<std::size_t>(r)] = {found.start_bin, found.certain_bin + 1};
      }
    }
    spans = echoSpans(echoes, *context.local, std::max(1, static_cast<int>(std::lround(context.look_bins))));
  }
  for (int r = 0; r < polar.rows(); ++r) {
    BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    const EvidenceReturn& found = first[static_cast<std::size_t>(r)];
    if (detection.hasObstacle() || found.start_bin < 0) continue;
    if (!spans.empty() && spans[static_cast<std::size_t>(r)] < span_rule.beamsAt(r, found.start_bin)) continue;
    if (context.local != nullptr && !weakReturnStands(polar, r, found, context, measured)) continue;
    // Its range: the leading edge of its loud part if it has one (a slowly rising echo), else the
    // leading edge of its echo's level (a step into reverberation, a weak face).
    const int loud = loudPartOf(polar, r, found, measured);
    const BeamDetection weak = loud >= 0 ? leadingEdgeAt(polar, r, loud, context, measured, options.leading_edge_db)
                                         : weakLeadingEdge(polar, r, found, context, measured, options.leading_edge_db);
    if (!heardInTheSkirt(polar, r, weak.range_m, loud_returns, context.beam_width_rad)) {
      detection = weak;
      detection.weak = true;
    }
  }
  return detections;
}

}  // namespace sonarmap::detail
