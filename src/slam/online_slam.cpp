/// @file online_slam.cpp
/// OnlineSlam (online_slam.hpp).

#include "sonarmap/slam/online_slam.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

/// The detector's options: the mapper's, detection not pipelined, so that each sweep reaches the
/// localizer as soon as it is final.
MapperOptions detectorOptions(MapperOptions options) {
  options.pipeline_detection = false;
  return options;
}

}  // namespace

OnlineSlam::OnlineSlam(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body, bool navigation,
                       const SlamOptions& slam, OnlineIntegration integration)
    : options_(options),
      sonar_to_body_(sonar_to_body),
      navigation_(navigation),
      slam_(slam),
      integration_(integration),
      localizer_(slam, navigation),
      detector_(std::make_unique<OnlineMapper>(detectorOptions(options), OnlineIntegration::kSweep)),
      mapper_(std::make_unique<OnlineMapper>(options, sonar_to_body, integration)) {
  detector_->detectOnly([this](DetectedSweep&& sweep) { addSweep(std::move(sweep)); });
}

OnlineSlam::OnlineSlam(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body, SlamOptionsFromFixes decide,
                       OnlineIntegration integration)
    : OnlineSlam(options, sonar_to_body, true, SlamOptions{}, integration) {
  if (!decide) throw ValueError("live slam: no rule to decide the localization's options by");
  decide_ = std::move(decide);
}

NavSample OnlineSlam::corrected(const NavSample& fix) const {
  const Pose2 pose = correction_ * Pose2{fix.position_ned_m.x(), fix.position_ned_m.y(), fix.yaw_rad};
  NavSample out = fix;
  out.position_ned_m.x() = pose.x_m;
  out.position_ned_m.y() = pose.y_m;
  out.yaw_rad = fix.yaw_rad + wrapAngle_rad(pose.yaw_rad - fix.yaw_rad);
  return out;
}

void OnlineSlam::addNavFix(const NavSample& fix) {
  if (!navigation_) throw ValueError("live slam: a navigation fix given to a run without navigation");
  if (!dead_reckoning_.empty() && !(fix.time_s > dead_reckoning_.back().time_s)) {
    throw ValueError("live slam: navigation fixes must come in strictly increasing time");
  }
  mapper_->addNavFix(corrected(fix));  // checks the values
  dead_reckoning_.push_back(fix);
  mapCoveredSweeps(*mapper_);
}

void OnlineSlam::addBeam(Beam beam) {
  if (finished_) throw ValueError("live slam: a beam after the end of the stream");
  if (!navigation_) {  // the vehicle believed still: a fix at the beam's time, where the scans put it
    NavSample fix;
    fix.time_s = beam.time_s;
    const NavTrack& last = dead_reckoning_;
    if (last.empty() || fix.time_s > last.back().time_s) {
      mapper_->addNavFix(corrected(fix));
      dead_reckoning_.push_back(fix);
    }
  }
  beams_.beams.push_back(beam);
  detector_->addBeam(beam);  // may finish a sweep: addSweep
  if (integration_ == OnlineIntegration::kProvisionalBeams) {
    mapper_->showBeam(beams_shown_, std::move(beam));
    ++beams_shown_;
  }
}

void OnlineSlam::addSweep(DetectedSweep&& sweep) {
  // The water evidence (SweepCalibration::water_evidence, about 2 KB a column) is kept only with the
  // newest sweep of each head setting: the provisional beams after it are detected with it.
  for (DetectedSweep& kept : sweeps_) {
    if (kept.setting == sweep.setting) {
      kept.detection.calibration.water_evidence = {};
      kept.detection.calibration.water_level = {};
    }
  }
  if (decide_ && sweeps_.empty()) {
    slam_ = decide_(dead_reckoning_);
    localizer_ = Localizer(slam_, navigation_);
  }
  DetectedLog one;
  one.options = options_;
  one.sweeps.push_back(std::move(sweep));
  const NavTrack none;
  std::vector<SonarScan> scans = formScans(one, navigation_ ? dead_reckoning_ : none, sonar_to_body_, slam_.forming);
  sweeps_.push_back(std::move(one.sweeps.front()));
  if (integration_ == OnlineIntegration::kProvisionalBeams) mapper_->calibrateWith(sweeps_.back());
  for (SonarScan& scan : scans) {
    // The scans before this one are in the map with (about) their poses as they are now.
    const std::vector<Pose2>& poses = localizer_.graph().poses();
    for (std::size_t k = mapped_poses_.size(); k < poses.size(); ++k) mapped_poses_.push_back(poses[k]);
    localizer_.addScan(std::move(scan));
  }
  rebuild_budget_ += kRebuildSweepsPerSweep;
  if (!localizer_.scans().empty()) {
    const std::size_t last = localizer_.scans().size() - 1;
    correction_ = localizer_.graph().pose(last) * localizer_.scans()[last].dead_reckoning.inverse();
    const std::size_t accepted = localizer_.report().loopClosuresAccepted();
    if (accepted > accepted_loops_) {
      accepted_loops_ = accepted;
      rebuild_wanted_ = rebuild_wanted_ || movedSinceRebuild();
    }
  }
  // A rebuild integrates every sweep so far again: it waits until the sweeps since the last one
  // have earned it, so that all of them together cost at most kRebuildSweepsPerSweep times the log.
  if (rebuild_wanted_ && rebuild_budget_ >= sweeps_.size()) {
    rebuild_budget_ -= sweeps_.size();
    rebuild_wanted_ = false;
    rebuild();
  }
  mapCoveredSweeps(*mapper_);
}

void OnlineSlam::mapCoveredSweeps(OnlineMapper& mapper) {
  while (sweeps_mapped_ < sweeps_.size()) {
    const DetectedSweep& sweep = sweeps_[sweeps_mapped_];
    const double last_beam_s = sweep.polar.time_s.empty() ? 0.0 : sweep.polar.time_s.back();
    const bool covered = finished_ || !navigation_ || (!dead_reckoning_.empty() && dead_reckoning_.back().time_s >= last_beam_s);
    if (!covered) return;
    mapper.addDetectedSweep(sweep);
    ++sweeps_mapped_;
  }
}

bool OnlineSlam::movedSinceRebuild() const {
  const std::vector<Pose2>& poses = localizer_.graph().poses();
  // Half a voxel, at the farthest a beam reaches: less than that changes no cell.
  const double voxel_m = mapper_->mapper().map().resolution_m();
  for (std::size_t k = 0; k < poses.size() && k < mapped_poses_.size(); ++k) {
    const double reach_m = localizer_.scans()[k].reach_m;
    const double moved_m = (poses[k].translation() - mapped_poses_[k].translation()).norm() +
                           reach_m * std::abs(wrapAngle_rad(poses[k].yaw_rad - mapped_poses_[k].yaw_rad));
    if (moved_m > 0.5 * voxel_m) return true;
  }
  return false;
}

NavTrack OnlineSlam::trajectory() const {
  return localizer_.correctedTrack(navigation_ ? dead_reckoning_ : NavTrack{});
}

void OnlineSlam::rebuild() {
  auto mapper = std::make_unique<OnlineMapper>(options_, sonar_to_body_, integration_);
  NavTrack track = trajectory();
  for (const NavSample& fix : track) mapper->addNavFix(fix);
  if (!navigation_) {  // a fix at each beam's time after the scans' track, as addBeam gives
    for (const Beam& beam : beams_.beams) {
      if (!track.empty() && beam.time_s <= track.back().time_s) continue;
      NavSample fix;
      fix.time_s = beam.time_s;
      fix = corrected(fix);
      mapper->addNavFix(fix);
      track.push_back(fix);
    }
  }
  sweeps_mapped_ = 0;
  mapCoveredSweeps(*mapper);
  sweeps_rebuilt_ += sweeps_mapped_;
  if (integration_ == OnlineIntegration::kProvisionalBeams && !finished_) showUnmappedBeams(*mapper);
  if (finished_) mapper->finish();
  mapped_poses_ = localizer_.graph().poses();
  std::unique_lock lock(swap_mutex_);
  mapper_ = std::move(mapper);
  ++rebuilds_;
}

void OnlineSlam::finish() {
  if (finished_) return;
  detector_->finish();  // the last sweeps' scans
  localizer_.optimize();
  if (!localizer_.scans().empty()) {
    const std::size_t last = localizer_.scans().size() - 1;
    correction_ = localizer_.graph().pose(last) * localizer_.scans()[last].dead_reckoning.inverse();
  }
  finished_ = true;
  rebuild();  // the map with the final trajectory: what the batch path makes
}

OcTree16 OnlineSlam::mapSnapshot() const {
  std::shared_lock lock(swap_mutex_);
  return mapper_->mapSnapshot();
}

std::size_t OnlineSlam::sweepsIntegrated() const {
  std::shared_lock lock(swap_mutex_);
  return mapper_->sweepsIntegrated();
}

std::size_t OnlineSlam::beamsUnshown() const {
  return integration_ == OnlineIntegration::kProvisionalBeams ? mapper_->beamsUnshown() : beamsPending();
}

OcTree16 OnlineSlam::shownSnapshot() const {
  std::shared_lock lock(swap_mutex_);
  return mapper_->shownSnapshot();
}

void OnlineSlam::visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const {
  std::shared_lock lock(swap_mutex_);
  mapper_->visitShown(box_m, visit);
}

void OnlineSlam::showUnmappedBeams(OnlineMapper& mapper) const {
  // The newest sweep of each head setting calibrates it (the older ones' water was dropped).
  std::vector<HeadSetting> calibrated;
  for (auto sweep = sweeps_.rbegin(); sweep != sweeps_.rend(); ++sweep) {
    if (std::find(calibrated.begin(), calibrated.end(), sweep->setting) != calibrated.end()) continue;
    calibrated.push_back(sweep->setting);
    mapper.calibrateWith(*sweep);
  }
  const std::size_t first = sweeps_mapped_ == 0 ? 0
                                                : sweeps_[sweeps_mapped_ - 1].first_beam +
                                                      static_cast<std::size_t>(sweeps_[sweeps_mapped_ - 1].polar.rows());
  for (std::size_t i = first; i < beams_shown_; ++i) mapper.showBeam(i, beams_.beams[i]);
}

std::size_t OnlineSlam::beamsPending() const {
  std::size_t pending = detector_->beamsPending();
  for (std::size_t k = sweeps_mapped_; k < sweeps_.size(); ++k) pending += static_cast<std::size_t>(sweeps_[k].polar.rows());
  return pending;
}

}  // namespace sonarmap
