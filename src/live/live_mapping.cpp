/// @file live_mapping.cpp
/// The mapper of a live run (see live_mapping.hpp).

#include "sonarmap/live/live_mapping.hpp"

#include <utility>

namespace sonarmap {

LiveMapping::LiveMapping(LiveMappingOptions options, std::chrono::steady_clock::time_point start,
                         const NavTrack& known_fixes)
    : options_(std::move(options)), start_(start), fixes_(known_fixes), origin_(options_.origin) {
  if (!origin_ && !fixes_.empty()) {
    origin_ = chooseLocalOrigin(fixes_, options_.given_origin, options_.origin_resolution_m, 0.0);
  }
  if (origin_) moveToOrigin(fixes_, origin_->ned_m);
  if (!fixes_.empty()) last_fix_ = fixes_.back();
  build();
}

LocalOrigin LiveMapping::origin() const {
  const std::lock_guard lock(origin_mutex_);
  return origin_.value_or(LocalOrigin{});
}

LiveMapping::~LiveMapping() = default;

void LiveMapping::build() {
  const std::lock_guard lock(replacing_);
  slam_.reset();
  mapper_.reset();
  if (options_.slam_from_fixes && options_.navigation) {
    slam_ = std::make_unique<OnlineSlam>(options_.mapper, options_.sonar_to_body, options_.slam_from_fixes, options_.integration);
    for (const NavSample& fix : fixes_) slam_->addNavFix(fix);
  } else if (options_.slam) {
    slam_ = std::make_unique<OnlineSlam>(options_.mapper, options_.sonar_to_body, options_.navigation, *options_.slam,
                                         options_.integration);
    for (const NavSample& fix : fixes_) slam_->addNavFix(fix);
  } else if (!options_.navigation) {
    mapper_ = std::make_unique<OnlineMapper>(options_.mapper, options_.integration);
  } else {
    mapper_ = std::make_unique<OnlineMapper>(options_.mapper, options_.sonar_to_body, options_.integration);
    for (const NavSample& fix : fixes_) mapper_->addNavFix(fix);
  }
}

void LiveMapping::addBeam(Beam beam, double arrival_s) {
  shown_.arrived(arrival_s, sweepsIntegrated() == 0);
  committed_.arrived(arrival_s, sweepsIntegrated() == 0);
  if (slam_) {
    slam_->addBeam(std::move(beam));
  } else {
    mapper_->addBeam(std::move(beam));
  }
  ++beams_;
  collect();
}

void LiveMapping::addFix(NavSample fix, double /*arrival_s*/) {
  if (!origin_) {
    const std::lock_guard lock(origin_mutex_);
    origin_ = chooseLocalOrigin({fix}, options_.given_origin, options_.origin_resolution_m, 0.0);
  }
  fix.position_ned_m -= origin_->ned_m;
  if (!isFinite(fix) || (!fixes_.empty() && !(fix.time_s > fixes_.back().time_s))) {
    ++fixes_dropped_;
    return;
  }
  if (slam_) {
    slam_->addNavFix(fix);
  } else {
    mapper_->addNavFix(fix);
  }
  fixes_.push_back(fix);
  last_fix_ = fix;
  collect();
}

void LiveMapping::finish() {
  if (slam_) {
    slam_->finish();
  } else {
    mapper_->finish();
  }
  beams_shown_ = beams_ - beams_at_reset_;
}

std::size_t LiveMapping::reset() {
  const std::size_t dropped = beams_ - beams_at_reset_;
  beams_at_reset_ = beams_;
  shown_ = StageLatencies{};
  committed_ = StageLatencies{};
  build();
  beams_shown_ = 0;
  return dropped;
}

OnlineMapper& LiveMapping::mapper() { return slam_ ? slam_->mapper() : *mapper_; }

OcTree16 LiveMapping::shownSnapshot() const {
  const std::lock_guard lock(replacing_);
  return slam_ ? slam_->shownSnapshot() : mapper_->shownSnapshot();
}

void LiveMapping::visitShown(const Eigen::AlignedBox3d& box_m, const ShownMapVisitor& visit) const {
  const std::lock_guard lock(replacing_);
  slam_ ? slam_->visitShown(box_m, visit) : mapper_->visitShown(box_m, visit);
}

std::size_t LiveMapping::sweepsIntegrated() const {
  const std::lock_guard lock(replacing_);
  return slam_ ? slam_->sweepsIntegrated() : mapper_->sweepsIntegrated();
}

void LiveMapping::collect() {
  const double now_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t unshown = slam_ ? slam_->beamsUnshown() : mapper_->beamsUnshown();
  shown_.settle(unshown, now_s);
  committed_.settle(slam_ ? slam_->beamsPending() : mapper_->beamsPending(), now_s);
  beams_shown_ = beams_ - beams_at_reset_ - unshown;
}

}  // namespace sonarmap
