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
#include "sonarmap/sonar/polar.hpp"

namespace sonarmap {

struct OnlineMapper::DetectedSweep {
  PolarImage polar;
  SweepDetection detection;
};

namespace {
std::size_t minBeams(const MapperOptions& options) {
  return static_cast<std::size_t>(std::max(1, options.detector.background.min_beams));
}
}  // namespace

OnlineMapper::OnlineMapper(const MapperOptions& options, SweepCallback on_sweep)
    : mapper_(options), on_sweep_(std::move(on_sweep)), grouper_(minBeams(options)) {}

OnlineMapper::OnlineMapper(const MapperOptions& options, const Eigen::Isometry3d& sonar_to_body, SweepCallback on_sweep)
    : OnlineMapper(options, std::move(on_sweep)) {
  if (!sonar_to_body.matrix().allFinite()) throw ValueError("online mapper: the sonar's mounting is not finite");
  sonar_to_body_ = sonar_to_body;
}

OnlineMapper::~OnlineMapper() {
  if (in_flight_ && in_flight_->valid()) in_flight_->wait();  // never leave the detection thread running
}

void OnlineMapper::addNavFix(const NavSample& fix) {
  if (!sonar_to_body_) throw ValueError("online mapper: navigation fixes need the navigation constructor");
  const bool finite = std::isfinite(fix.time_s) && fix.position_ned_m.allFinite() && std::isfinite(fix.roll_rad) &&
                      std::isfinite(fix.pitch_rad) && std::isfinite(fix.yaw_rad);
  if (!finite) throw ValueError("online mapper: navigation fix with a value that is not finite");
  if (!fixes_.empty() && !(fix.time_s > fixes_.back().time_s)) {
    throw ValueError("online mapper: navigation fix at " + std::to_string(fix.time_s) + " s is not after the previous one (" +
                     std::to_string(fixes_.back().time_s) + " s)");
  }
  fixes_.push_back(fix);
  processReady();
}

void OnlineMapper::addBeam(Beam beam) {
  if (finished_) throw ValueError("online mapper: beam after finish()");
  if (!(std::isfinite(beam.bin_length_m) && beam.bin_length_m > 0.0)) {
    throw ValueError("online mapper: beam at " + std::to_string(beam.time_s) + " s has a bin length that is not > 0 m");
  }
  const std::size_t final_beams = grouper_.add(splitter_.startsSweep(beam));
  if (final_beams > 0) emitGroup(final_beams);
  held_.push_back(std::move(beam));
  processReady();
}

void OnlineMapper::finish() {
  if (finished_) return;
  finished_ = true;
  if (const std::size_t last = grouper_.finish(); last > 0) emitGroup(last);
  processReady();
  if (in_flight_) {
    std::unique_ptr<std::future<DetectedSweep>> last = std::move(in_flight_);
    integrate(last->get());
  }
}

void OnlineMapper::emitGroup(std::size_t beams) {
  std::vector<Beam> group;
  group.reserve(beams);
  std::move(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(beams), std::back_inserter(group));
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(beams));
  waiting_beams_ += beams;
  ready_.push_back(std::move(group));
}

bool OnlineMapper::navigationCovers(const std::vector<Beam>& group) const {
  if (!sonar_to_body_ || finished_) return true;
  double latest_s = -std::numeric_limits<double>::infinity();
  for (const Beam& beam : group) latest_s = std::max(latest_s, beam.time_s);
  return !fixes_.empty() && fixes_.back().time_s >= latest_s;
}

void OnlineMapper::processReady() {
  while (!ready_.empty() && navigationCovers(ready_.front())) {
    std::vector<Beam> group = std::move(ready_.front());
    ready_.pop_front();
    auto detect = [this, group = std::move(group)]() {
      DetectedSweep sweep{makePolarImage(group, 0, group.size()), {}};
      sweep.detection = mapper_.detectSweep(sweep.polar);  // const: touches no mapper state
      return sweep;
    };
    if (!mapper_.options().pipeline_detection) {
      integrate(detect());
      continue;
    }
    // Detect this sweep on a second thread while the one before it is integrated here.
    auto next = std::make_unique<std::future<DetectedSweep>>(std::async(std::launch::async, std::move(detect)));
    std::unique_ptr<std::future<DetectedSweep>> previous = std::exchange(in_flight_, std::move(next));
    if (previous) integrate(previous->get());  // rethrows what its detection threw
  }
}

void OnlineMapper::integrate(DetectedSweep sweep) {
  {
    const std::unique_lock lock(map_mutex_);
    mapper_.recordDetection(sweep.detection);
    if (!sonar_to_body_) {
      mapper_.integrateSweep(sweep.polar, sweep.detection.detections);
    } else {
      std::vector<std::optional<Eigen::Isometry3d>> poses;
      poses.reserve(sweep.polar.time_s.size());
      if (fixes_.empty()) {
        poses.assign(sweep.polar.time_s.size(), std::nullopt);
      } else {
        const NavInterpolator interpolator(fixes_);
        const Eigen::Isometry3d ned_to_map = nedToMap();
        for (const double time_s : sweep.polar.time_s) {
          const std::optional<Eigen::Isometry3d> body_to_ned = interpolator.bodyToNedAt(time_s);
          poses.push_back(body_to_ned ? std::optional(ned_to_map * *body_to_ned * *sonar_to_body_) : std::nullopt);
        }
      }
      mapper_.integrateSweep(sweep.polar, sweep.detection.detections, poses);
    }
    ++sweeps_;
    waiting_beams_ -= static_cast<std::size_t>(sweep.polar.rows());
  }
  if (on_sweep_) on_sweep_(sweeps_);
}

std::size_t OnlineMapper::sweepsIntegrated() const {
  const std::shared_lock lock(map_mutex_);
  return sweeps_;
}

OcTree16 OnlineMapper::mapSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  return mapper_.map();
}

MappingStats OnlineMapper::statsSnapshot() const {
  const std::shared_lock lock(map_mutex_);
  return mapper_.stats();
}

SonarMapper OnlineMapper::release() && {
  if (in_flight_ && in_flight_->valid()) in_flight_->wait();
  in_flight_.reset();
  return std::move(mapper_);
}

}  // namespace sonarmap
