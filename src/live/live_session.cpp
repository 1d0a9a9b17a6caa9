/// @file live_session.cpp
/// A live run's loop: links polled, beams and fixes mapped and recorded (see live_session.hpp).

#include "sonarmap/live/live_session.hpp"

#include <malloc.h>
#include <poll.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

#include "head_input.hpp"
#include "sonarmap/live/live_map_files.hpp"
#include "nav_input.hpp"
#include "silence_watch.hpp"
#include "periodic_map_writer.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/core/statistics.hpp"
#include "sonarmap/formats/dive_recorder.hpp"

namespace sonarmap {
namespace {

using Clock = std::chrono::steady_clock;

/// The longest wait of one poll: the stop flag, the driver's timeouts and the page's requests are
/// looked at this often.
constexpr int kPollPeriod_ms = 50;
/// Beams replayed as fast as possible between two looks at the stop flag and the page's requests.
constexpr std::size_t kReplayBatch = 64;

double median(std::vector<double> values) {
  return values.empty() ? std::numeric_limits<double>::quiet_NaN() : percentile(values, 0.5);
}

}  // namespace

struct LiveSession::Inputs {
  std::unique_ptr<live::HeadInput> head;
  std::unique_ptr<live::NavInput> nav;
  std::unique_ptr<BeamSource> replay;
  double rate = 0.0;
  double idle_timeout_s = 0.0;
  std::optional<Beam> next_replayed;  ///< the replay's next beam, read ahead to pace it
  std::optional<double> replay_zero_s;  ///< the replayed log's time at the run's start
  std::unique_ptr<DiveRecorder> recorder;
  std::vector<SkipReasonGroup> skip_reasons;  ///< grouped as they come: a stream may run for days
  live::SilenceWatch nav_watch{"the navigation"};  ///< a --nav-stream that falls silent, said
};

LiveSession::LiveSession(LiveInput input, LiveOutputs outputs, LiveMappingOptions mapping, NavTrack known_fixes,
                         LiveObserver* observer)
    : outputs_(std::move(outputs)), observer_(observer != nullptr ? observer : &silent_), start_(Clock::now()),
      epoch_at_start_s_(std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count()),
      inputs_(std::make_unique<Inputs>()) {
  Inputs& in = *inputs_;
  if (input.replay && !input.head.empty()) throw ValueError("a live run reads a head or replays a log, not both");
  if (!input.replay && input.head.empty()) throw ValueError("a live run needs a head's link or a log to replay");
  if (!(input.rate >= 0.0) || !std::isfinite(input.rate)) {
    throw ValueError("--rate must be ≥ 0 (1: the log's own pace, 0: as fast as possible)");
  }
  if (input.replay && !input.nav.empty()) throw ValueError("a replayed log takes --nav, not --nav-stream");
  in.rate = input.rate;
  in.idle_timeout_s = input.idle_timeout_s;
  if (input.replay) {
    in.replay = std::move(input.replay);
    in.replay->rewind();
  } else {
    in.head = std::make_unique<live::HeadInput>(input.head, input.baud, input.format, input.drive, input.settings);
    // Fixes known at the start count their time from it: put them on the run's clock.
    for (NavSample& fix : known_fixes) fix.time_s = beamClock(fix.time_s);
  }
  if (!input.nav.empty()) in.nav = std::make_unique<live::NavInput>(input.nav, input.baud);
  if (!outputs_.record_path.empty()) {
    DiveRecorderOptions record;
    record.nominal_beam = NominalBeam{mapping.mapper.beam_width_rad, mapping.mapper.vertical_aperture_rad};
    in.recorder = std::make_unique<DiveRecorder>(outputs_.record_path, record);
    if (!outputs_.record_metadata.empty()) in.recorder->addMetadata("sonarmap.run", outputs_.record_metadata);
    for (const NavSample& fix : known_fixes) in.recorder->addNavFix(fix);
  }
  mapping_ = std::make_unique<LiveMapping>(std::move(mapping), start_, known_fixes);
}

LiveSession::~LiveSession() = default;

double LiveSession::secondsSinceStart() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

double LiveSession::beamClock(double arrival_s) const { return DiveRecorder::recordedTime(epoch_at_start_s_ + arrival_s); }

std::string LiveSession::headDescription() const {
  if (inputs_->head) return inputs_->head->description() + (inputs_->head->driving() ? " (driving the head)" : " (listening)");
  return "a replayed log";
}

std::string LiveSession::navDescription() const { return inputs_->nav ? inputs_->nav->description() : std::string(); }

void LiveSession::feedBeam(Beam beam, double arrival_s, double time_s) {
  beam.time_s = time_s;
  if (inputs_->recorder) inputs_->recorder->addBeam(beam);
  Eigen::Isometry3d sonar_to_map = staticSonarToMap();
  if (const std::optional<NavSample>& fix = mapping_->lastFix()) sonar_to_map = sonarToMap(*fix, mapping_->sonarToBody());
  observer_->beam(mapping_->beams(), beam, arrival_s, sonar_to_map);
  mapping_->addBeam(std::move(beam), arrival_s);
  observer_->mapped(mapping_->beams() - mapping_->beamsUnshown(), mapping_->sweepsIntegrated());
}

void LiveSession::feedFix(NavSample fix, double arrival_s) {
  if (inputs_->recorder && isFinite(fix)) inputs_->recorder->addNavFix(fix);
  const std::size_t before = mapping_->fixes();
  mapping_->addFix(std::move(fix), arrival_s);
  if (mapping_->fixes() > before) observer_->fix(*mapping_->lastFix());
}

void LiveSession::serviceRequests() {
  if (reset_requested_) {
    mapping_->reset();
    ++resets_;
    observer_->reset();
    observer_->note("the map was reset: it starts again from the next beam");
    {
      const std::lock_guard lock(saving_);
      reset_requested_ = false;
    }
    reset_done_.notify_all();
  }
  if (flush_requested_.exchange(false) && inputs_->recorder) inputs_->recorder->flush();
}

void LiveSession::resetNow() {
  std::unique_lock lock(saving_);
  if (!running_) return;
  reset_requested_ = true;
  reset_done_.wait_for(lock, std::chrono::seconds(2), [this] { return !reset_requested_ || !running_; });
}

std::vector<std::pair<std::string, std::string>> LiveSession::saveNow() {
  std::vector<std::pair<std::string, std::string>> written;
  if (!outputs_.map_path.empty()) {
    live::writeLiveMapFiles(mapping_->shownSnapshot(), outputs_, mapping_->origin());
    written.emplace_back("map", outputs_.map_path);
    if (!outputs_.geotiff_path.empty() && outputs_.geodetic_origin) written.emplace_back("geotiff", outputs_.geotiff_path);
  }
  if (inputs_->recorder) {
    flush_requested_ = true;
    written.emplace_back("recording", inputs_->recorder->partialPath());
  }
  return written;
}

void LiveSession::report(double now_s, LiveResult& result) {
  if (now_s < last_status_s_ + 1.0) return;
  LiveProgress status;
  status.elapsed_s = now_s;
  status.bytes = inputs_->head ? inputs_->head->bytes() : 0;
  status.beams = mapping_->beams();
  status.beams_per_s = static_cast<double>(status.beams - beams_at_status_) / std::max(now_s - last_status_s_, 1e-9);
  status.skipped = inputs_->head ? inputs_->head->skipped() : 0;
  status.sweeps = mapping_->sweepsIntegrated();
  status.map_nodes = mapping_->mapper().mapper().map().counts().nodes;
  status.fixes = mapping_->fixes();
  status.shown_latency_s = median(mapping_->shown().takeRecent());
  status.committed_latency_s = median(mapping_->committed().takeRecent());
  observer_->status(status);
  beams_at_status_ = status.beams;
  last_status_s_ = now_s;
  if (inputs_->recorder) inputs_->recorder->flush();  // a killed run loses at most a second
  // The map's copies (the page's picture, the periodic write) come and go on other threads; glibc
  // keeps what they freed in their arenas, and a run of hours creeps up by it. Handed back once a
  // second (bench/live/live_dive.sh: see docs/performance.md, "Live on a vehicle").
  ::malloc_trim(0);
  (void)result;
}

void LiveSession::takeHeadNotes(LiveResult& result) {
  Inputs& in = *inputs_;
  if (!in.head) return;
  for (const std::string& line : in.head->takeNotes()) observer_->note(line);
  addSkipReasons(in.skip_reasons, in.head->takeSkipReasons());
  const std::string device = in.head->device();
  const AppliedSettings applied = in.head->applied();
  if (device != result.device || applied.text() != result.settings.text()) {
    result.device = device;
    result.settings = applied;
    observer_->headSettings(device, applied);
    if (in.recorder && !applied.fields.empty()) {
      std::map<std::string, std::string> values(applied.fields.begin(), applied.fields.end());
      values["head"] = applied.head;
      if (!device.empty()) values["device"] = device;
      in.recorder->addMetadata("sonarmap.head", values);
    }
  }
}

bool LiveSession::replayStep(double now_s) {
  Inputs& in = *inputs_;
  for (std::size_t fed = 0; fed < kReplayBatch; ++fed) {
    if (!in.next_replayed) in.next_replayed = in.replay->next();
    if (!in.next_replayed) return false;
    if (in.rate > 0.0) {
      if (!in.replay_zero_s) in.replay_zero_s = in.next_replayed->time_s - now_s * in.rate;
      const double due_s = (in.next_replayed->time_s - *in.replay_zero_s) / in.rate;
      if (due_s > secondsSinceStart()) {
        const auto wait_ms = static_cast<int>(std::ceil(1000.0 * (due_s - secondsSinceStart())));
        ::poll(nullptr, 0, std::clamp(wait_ms, 0, kPollPeriod_ms));
        return true;
      }
    }
    const double time_s = in.next_replayed->time_s;
    feedBeam(std::move(*in.next_replayed), secondsSinceStart(), time_s);
    in.next_replayed.reset();
  }
  return true;
}

LiveResult LiveSession::run(const std::function<bool()>& stop_requested) {
  Inputs& in = *inputs_;
  LiveResult result;
  live::PeriodicMapWriter writer(*mapping_, outputs_);
  running_ = true;
  if (in.head) in.head->start(secondsSinceStart());
  takeHeadNotes(result);
  double last_byte_s = 0.0;
  while (!stop_requested()) {
    serviceRequests();
    double now_s = secondsSinceStart();
    if (in.replay) {
      if (!replayStep(now_s)) break;
    } else {
      std::array<pollfd, 2> waiting{pollfd{in.head->fd(), POLLIN, 0}, pollfd{in.nav ? in.nav->fd() : -1, POLLIN, 0}};
      const int ready = ::poll(waiting.data(), in.nav ? 2 : 1, kPollPeriod_ms);
      now_s = secondsSinceStart();
      if (ready > 0 && in.nav && (waiting[1].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        bool ended = false;
        std::vector<NavSample> fixes = in.nav->read(now_s, ended);
        if (!fixes.empty()) {
          if (std::optional<std::string> back = in.nav_watch.heard(now_s)) observer_->note(*back);
        }
        for (NavSample& fix : fixes) {
          fix.time_s = beamClock(fix.time_s);
          feedFix(std::move(fix), now_s);
        }
        if (ended) observer_->note("the navigation stream ended (" + in.nav->description() + ")");
        result.nav_skipped = in.nav->skipped();
        result.nav_protocol = in.nav->protocol();
        for (const std::string& line : in.nav->takeNotes()) {
          observer_->note(line);
          result.nav_skip_reason = line;
        }
        if (ended) in.nav.reset();  // the navigation ended: beams beyond its last fix wait, then count
      }
      if (in.nav) in.nav->poll(now_s);
      if (std::optional<std::string> lost = in.nav_watch.check(now_s, "the beams after its last fix wait for it")) {
        observer_->note(*lost);
      }
      if (ready > 0 && (waiting[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        const std::size_t bytes_before = in.head->bytes();
        live::HeadRead read = in.head->read(now_s);
        if (in.head->bytes() > bytes_before) last_byte_s = now_s;
        const double time_s = beamClock(now_s);
        for (Beam& beam : read.beams) feedBeam(std::move(beam), now_s, time_s);
        if (read.ended) break;
      }
      in.head->poll(now_s);
      takeHeadNotes(result);
      if (in.idle_timeout_s > 0.0 && now_s - last_byte_s >= in.idle_timeout_s) break;
    }
    report(now_s, result);
    if (std::string line = writer.takeNote(); !line.empty()) observer_->note(line);
  }
  result.stopped = stop_requested();
  {
    const std::lock_guard lock(saving_);
    running_ = false;
  }
  reset_done_.notify_all();
  if (in.head) {
    in.head->stop();
    const double now_s = secondsSinceStart();
    for (Beam& beam : in.head->finish()) feedBeam(std::move(beam), now_s, beamClock(now_s));
    takeHeadNotes(result);
  }
  writer.stop();  // no periodic write races the final one
  mapping_->finish();
  if (in.recorder) {
    in.recorder->finish();
    result.recorded = in.recorder->path();
  }
  result.bytes = in.head ? in.head->bytes() : 0;
  result.beams = mapping_->beams();
  result.fixes = mapping_->fixes();
  result.fixes_dropped = mapping_->fixesDropped();
  result.skipped = in.head ? in.head->skipped() : in.replay->header().skipped_beams;
  if (in.replay) addSkipReasons(in.skip_reasons, in.replay->header().skip_reasons);
  result.skip_reasons = in.skip_reasons;
  result.resets = resets_;
  result.seconds = secondsSinceStart();
  return result;
}

}  // namespace sonarmap
