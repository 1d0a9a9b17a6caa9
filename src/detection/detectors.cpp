/// @file detectors.cpp
/// detectObstacles: validation, calibration, dispatch and names (see detectors.hpp).

#include "sonarmap/detection/detectors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "detector_internal.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

[[noreturn]] void throwOption(const std::string& what) { throw ValueError("detector options: " + what); }

void checkImage(const PolarImage& polar) {
  if (polar.intensities.type() != CV_8UC1) throw ValueError("detection: the polar image must be CV_8UC1");
  if (static_cast<int>(polar.valid_bins.size()) != polar.rows()) {
    throw ValueError("detection: valid_bins has " + std::to_string(polar.valid_bins.size()) + " entries for " +
                     std::to_string(polar.rows()) + " rows");
  }
  if (!(polar.bin_length_m > 0.0) || !std::isfinite(polar.bin_length_m)) {
    throw ValueError("detection: bin_length_m must be > 0 m");
  }
}

void requireNonNegative(double value, const char* what) {
  if (!(std::isfinite(value) && value >= 0.0)) throwOption(std::string(what) + " must be finite and >= 0");
}

void checkCanny(const CannyOptions& o) {
  requireNonNegative(o.blur_range_m, "canny blur along the beam (m)");
  requireNonNegative(o.blur_bearing_rad, "canny blur across beams");
  requireNonNegative(o.low_threshold_db, "canny low threshold (dB)");
  if (!(std::isfinite(o.high_threshold_db) && o.high_threshold_db >= o.low_threshold_db)) {
    throwOption("canny thresholds must satisfy 0 <= low <= high (dB)");
  }
  if (o.aperture_size != 3 && o.aperture_size != 5 && o.aperture_size != 7) {
    throwOption("canny aperture must be 3, 5 or 7, got " + std::to_string(o.aperture_size));
  }
}

void checkBackground(const BackgroundOptions& o) {
  o.calibration.validate();
  requireNonNegative(o.min_echo_length_m, "the minimum echo length (m)");
  requireNonNegative(o.leading_edge_db, "the leading edge's level below the peak (dB)");
  requireNonNegative(o.water_band_m, "the water band (m)");
  if (o.min_beams < 1) throwOption("background min_beams must be >= 1");
}

/// A name the CLI accepts, with the detector and (for kCfar) the variant it selects.
struct NamedDetector {
  const char* name;
  Detector kind;
  CfarVariant variant;
};

constexpr NamedDetector kDetectorNames[] = {
    {"background", Detector::kBackgroundSubtracted, CfarVariant::kCellAveraging},
    {"threshold", Detector::kThreshold, CfarVariant::kCellAveraging},
    {"canny", Detector::kCanny, CfarVariant::kCellAveraging},
    {"cfar-ca", Detector::kCfar, CfarVariant::kCellAveraging},
    {"cfar-so", Detector::kCfar, CfarVariant::kSmallestOf},
    {"cfar-go", Detector::kCfar, CfarVariant::kGreatestOf},
    {"cfar-os", Detector::kCfar, CfarVariant::kOrderedStatistic},
    {"evidence", Detector::kEvidence, CfarVariant::kCellAveraging},
};

const NamedDetector& namedDetector(std::string_view name) {
  for (const NamedDetector& named : kDetectorNames) {
    if (name == named.name) return named;
  }
  std::string expected;
  for (const NamedDetector& named : kDetectorNames) expected += (expected.empty() ? "" : ", ") + std::string(named.name);
  throw ValueError("unknown detector '" + std::string(name) + "', expected one of " + expected);
}

}  // namespace

void DetectorOptions::validate() const {
  if (min_range_m) requireNonNegative(*min_range_m, "the minimum range (m)");
  if (intensity_span_db && !(std::isfinite(*intensity_span_db) && *intensity_span_db > 0.0)) {
    throwOption("the intensity span must be a finite number of dB > 0");
  }
  requireNonNegative(onset_length_m, "the echo onset length (m)");
  if (!(beam_width_rad >= 0.0 && beam_width_rad < std::numbers::pi)) throwOption("the beam width must be in [0, pi) rad");
  switch (kind) {
    case Detector::kThreshold:
      requireNonNegative(threshold.min_rise_db, "the threshold's rise (dB)");
      break;
    case Detector::kCanny:
      checkCanny(canny);
      break;
    case Detector::kBackgroundSubtracted:
    case Detector::kEvidence:
      checkBackground(background);
      reverberation.validate();
      break;
    case Detector::kCfar:
      background.calibration.validate();
      cfar.validate();
      break;
  }
}

namespace detail {

BeamDetection detectionAt(const PolarImage& polar, int row, int bin) {
  return BeamDetection{bin, polar.intensities.at<std::uint8_t>(row, bin), (bin + 0.5) * polar.bin_length_m};
}

std::vector<BeamDetection> detectCfar(const PolarImage& polar, const DetectionContext& context,
                                      const CfarOptions& options, const SweepCalibration& calibration) {
  const CfarCells cells = options.cells(polar.bin_length_m);
  const auto contrast = static_cast<float>(countsForDb(options.min_contrast_db, context.span_db));
  std::vector<float> floor(calibration.background.size());
  for (std::size_t c = 0; c < floor.size(); ++c) {
    floor[c] = calibration.background[c] + std::max(contrast, calibration.threshold[c]);
  }
  std::vector<BeamDetection> detections(static_cast<std::size_t>(polar.rows()));
  for (int r = 0; r < polar.rows(); ++r) {
    const auto end = static_cast<std::size_t>(std::clamp(polar.valid_bins[static_cast<std::size_t>(r)], 0, polar.cols()));
    const int bin = firstCfarBin(std::span(polar.intensities.ptr<std::uint8_t>(r), end), context.min_bin, cells, floor);
    if (bin >= 0) detections[static_cast<std::size_t>(r)] = detectionAt(polar, r, bin);
  }
  return detections;
}

}  // namespace detail

namespace {

/// The detections of `options.kind` from the all-rows `calibration` (already checked against the
/// image); `water` receives the calibration the detections were made with.
std::vector<BeamDetection> runDetector(const PolarImage& polar, const DetectorOptions& options,
                                       const detail::DetectionContext& context, const SweepCalibration& calibration,
                                       SweepCalibration& water) {
  water = calibration;
  switch (options.kind) {
    case Detector::kThreshold:
      return detail::detectThreshold(polar, context, options.threshold);
    case Detector::kCanny:
      return detail::detectCanny(polar, context, options.canny);
    case Detector::kBackgroundSubtracted:
      return detail::detectBackgroundSubtracted(polar, context, options.background, water);
    case Detector::kEvidence:
      return detail::detectEvidence(polar, context, options.background, water);
    case Detector::kCfar:
      // The floor: above the background of the water, as the background detector measures it.
      detail::outwardPass(polar, context, options.background, water);
      return detail::detectCfar(polar, context, options.cfar, water);
  }
  return std::vector<BeamDetection>(static_cast<std::size_t>(polar.rows()));
}

/// Counts, among the rows without an obstacle, those with an echo above the threshold between the
/// band's end and the minimum range, and those whose echo was too short (DetectionDiagnostics).
DetectionDiagnostics diagnose(const PolarImage& polar, const detail::DetectionContext& context,
                              const SweepCalibration& calibration, const std::vector<BeamDetection>& detections) {
  DetectionDiagnostics diagnostics;
  diagnostics.beams = detections.size();
  const int band = firstBinAtOrBeyond(calibration.band_end_m, polar.bin_length_m, polar.cols());
  for (int r = 0; r < polar.rows(); ++r) {
    const BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    diagnostics.reach_m = std::max(diagnostics.reach_m, polar.valid_bins[static_cast<std::size_t>(r)] * polar.bin_length_m);
    if (detection.hasObstacle()) {
      ++diagnostics.obstacles;
      continue;
    }
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    diagnostics.reach_m = std::max(diagnostics.reach_m, end * polar.bin_length_m);
    if (detection.water_range_m > 0.0 && detection.water_range_m < end * polar.bin_length_m) ++diagnostics.echoes_too_short;
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    for (int c = band; c < std::min(context.min_bin, end); ++c) {
      const auto i = static_cast<std::size_t>(c);
      if (static_cast<float>(row[c]) - calibration.background[i] >= calibration.threshold[i]) {
        ++diagnostics.echoes_before_min_range;
        break;
      }
    }
  }
  if (diagnostics.echoes_before_min_range > 0) {
    diagnostics.hidden_from_m = band * polar.bin_length_m;
    diagnostics.hidden_to_m = context.min_bin * polar.bin_length_m;
  }
  return diagnostics;
}

/// Sets each detection's water_range_m (detection.hpp): its range with an obstacle; without one, the
/// start of the first bin at or beyond the minimum range whose residual above `calibration`'s
/// background reaches the threshold (an echo too short to be an obstacle), or the row's end.
/// Sets each detection's echo_onset_m (detection.hpp, DetectorOptions::onset_length_m): the start
/// of the first window at or beyond the minimum range whose mean residual above the background
/// reaches the onset level, at most the water range.
void setEchoOnsets(const PolarImage& polar, const DetectorOptions& options, const detail::DetectionContext& context,
                   const SweepCalibration& calibration, std::vector<BeamDetection>& detections) {
  constexpr double kSpeckleMeanDb = 2.9;  // one-look speckle: mean dB above its 25th percentile
  const int window = std::max(8, static_cast<int>(std::lround(options.onset_length_m / polar.bin_length_m)));
  const double level_db =
      kSpeckleMeanDb + std::max(0.0, calibration.threshold_db - kSpeckleMeanDb) / std::sqrt(static_cast<double>(window));
  const double level = level_db * 255.0 / context.span_db * window;  // on the window's sum
  const int look = std::max(1, static_cast<int>(std::lround(context.look_bins)));
  for (int r = 0; r < polar.rows(); ++r) {
    BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    const int last = std::min(end, static_cast<int>(std::ceil(detection.water_range_m / polar.bin_length_m)));
    // Under the reverberation model an echo counts from the level its beam has come down to as well
    // (RowFloor: the cut's edge is no return).
    auto residual = [&](int c) {
      const float background = calibration.background[static_cast<std::size_t>(c)];
      return static_cast<double>(row[c]) - (context.local ? std::max(background, context.floorAt(r, c)) : background);
    };
    double sum = 0.0;
    int onset = -1, c = context.min_bin;
    for (; c < end; ++c) {
      sum += residual(c);
      if (c - window >= context.min_bin) sum -= residual(c - window);
      const int start = c - window + 1;
      if (start >= last) break;
      if (start < context.min_bin || sum < level) continue;
      // Under the reverberation model an echo that goes on with no shadow behind it (standsOut) is
      // the seabed's or the surface's reverberation entering the beam, not a surface at the sonar's
      // level: the beam still proves water through it, and the next echo is sought where it ends.
      int echo_end = c + 1;
      while (echo_end < end && sum >= level) {
        sum += residual(echo_end) - residual(echo_end - window);
        ++echo_end;
      }
      if (context.local == nullptr ||
          (echo_end - start <= 2 * context.local->halfWindowBins(start) && detail::standsOut(polar, *context.local, r, start, echo_end, echo_end, context.min_bin, look,
                            calibration.background[static_cast<std::size_t>(start)]))) {
        onset = start;
        break;
      }
      c = echo_end - 1;
    }
    // Under the reverberation model the echo also starts where it first rises above the local level
    // of the diffuse echo (reverberation.hpp; one-look speckle's mean lies 0.9 dB under its median,
    // and the window holds window / look_bins independent looks): a surface the background across
    // bearings hides, or one whose shadow cannot be told. The beam clears to the nearer of the two.
    if (context.local != nullptr) {
      const double median_mean_db = -0.5772156649015329 * 10.0 * std::log10(std::exp(1.0)) - 10.0 * std::log10(std::log(2.0));
      const double looks = std::max(1.0, window / context.look_bins);
      const double local_level = (median_mean_db + std::max(0.0, context.local_threshold_db - median_mean_db) / std::sqrt(looks)) *
                                 255.0 / context.span_db * window;
      const int stop = onset >= 0 ? onset : last;
      double local_sum = 0.0;
      for (int k = context.min_bin; k < end; ++k) {
        local_sum += static_cast<double>(row[k]) - context.localLevelAt(r, k);
        if (k - window >= context.min_bin) local_sum -= static_cast<double>(row[k - window]) - context.localLevelAt(r, k - window);
        const int start = k - window + 1;
        if (start >= stop) break;
        if (start >= context.min_bin && local_sum >= local_level) {
          onset = start;
          break;
        }
      }
    }
    detection.echo_onset_m = onset >= 0 ? std::min(onset * polar.bin_length_m, detection.water_range_m)
                                        : detection.water_range_m;
  }
}

void setWaterRanges(const PolarImage& polar, const detail::DetectionContext& context,
                    const SweepCalibration& calibration, std::vector<BeamDetection>& detections) {
  // An echo counts from the level its beam has come down to (RowFloor): a beam still in the near
  // field's reverberation where the minimum range cuts it proves no water there.
  for (int r = 0; r < polar.rows(); ++r) {
    BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    if (detection.hasObstacle()) {
      detection.water_range_m = detection.range_m;
      continue;
    }
    // Under the reverberation model the loud pass measured it (detectExtendedEchoes); a weak return
    // found since ends it there.
    if (context.local) continue;
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    auto below = [&](int c) {
      if (context.local) return static_cast<float>(row[c]) - context.localLevelAt(r, c) < context.local_threshold;
      return static_cast<float>(row[c]) - std::max(calibration.background[static_cast<std::size_t>(c)], context.floorAt(r, c)) <
             calibration.threshold[static_cast<std::size_t>(c)];
    };
    int c = context.min_bin;
    while (c < end && below(c)) ++c;
    // A beam that shows nothing beyond the minimum range proves no water (its bins may be zeroed).
    detection.water_range_m = c > context.min_bin ? c * polar.bin_length_m : 0.0;
  }
}

/// BeamDetection::echo_end_m of every beam with an obstacle: forward from the obstacle's bin while
/// the echo does not stay below half the threshold for `quiet_bins` bins in a row.
void setEchoEnds(const PolarImage& polar, const detail::DetectionContext& context, const SweepCalibration& calibration,
                 int quiet_bins, std::vector<BeamDetection>& detections) {
  for (int r = 0; r < polar.rows(); ++r) {
    BeamDetection& detection = detections[static_cast<std::size_t>(r)];
    if (!detection.hasObstacle()) continue;
    const auto* row = polar.intensities.ptr<std::uint8_t>(r);
    const int end = std::min(polar.valid_bins[static_cast<std::size_t>(r)], polar.cols());
    int last = detection.obstacle_bin;
    for (int c = detection.obstacle_bin, quiet = 0; c < end && quiet < quiet_bins; ++c) {
      const auto column = static_cast<std::size_t>(c);
      const bool loud = context.local ? static_cast<float>(row[c]) - context.localLevelAt(r, c) >= 0.5f * context.local_threshold
                                      : static_cast<float>(row[c]) - calibration.background[column] >= 0.5f * calibration.threshold[column];
      if (loud) {
        last = c;
        quiet = 0;
      } else {
        ++quiet;
      }
    }
    detection.echo_end_m = (last + 0.5) * polar.bin_length_m;
  }
}

}  // namespace

SweepDetection detectSweep(const PolarImage& polar, const DetectorOptions& options) {
  checkImage(polar);
  options.validate();
  const double span_db = options.intensity_span_db.value_or(intensitySpan_db(polar));
  return detectSweep(polar, options, calibrateSweep(polar, options.background.calibration, span_db));
}

namespace {
/// `options` with each required echo length no longer than the image's pulse (PolarImage::
/// pulse_length_m, when the log records it): a hard surface at normal incidence returns an echo
/// about one pulse long, so a short range's pulse (a Ping360's 8 mm at 2 m) must not be asked for
/// the 4 cm that reject speckle at longer ranges.
DetectorOptions capEchoLengthsAtPulse(DetectorOptions options, const PolarImage& polar) {
  if (polar.pulse_length_m) {
    options.background.min_echo_length_m = std::min(options.background.min_echo_length_m, *polar.pulse_length_m);
    options.cfar.min_echo_length_m = std::min(options.cfar.min_echo_length_m, *polar.pulse_length_m);
  }
  return options;
}

/// detectSweep and detectRows: the detections of `polar` with `calibration`, the background measured
/// again over the rows or not.
SweepDetection detectWith(const PolarImage& polar, const DetectorOptions& requested, const SweepCalibration& calibration,
                          bool measure_background) {
  checkImage(polar);
  requested.validate();
  const DetectorOptions options = capEchoLengthsAtPulse(requested, polar);
  const auto cols = static_cast<std::size_t>(polar.cols());
  if (calibration.background.size() != cols || calibration.threshold.size() != cols) {
    throw ValueError("detection: the calibration has " + std::to_string(calibration.background.size()) +
                     " columns for an image of " + std::to_string(cols));
  }
  SweepDetection result;
  result.min_range_m = options.min_range_m.value_or(calibration.near_field_end_m);
  const int min_bin = firstBinAtOrBeyond(result.min_range_m, polar.bin_length_m, polar.cols());
  const detail::RowFloor floor(polar, min_bin, options.background.water_band_m, calibration.quiet_water_counts);
  detail::DetectionContext context{min_bin, calibration.span_db, measure_background, options.beam_width_rad, &floor};
  // The evidence detector's local reverberation level (reverberation.hpp): measured on a whole
  // sweep, or for rows of a sweep in progress the whole sweep's at their bearings.
  LocalLevel local;
  if (options.kind == Detector::kEvidence && options.reverberation.enabled) {
    const double pulse_bins = polar.pulse_length_m ? *polar.pulse_length_m / polar.bin_length_m : 1.0;
    context.look_bins = std::max(1.0, pulse_bins);
    if (measure_background) {
      const std::vector<BeamDetection> none(static_cast<std::size_t>(polar.rows()));
      context.look_bins = std::max(context.look_bins, detail::waterBinsPerLook(polar, min_bin, none, calibration.background));
      local = LocalLevel(polar, min_bin, context.look_bins, options.beam_width_rad, options.reverberation);
    } else if (!calibration.local_level.empty()) {
      local = LocalLevel::atBearingsOf(calibration.local_level, polar);
      context.echo_beams = std::max(1, calibration.echo_beams);
    }
    if (!local.empty()) {
      context.local = &local;
      context.local_threshold_db = thresholdDb(options.background.calibration, kLocalLevelPercentile);
      context.local_threshold = static_cast<float>(countsForDb(context.local_threshold_db, calibration.span_db));
    }
  }
  result.detections = runDetector(polar, options, context, calibration, result.calibration);
  setWaterRanges(polar, context, result.calibration, result.detections);
  setEchoOnsets(polar, options, context, result.calibration, result.detections);
  setEchoEnds(polar, context, result.calibration,
              binsForLength(options.background.min_echo_length_m, polar.bin_length_m, 1, std::max(1, polar.cols())),
              result.detections);
  if (context.local) {
    result.calibration.local_threshold_db = context.local_threshold_db;
    result.calibration.local_level = measure_background ? std::move(local) : calibration.local_level;
  }
  result.diagnostics = diagnose(polar, context, result.calibration, result.detections);
  return result;
}
}  // namespace

SweepDetection detectSweep(const PolarImage& polar, const DetectorOptions& options, const SweepCalibration& calibration) {
  return detectWith(polar, options, calibration, true);
}

SweepDetection detectRows(const PolarImage& polar, const DetectorOptions& options, const SweepCalibration& calibration) {
  return detectWith(polar, options, calibration, false);
}

std::vector<BeamDetection> detectObstacles(const PolarImage& polar, const DetectorOptions& options) {
  return detectSweep(polar, options).detections;
}

DetectionDiagnostics& DetectionDiagnostics::operator+=(const DetectionDiagnostics& other) {
  beams += other.beams;
  obstacles += other.obstacles;
  echoes_before_min_range += other.echoes_before_min_range;
  hidden_from_m = std::min(hidden_from_m, other.hidden_from_m);
  hidden_to_m = std::max(hidden_to_m, other.hidden_to_m);
  echoes_too_short += other.echoes_too_short;
  reach_m = std::max(reach_m, other.reach_m);
  return *this;
}

Detector parseDetector(std::string_view name) { return namedDetector(name).kind; }

void selectDetector(DetectorOptions& options, std::string_view name) {
  const NamedDetector& named = namedDetector(name);
  options.kind = named.kind;
  if (named.kind == Detector::kCfar) options.cfar.variant = named.variant;
}

std::string detectorName(Detector kind) {
  DetectorOptions options;
  options.kind = kind;
  options.cfar.variant = CfarVariant::kCellAveraging;
  return detectorName(options);
}

std::string detectorName(const DetectorOptions& options) {
  for (const NamedDetector& named : kDetectorNames) {
    if (named.kind == options.kind && (named.kind != Detector::kCfar || named.variant == options.cfar.variant)) {
      return named.name;
    }
  }
  return "unknown";
}

}  // namespace sonarmap
