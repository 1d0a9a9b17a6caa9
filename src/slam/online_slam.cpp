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

std::size_t minBeams(const MapperOptions& options) {
  return static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
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
      grouper_(minBeams(options)),
      mapper_(std::make_unique<OnlineMapper>(options, sonar_to_body, integration)) {}

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
}

void OnlineSlam::addBeam(Beam beam) {
  if (finished_) throw ValueError("live slam: a beam after the end of the stream");
  const bool starts_sweep = splitter_.startsSweep(beam);
  const std::size_t final_beams = grouper_.add(starts_sweep, headSettingOf(beam));
  if (final_beams > 0) closeGroup(final_beams);
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
  mapper_->addBeam(std::move(beam));
}

void OnlineSlam::closeGroup(std::size_t beams) {
  SonarLog group;
  group.beams.assign(beams_.beams.begin() + static_cast<std::ptrdiff_t>(grouped_),
                     beams_.beams.begin() + static_cast<std::ptrdiff_t>(grouped_ + beams));
  const NavTrack none;
  std::vector<SonarScan> scans = formScans(group, navigation_ ? dead_reckoning_ : none, sonar_to_body_, options_, slam_.forming);
  for (SonarScan& scan : scans) {
    scan.first_beam += grouped_;
    // The scans before this one are in the map with (about) their poses as they are now.
    const std::vector<Pose2>& poses = localizer_.graph().poses();
    for (std::size_t k = mapped_poses_.size(); k < poses.size(); ++k) mapped_poses_.push_back(poses[k]);
    localizer_.addScan(std::move(scan));
  }
  grouped_ += beams;
  if (localizer_.scans().empty()) return;
  const std::size_t last = localizer_.scans().size() - 1;
  correction_ = localizer_.graph().pose(last) * localizer_.scans()[last].dead_reckoning.inverse();
  const std::size_t accepted = localizer_.report().loopClosuresAccepted();
  if (accepted > accepted_loops_) {
    accepted_loops_ = accepted;
    if (movedSinceRebuild()) rebuild();
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
  for (const Beam& beam : beams_.beams) {
    if (!navigation_ && (track.empty() || beam.time_s > track.back().time_s)) {
      NavSample fix;
      fix.time_s = beam.time_s;
      fix = corrected(fix);
      mapper->addNavFix(fix);
      track.push_back(fix);
    }
    mapper->addBeam(beam);
  }
  if (finished_) mapper->finish();
  mapped_poses_ = localizer_.graph().poses();
  std::unique_lock lock(swap_mutex_);
  mapper_ = std::move(mapper);
  ++rebuilds_;
}

void OnlineSlam::finish() {
  if (finished_) return;
  if (const std::size_t rest = grouper_.finish(); rest > 0) closeGroup(rest);
  localizer_.optimize();
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

std::size_t OnlineSlam::beamsPending() const { return mapper_->beamsPending(); }

}  // namespace sonarmap
