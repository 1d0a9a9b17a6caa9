#pragma once
/// @file detector_internal.hpp
/// Shared helpers and the per-detector entry points behind detectObstacles (not installed).

#include <algorithm>
#include <utility>
#include <vector>

#include "sonarmap/detection/detectors.hpp"
#include "sonarmap/detection/reverberation.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap::detail {

/// The echo's peak is sought this far behind its first bin above the threshold (at least two
/// bins), metres: a pulse length or two (Ping360 at 50 m: ≈ 0.2 m). The leading edge is then
/// sought forward from the rise's foot, so a stronger echo within the window (reverberation or
/// multipath behind a wall) can only raise the edge's level, never move it behind the first rise.
constexpr double kPeakWindow_m = 0.3;

/// Each row's floor: the level a row is in where the minimum range cuts it, intensity counts, until
/// it comes down to the water. A return is a rise: it must stand out of the level its own beam has
/// come down to, as well as out of the water at its range. A beam still in an echo where the minimum
/// range cuts it (the near field's reverberation, the seabed or surface entering the vertical
/// aperture at short range: the shared Ping360 basin log's beams bright from the head to 2.5–5 m)
/// has not come down: the cut's edge, and the reverberation that only fades beyond it, are never a
/// return, while an echo that rises out of it (a wall seen through the tail of that reverberation)
/// still is.
///
/// The floor at a column is the lowest mean, since the minimum range, over the row's bins ending
/// there, at most a band of them, once the row holds a water band's worth
/// (BackgroundOptions::water_band_m, at least 8 bins; the first water band's mean until then). It
/// ends (0 from there on) where it falls to the water's level W (SweepCalibration::
/// quiet_water_counts: the level water alone exceeds in a tenth of its bins); a row that starts in
/// water has none, and the background decides alone. The band holds kLooks independent looks (the
/// pulse's length in bins each, where the log records it; a bin each where it does not): one-look
/// speckle's spread in dB (5.6 dB) shrinks to 1.4 dB over 16 looks, so the lowest band mean lies a
/// few dB under the level the reverberation came down to, not a threshold (16.8 dB at Pfa 10⁻⁶)
/// under it as a single look's would, and the patches of a seabed's reverberation do not stand out
/// of each other. On the shared Ping360 basin log (3 bins a pulse at 10 m) the band is 0.4 m.
class RowFloor {
 public:
  /// Looks a band holds.
  static constexpr double kLooks = 16.0;
  /// The floor of every row of `polar` from column `min_bin` on (0 before it, beyond the row's
  /// valid bins, and from where it comes down to `water_counts`); `water_band_m` ≥ 0.
  RowFloor(const PolarImage& polar, int min_bin, double water_band_m, float water_counts);
  /// Row r's floor at column c, intensity counts.
  float at(int r, int c) const { return floor_.at<float>(r, c); }

 private:
  cv::Mat floor_;  ///< CV_32FC1, rows × cols
};

/// What every detector needs besides its own options: the first bin it may report and the image's
/// intensity scale.
struct DetectionContext {
  int min_bin = 0;         ///< first bin whose centre is at or beyond the minimum range
  double span_db = 45.0;   ///< dB span of the intensities 0…255
  /// The background detector measures the background again over the rows still in water (a whole
  /// sweep); false: it uses the given calibration's as it is (a few rows of a sweep in progress,
  /// detectRows).
  bool measure_background = true;
  /// The beams' horizontal −3 dB width, radians (DetectorOptions::beam_width_rad).
  double beam_width_rad = 0.0;
  /// Each row's floor from min_bin on, made once for the sweep (none: every floor 0).
  const RowFloor* floor = nullptr;
  /// Row r's floor at column c, intensity counts.
  float floorAt(int r, int c) const { return floor ? floor->at(r, c) : 0.0f; }
  /// The sweep's local reverberation level (reverberation.hpp), with the threshold above it in
  /// intensity counts; none: each range is judged by the sweep's background B(c) (calibration.hpp).
  const LocalLevel* local = nullptr;
  float local_threshold = 0.0f;
  double local_threshold_db = 0.0;
  /// Bins per independent look along range (≥ 1): the pulse's length in bins or the water's own
  /// runs, whichever is longer (waterBinsPerLook); the reach of a run into its neighbour's.
  double look_bins = 1.0;
  /// Fewest beams an echo must span; 0: measured on the sweep (requiredEchoBeams). Rows of a sweep
  /// in progress cannot measure it and use the whole sweep's.
  int echo_beams = 0;
  /// Row r's level at column c under the reverberation model, intensity counts: the larger of the
  /// local level and the row's floor (0 without a local level).
  float localLevelAt(int r, int c) const { return local ? std::max(local->at(r, c), floorAt(r, c)) : 0.0f; }
};

/// The detection of `bin` in `row`, with the image's intensity there and the bin's centre as range.
BeamDetection detectionAt(const PolarImage& polar, int row, int bin);

/// The leading edge of the echo whose run above `threshold` starts at `bin` in `row`, the excess of
/// bin c over its level given by `excess(c)` (intensity counts): back from `bin` while the echo
/// stays above half the threshold (its foot, not before `context.min_bin`), the echo's peak within
/// kPeakWindow_m of `bin`, then the first bin from the foot within `edge_db` of the peak and at
/// least half the threshold over the level; its centre is the range (detectors.hpp,
/// BackgroundOptions, step 3), the distance to the peak the rise.
template <class Excess>
BeamDetection leadingEdgeOf(const PolarImage& polar, int row, int bin, const DetectionContext& context, Excess&& excess,
                            float threshold, double edge_db) {
  const int end = std::min(polar.valid_bins[static_cast<std::size_t>(row)], polar.cols());
  const float half_threshold = 0.5f * threshold;
  int foot = bin;
  while (foot > context.min_bin && excess(foot - 1) >= half_threshold) --foot;
  // The echo's peak, within a pulse or two of the run's start (what lies farther is another echo,
  // reverberation or multipath, and must not pull the edge to itself).
  const int window_end = std::min(end, bin + binsForLength(kPeakWindow_m, polar.bin_length_m, 2, std::max(2, end)));
  int peak = bin;
  for (int c = bin; c < window_end; ++c) {
    if (excess(c) > excess(peak)) peak = c;
  }
  const float edge = std::max(excess(peak) - static_cast<float>(countsForDb(edge_db, context.span_db)), half_threshold);
  int first = foot;
  while (first < peak && excess(first) < edge) ++first;
  BeamDetection detection = detectionAt(polar, row, first);
  detection.rise_m = (peak - first) * polar.bin_length_m;
  return detection;
}

/// The detection of the echo found at `bin` in `row` at its leading edge: the echo is the run of
/// bins above the threshold from `bin` on; back from its peak over the bins within `edge_db` of the
/// peak (and at least half the threshold above the background), the first of them, its centre as
/// the range (detectors.hpp, BackgroundOptions, step 3).
BeamDetection leadingEdgeAt(const PolarImage& polar, int row, int bin, const DetectionContext& context,
                            const SweepCalibration& calibration, double edge_db);

/// Each row's own ring-down (SweepCalibration::ring_down): every ping rings with the sweep's shape,
/// louder or quieter by a level of its own (the shared Ping360 logs at 60 m and gain 0, over
/// 0.40–0.50 m: a quarter of the pings under 11 counts, a tenth over 63; a louder ping rings
/// longer). A row's offset is the median of its excess over the ring on the ring's unsaturated
/// decline; its ring at a column is the ring's level there plus that offset. A return must rise
/// out of the water at its range, and near the head a ping's water is its own ring.
class RowRingDown {
 public:
  /// `polar` and `calibration` must outlive this object.
  RowRingDown(const PolarImage& polar, const SweepCalibration& calibration);
  /// The level of row r's ring at column c, intensity counts (0 where the sweep has none).
  float at(int r, int c) const {
    if (c >= static_cast<int>(ring_.size())) return 0.0f;
    const float ring = ring_[static_cast<std::size_t>(c)] + offset_[static_cast<std::size_t>(r)];
    return ring > 0.0f ? ring : 0.0f;
  }

 private:
  const std::vector<float>& ring_;
  std::vector<float> offset_;  ///< per row, counts
};

/// Paper §8.2 threshold on the rise between consecutive bins; options already validated.
std::vector<BeamDetection> detectThreshold(const PolarImage& polar, const DetectionContext& context,
                                           const ThresholdOptions& options);

/// Paper §9 Gaussian blur + Canny; options already validated.
std::vector<BeamDetection> detectCanny(const PolarImage& polar, const DetectionContext& context,
                                       const CannyOptions& options);

/// The background detector's outward pass (detectors.hpp, BackgroundOptions): range by range from
/// the minimum range, B measured over the rows still in water (not yet detected, not inside an
/// echo), and each row's first bin of the first run of min_echo_length_m at least T above B (−1 if
/// none).
/// `water` enters as the all-rows calibration and leaves with the values measured on the water
/// (a range with fewer than 10 % of the rows in water keeps the values of the range before it).
std::vector<int> outwardPass(const PolarImage& polar, const DetectionContext& context, const BackgroundOptions& options,
                             SweepCalibration& water);

/// The reverberation model's loud returns (reverberation.hpp): each row's runs of at least
/// min_echo_length_m whose excess over the row's level (the local level, the floor, the row's own
/// ring-down) reaches context.local_threshold; a run is an obstacle when it belongs to a chain of
/// overlapping runs (within a look) over at least requiredEchoBeams() consecutive beams in bearing
/// order; each row's nearest such run, at its leading edge. Needs context.local. `calibration`
/// supplies the ring-down. Options validated.
/// The fewest consecutive beams an echo must span (reverberation.hpp, requiredEchoBeams): the
/// sweep's, from the density of its chance runs (those no neighbour's run overlaps), and more where
/// those runs are denser within the local level's window around the echo.
class EchoSpanRule {
 public:
  EchoSpanRule() = default;
  /// A rule asking `beams` everywhere (rows of a sweep in progress: the whole sweep's).
  explicit EchoSpanRule(int beams) : needed_(std::max(1, beams)) {}
  /// The sweep's span: never fewer are asked anywhere.
  int sweepBeams() const { return needed_; }
  /// The span asked of an echo of row `row` starting at column `bin`.
  int beamsAt(int row, int bin) const;

 private:
  friend std::vector<BeamDetection> detectExtendedEchoes(const PolarImage&, const DetectionContext&, const BackgroundOptions&,
                                                         const SweepCalibration&, EchoSpanRule&);
  int needed_ = 1;
  double overlap_bins_ = 0.0;
  double false_alarm_probability_ = 1e-6;
  const LocalLevel* local_ = nullptr;
  cv::Mat chance_, searched_;  ///< integral images over (bearing position, column): chance runs, bins searched
};

/// `rule` receives the span rule the echoes were judged by (context.echo_beams everywhere, when set).
std::vector<BeamDetection> detectExtendedEchoes(const PolarImage& polar, const DetectionContext& context,
                                                const BackgroundOptions& options, const SweepCalibration& calibration,
                                                EchoSpanRule& rule);

/// Whether the echo of row `row` over bins [begin, loud_end), which falls back at `echo_end`, stands
/// out of what follows it (reverberation.hpp): behind it the level falls at least half-way back from
/// the echo's median to the level in front (its shadow, or the water or seabed it stands in), where
/// a step into the seabed's or the surface's reverberation goes on at the level it rose to. Both
/// levels are medians over twice the local level's half window (LocalLevel::halfWindowBins) of the
/// row and its two neighbours in bearing, `slack` bins (a look) away from the echo; before
/// `min_bin` nothing counts, and with nothing in front `front_level` stands for it. True when less
/// than a look lies behind (the beam's end).
bool standsOut(const PolarImage& polar, const LocalLevel& local, int row, int begin, int loud_end, int echo_end, int min_bin,
               int slack, float front_level);

/// The span of each row's echo [first, second) (bins; first < 0: none) in consecutive beams of
/// `local`'s bearing order whose echoes overlap it within `slack` bins, chained (0 without one).
std::vector<int> echoSpans(const std::vector<std::pair<int, int>>& echoes, const LocalLevel& local, int slack);

/// Background-subtracted detector: the outward pass, then each echo's leading edge. `water` enters
/// as the all-rows calibration and leaves as the calibration on the water. Options validated.
std::vector<BeamDetection> detectBackgroundSubtracted(const PolarImage& polar, const DetectionContext& context,
                                                      const BackgroundOptions& options, SweepCalibration& water);

/// A return found by its evidence: the first bin of its run and the bin where it became certain.
struct EvidenceReturn {
  int start_bin = -1;    ///< where the row's evidence sum left 0 (Page's CUSUM change point), −1: none
  int certain_bin = -1;  ///< where it reached the decision level
};

/// The evidence detector's outward pass (water_evidence.hpp, detectors.hpp): range by range, the
/// level measured over the rows still in water, the water's excess distribution over the band of
/// ranges up to this one on the rows outside any return, and each row's evidence added until it
/// reaches ln(1 / false_alarm_probability): per row, its run's first bin (where the sum left 0: the
/// change point of Page's CUSUM, Page 1954, Biometrika 41) and the bin where it became certain.
std::vector<EvidenceReturn> evidencePass(const PolarImage& polar, const DetectionContext& context, const BackgroundOptions& options,
                              SweepCalibration& water);

/// The weight of one bin's evidence: its share of an independent look, 1 / L. The evidence detector
/// adds the bins' log-likelihood ratios as if each were a look of its own, and bins closer than the
/// speckle's correlation length share their speckle (Goodman, "Speckle Phenomena in Optics" 2007;
/// ../shared/docs/echo-model.md, "What water looks like"). Where the log records its pulse
/// (PolarImage::pulse_length_m), L is the larger of the pulse's length in bins and the water's own
/// bins per look `water_bins_per_look` (measured on the sweep: SweepCalibration::water_bins_per_look):
/// water the receiver clips at its floor (a Ping360 at gain 0) shows its noise in blobs several
/// pulses long, each one look, not a look per pulse length. Where the log records no pulse, 1.
double evidenceWeight(const PolarImage& polar, double water_bins_per_look);

/// The water's bins per look along range, measured on the runs of its loudest bins (see
/// evidenceWeight): each row's bins from `min_bin` to a peak window short of its obstacle in `loud`
/// (or its end), their excess over `background` (counts); 1 with too few bins.
double waterBinsPerLook(const PolarImage& polar, int min_bin, const std::vector<BeamDetection>& loud,
                        const std::vector<float>& background);

/// Evidence detector: the evidence pass, then each return's leading edge. `water` as for
/// detectBackgroundSubtracted. Options validated.
std::vector<BeamDetection> detectEvidence(const PolarImage& polar, const DetectionContext& context,
                                          const BackgroundOptions& options, SweepCalibration& water);

/// CFAR along each row, with a floor at the calibrated background plus the minimum contrast.
std::vector<BeamDetection> detectCfar(const PolarImage& polar, const DetectionContext& context,
                                      const CfarOptions& options, const SweepCalibration& calibration);

}  // namespace sonarmap::detail
