/// @file online_mapper.cpp
/// OnlineMapper (see online_mapper.hpp).

#include "sonarmap/mapping/online_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/octree/box_copy.hpp"
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {

namespace {
std::size_t minBeams(const MapperOptions& options) {
  return static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
}

/// `polar` with the calibration's columns: a longer row is cut at its last one, a shorter one padded
/// with zeros beyond its valid bins.
PolarImage fitToCalibration(PolarImage polar, const SweepCalibration& calibration) {
  const int cols = static_cast<int>(calibration.background.size());
  if (polar.cols() == cols) return polar;
  cv::Mat resized = cv::Mat::zeros(polar.rows(), cols, CV_8UC1);
  const int kept = std::min(cols, polar.cols());
  polar.intensities.colRange(0, kept).copyTo(resized.colRange(0, kept));
  polar.intensities = resized;
  for (int& valid : polar.valid_bins) valid = std::min(valid, cols);
  return polar;
}

/// @throws ValueError naming the beam's time for a bin length that is not finite and > 0, or an
/// intensity span or pulse length that is set and not finite and > 0 (unset: not recorded).
void checkBeam(const Beam& beam) {
  const auto positive = [](double value) { return std::isfinite(value) && value > 0.0; };
  const std::string at = "online mapper: beam at " + std::to_string(beam.time_s) + " s has ";
  if (!positive(beam.bin_length_m)) throw ValueError(at + "a bin length that is not > 0 m");
  if (beam.intensity_span_db && !positive(*beam.intensity_span_db)) {
    throw ValueError(at + "an intensity span that is not a finite number of dB > 0 (unset: not recorded)");
  }
  if (beam.pulse_length_m && !positive(*beam.pulse_length_m)) {
    throw ValueError(at + "a pulse length that is not a finite number of metres > 0 (unset: not recorded)");
  }
}
}  // namespace

OnlineMapper::OnlineMapper(const MapperOptions& options, OnlineIntegration integration, SweepCallback on_sweep)
    : mapper_(options), integration_(integration), on_sweep_(std::move(on_sweep)), grouper_(minBeams(options)) {
  if (integration == OnlineIntegration::kProvisionalBeams) provisional_ = std::make_unique<ProvisionalBeams>(options);
}

OnlineMapper::OnlineMapper(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body,
                           OnlineIntegration integration, SweepCallback on_sweep)
    : OnlineMapper(options, integration, std::move(on_sweep)) {
  if (!sonar_to_body.matrix().allFinite()) throw ValueError("online mapper: the sonar's mounting is not finite");
  sonar_to_body_ = sonar_to_body;
}

OnlineMapper::~OnlineMapper() { waitForDetections(); }

void OnlineMapper::addNavFix(const NavSample& fix) {
  if (!sonar_to_body_) throw ValueError("online mapper: navigation fixes need the navigation constructor");
  if (!isFinite(fix)) throw ValueError("online mapper: navigation fix with a value that is not finite");
  if (!fixes_.empty() && !(fix.time_s > fixes_.back().time_s)) {
    throw ValueError("online mapper: navigation fix at " + std::to_string(fix.time_s) + " s is not after the previous one (" +
                     std::to_string(fixes_.back().time_s) + " s)");
  }
  fixes_.push_back(fix);
  processReady();
  showWaitingBeams();
}

void OnlineMapper::addBeam(Beam beam) {
  if (finished_) throw ValueError("online mapper: beam after finish()");
  checkBeam(beam);
  if (shows_given_beams_) throw ValueError("online mapper: addBeam on a mapper given beams to show (showBeam)");
  const bool starts_sweep = splitter_.startsSweep(beam);
  const HeadSetting setting = headSettingOf(beam);
  const std::size_t final_beams = grouper_.add(starts_sweep, setting);
  if (final_beams > 0) emitGroup(final_beams, headSettingOf(held_[final_beams - 1]) != setting);
  if (provisional_) unshown_.push_back({beams_added_, starts_sweep, beam});
  ++beams_added_;
  held_.push_back(std::move(beam));
  processReady();
  showWaitingBeams();
}

void OnlineMapper::showBeam(std::size_t index, Beam beam) {
  if (!provisional_) throw ValueError("online mapper: showBeam needs OnlineIntegration::kProvisionalBeams");
  if (beams_added_ > 0) throw ValueError("online mapper: showBeam on a mapper fed beams (addBeam), which shows them itself");
  if (finished_) throw ValueError("online mapper: beam after finish()");
  checkBeam(beam);
  if (shows_given_beams_ && index <= last_shown_index_) {
    throw ValueError("online mapper: beam " + std::to_string(index) + " to show is not after the previous one");
  }
  shows_given_beams_ = true;
  last_shown_index_ = index;
  const bool starts_sweep = splitter_.startsSweep(beam);
  if (index >= committed_end_) unshown_.push_back({index, starts_sweep, std::move(beam)});
  showWaitingBeams();
}

void OnlineMapper::calibrateWith(const DetectedSweep& sweep) {
  keepCalibration(sweep.setting, sweep.detection.calibration, static_cast<std::size_t>(sweep.polar.rows()));
  showWaitingBeams();
}

void OnlineMapper::finish() {
  if (finished_) return;
  finished_ = true;
  if (const std::size_t last = grouper_.finish(); last > 0) emitGroup(last, true);
  processReady();
  integrateInFlight();
  mapper_.finish();
}

void OnlineMapper::commitHeld(bool navigation_ended) {
  if (finished_) return;
  if (const std::size_t last = grouper_.finish(); last > 0) emitGroup(last, true);
  splitter_ = SweepSplitter{};  // the next beam starts a sweep of its own
  navigation_ended_ = navigation_ended;
  try {
    processReady();
    integrateInFlight();
  } catch (...) {
    navigation_ended_ = false;
    throw;
  }
  navigation_ended_ = false;
  std::unique_lock lock(map_mutex_);  // the inversion model's last window goes into the map
  mapper_.finish();
}

void OnlineMapper::emitGroup(std::size_t beams, bool cut) {
  std::vector<Beam> group;
  group.reserve(beams);
  std::move(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(beams), std::back_inserter(group));
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(beams));
  waiting_beams_ += beams;
  ready_.push_back({std::move(group), cut, beams_grouped_});
  beams_grouped_ += beams;
}

bool OnlineMapper::navigationCovers(double time_s) const {
  if (!sonar_to_body_ || finished_ || navigation_ended_) return true;
  return !fixes_.empty() && fixes_.back().time_s >= time_s;
}

namespace {
/// How long after the last fix a beam is still shown at its pose (showWaitingBeams), seconds.
constexpr double kHeldPoseShown_s = 1.0;

double latestTime_s(const std::vector<Beam>& beams) {
  double latest_s = -std::numeric_limits<double>::infinity();
  for (const Beam& beam : beams) latest_s = std::max(latest_s, beam.time_s);
  return latest_s;
}
}  // namespace

void OnlineMapper::processReady() {
  while (!ready_.empty() && navigationCovers(latestTime_s(ready_.front().beams))) {
    ReadyGroup ready = std::move(ready_.front());
    ready_.pop_front();
    if (detectedAsShort(ready)) {
      processShortGroup(std::move(ready));
      continue;
    }
    std::vector<Beam> group = std::move(ready.beams);
    auto detect = [this, group = std::move(group), first_beam = ready.first_beam]() {
      DetectedSweep sweep{makePolarImage(group, 0, group.size()), {}, headSettingOf(group.front()), first_beam};
      sweep.detection = mapper_.detectSweep(sweep.polar);  // const: touches no mapper state
      return sweep;
    };
    if (!mapper_.options().pipeline_detection || provisional_) {
      integrate(detect());
      continue;
    }
    // Detect this sweep on another thread while the oldest sweep in detection is integrated here.
    in_flight_.push_back(std::async(std::launch::async, std::move(detect)));
    while (in_flight_.size() > detections_ahead_) integrateOldest();
  }
}

void OnlineMapper::setDetectionsAhead(std::size_t sweeps) {
  if (sweeps == 0) throw ValueError("online mapper: at least one sweep is detected ahead");
  detections_ahead_ = sweeps;
}

void OnlineMapper::integrateOldest() {
  std::future<DetectedSweep> oldest = std::move(in_flight_.front());
  in_flight_.pop_front();
  integrate(oldest.get());  // rethrows what its detection threw
}

void OnlineMapper::integrateInFlight() {
  while (!in_flight_.empty()) integrateOldest();
}

void OnlineMapper::waitForDetections() {
  for (std::future<DetectedSweep>& detection : in_flight_) {
    if (detection.valid()) detection.wait();  // never leave a detection thread running
  }
}

bool OnlineMapper::detectedAsShort(const ReadyGroup& group) {
  if (group.beams.size() < minBeams(mapper_.options())) return true;
  if (!group.cut) return false;
  // A sweep cut short by a range or gain change, or by the end of the log, covers a few bearings:
  // its own background and near field would be those of one patch of the scene (a seabed seen in
  // every one of its beams is taken for the near field). Its setting's last whole sweep measured
  // them over more bearings; the sweep before it may still be in detection.
  integrateInFlight();
  const HeadSetting setting = headSettingOf(group.beams.front());
  for (const KeptCalibration& kept : calibrations_) {
    if (kept.setting == setting) return 2 * group.beams.size() < kept.beams;
  }
  return false;
}

void OnlineMapper::processShortGroup(ReadyGroup ready) {
  const std::vector<Beam>& group = ready.beams;
  // Too few bearings to measure a background on: detected with the calibration of the last whole
  // sweep of its head setting, which must be known first.
  integrateInFlight();
  const HeadSetting setting = headSettingOf(group.front());
  const SweepCalibration* calibration = calibrationOf(setting);
  if (calibration == nullptr) {
    const std::unique_lock lock(map_mutex_);
    mapper_.stats().beams_uncalibrated += group.size();
    waiting_beams_ -= group.size();
    committedBefore(ready.first_beam + group.size());
    return;
  }
  DetectedSweep sweep{makePolarImage(group, 0, group.size()), {}, setting, ready.first_beam};
  PolarImage rows = fitToCalibration(sweep.polar, *calibration);
  sweep.detection = mapper_.detectRows(rows, *calibration);
  sweep.polar = std::move(rows);
  integrate(std::move(sweep), false);
}

const SweepCalibration* OnlineMapper::calibrationOf(const HeadSetting& setting) const {
  for (const KeptCalibration& kept : calibrations_) {
    if (kept.setting == setting) return &kept.calibration;
  }
  return nullptr;
}

void OnlineMapper::keepCalibration(const HeadSetting& setting, SweepCalibration calibration, std::size_t beams) {
  for (KeptCalibration& kept : calibrations_) {
    if (kept.setting == setting) {
      kept.calibration = std::move(calibration);
      kept.beams = beams;
      return;
    }
  }
  calibrations_.push_back({setting, std::move(calibration), beams});
}

void OnlineMapper::detectOnly(DetectedSweepSink sink) {
  if (provisional_) throw ValueError("online mapper: detection alone shows nothing (kSweep)");
  if (beams_grouped_ > 0 || !held_.empty() || finished_) throw ValueError("online mapper: detectOnly after the first beam");
  if (!sink) throw ValueError("online mapper: detectOnly needs a sink");
  detect_only_ = std::move(sink);
}

void OnlineMapper::addDetectedSweep(const DetectedSweep& sweep) {
  if (detect_only_) throw ValueError("online mapper: a detected sweep given to a detect-only mapper");
  integrateIntoMap(sweep);
  if (on_sweep_) on_sweep_(sweeps_);
  showWaitingBeams();
}

void OnlineMapper::integrateIntoMap(const DetectedSweep& sweep) {
  const std::unique_lock lock(map_mutex_);
  mapper_.recordDetection(sweep.detection);
  if (!sonar_to_body_) {
    mapper_.integrateSweep(sweep.polar, sweep.detection.detections, staticSonarToMap());  // no navigation
  } else {
    mapper_.integrateSweep(sweep.polar, sweep.detection.detections, posesAt(sweep.polar.time_s));
  }
  ++sweeps_;
  committedBefore(sweep.first_beam + static_cast<std::size_t>(sweep.polar.rows()));
}

void OnlineMapper::committedBefore(std::size_t end) {
  if (!provisional_) return;
  committed_end_ = std::max(committed_end_, end);
  while (!unshown_.empty() && unshown_.front().index < committed_end_) unshown_.pop_front();
  provisional_->dropBefore(committed_end_);
  // A longer range scale coarsened the committed map: the beams still shown follow it.
  if (mapper_.options().resolution_m) provisional_->atResolution(*mapper_.options().resolution_m);
}

void OnlineMapper::showWaitingBeams() {
  while (!unshown_.empty()) {
    const UnshownBeam& next = unshown_.front();
    // A beam after the last fix is shown at once at that fix's pose, held (the navigation lags the
    // sonar by up to a fix period, more through an autopilot's stream): for the eye only, as the
    // whole provisional layer is; its sweep is committed with the interpolated poses once the
    // navigation covers it. A beam more than kHeldPoseShown_s after the last fix waits.
    const bool covered = navigationCovers(next.beam.time_s);
    if (!covered && (fixes_.empty() || next.beam.time_s - fixes_.back().time_s > kHeldPoseShown_s)) return;
    // Otherwise a beam without a calibration waits for its setting's first whole sweep, and every
    // beam for the committed map's first sweep (its resolution).
    const SweepCalibration* calibration = calibrationOf(headSettingOf(next.beam));
    if (calibration == nullptr && shows_given_beams_ && headSettingOf(unshown_.back().beam) != headSettingOf(next.beam)) {
      // Given to show, with a beam of another setting after it: its group ended and was detected
      // (calibrateWith comes with it) without a calibration (too few beams to calibrate on), so
      // it is never shown. Fed by addBeam, such a group leaves with its commit.
      unshown_.pop_front();
      continue;
    }
    if (calibration == nullptr || !mapper_.options().resolution_m) return;
    PolarImage row = fitToCalibration(makePolarImage(std::vector<Beam>{next.beam}, 0, 1), *calibration);
    SweepDetection detection = mapper_.detectRows(row, *calibration);
    const std::optional<Eigen::Isometry3d> pose =
        covered ? posesAt(row.time_s).front() : std::optional(nedToMap() * bodyToNed(fixes_.back()) * *sonar_to_body_);
    {
      const std::unique_lock lock(map_mutex_);
      provisional_->atResolution(*mapper_.options().resolution_m);
      provisional_->add(next.index, next.starts_sweep, std::move(row), detection.detections.front(), pose);
    }
    unshown_.pop_front();
  }
}

void OnlineMapper::integrate(DetectedSweep sweep, bool calibrates) {
  const auto rows = static_cast<std::size_t>(sweep.polar.rows());
  if (detect_only_) {
    ++sweeps_;
  } else {
    integrateIntoMap(sweep);
  }
  waiting_beams_ -= rows;
  // The calibration later beams of this setting are detected with (short groups, provisional beams).
  if (calibrates) {  // the sink needs the sweep's own; otherwise it is moved, not copied
    keepCalibration(sweep.setting, detect_only_ ? sweep.detection.calibration : std::move(sweep.detection.calibration), rows);
  }
  if (detect_only_) detect_only_(std::move(sweep));
  if (on_sweep_) on_sweep_(sweeps_);
}

std::vector<std::optional<Eigen::Isometry3d>> OnlineMapper::posesAt(const std::vector<double>& times_s) const {
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  poses.reserve(times_s.size());
  if (!sonar_to_body_) {
    poses.assign(times_s.size(), staticSonarToMap());
    return poses;
  }
  if (fixes_.empty()) {
    poses.assign(times_s.size(), std::nullopt);
    return poses;
  }
  const NavInterpolator interpolator(fixes_, NavInterpolator::Prechecked{});  // addNavFix checked each fix
  const Eigen::Isometry3d ned_to_map = nedToMap();
  for (const double time_s : times_s) {
    const std::optional<Eigen::Isometry3d> body_to_ned = interpolator.bodyToNedAt(time_s);
    poses.push_back(body_to_ned ? std::optional(ned_to_map * *body_to_ned * *sonar_to_body_) : std::nullopt);
  }
  return poses;
}

std::size_t OnlineMapper::sweepsIntegrated() const {
  const std::shared_lock lock(map_mutex_);
  return sweeps_;
}

OcTree16 OnlineMapper::mapSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  return mapper_.map();
}

OcTree16 OnlineMapper::shownSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  OcTree16 map = mapper_.map();
  if (provisional_) provisional_->overlay(map);
  return map;
}

void OnlineMapper::visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const {
  const std::shared_lock lock(map_mutex_);
  const OcTree16& committed = mapper_.map();
  if (!provisional_ || box_m.isEmpty()) return visit(committed, {});
  const auto [min_key, max_key] = keyBoxOf(committed.coder(), box_m);
  visit(committed, provisional_->shownVoxels(committed, min_key, max_key));
}

MappingStats OnlineMapper::statsSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  return mapper_.stats();
}

MapperOptions OnlineMapper::optionsSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  return mapper_.options();
}

SonarMapper OnlineMapper::release() && {
  waitForDetections();
  in_flight_.clear();
  return std::move(mapper_);
}

}  // namespace sonarmap
