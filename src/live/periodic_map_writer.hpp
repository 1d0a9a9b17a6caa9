#pragma once
/// @file periodic_map_writer.hpp
/// Private to src/live: the map as shown rewritten atomically every few seconds on its own thread,
/// from a snapshot, so that writing a large map never holds up the beams.

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>
#include <utility>

#include "sonarmap/live/live_mapping.hpp"
#include "sonarmap/live/live_map_files.hpp"
#include "sonarmap/live/live_session.hpp"
#include "sonarmap/mapping/map_frame.hpp"

namespace sonarmap::live {

class PeriodicMapWriter {
 public:
  /// Writes `mapping`'s map as shown to outputs.map_path (and its GeoTIFF: writeLiveMapFiles) every
  /// outputs.write_every_s seconds once a sweep is integrated (nothing when map_path is empty). A
  /// failed write keeps the last good map, and is said once (takeNote) until writes work again;
  /// the final write, the caller's, reports for good.
  PeriodicMapWriter(const LiveMapping& mapping, LiveOutputs outputs) {
    if (outputs.map_path.empty()) return;
    const double every_s = outputs.write_every_s;
    thread_ = std::jthread([this, &mapping, outputs = std::move(outputs), every_s](std::stop_token stop) {
      std::mutex mutex;
      std::unique_lock lock(mutex);
      while (!wake_.wait_for(lock, stop, std::chrono::duration<double>(every_s), [] { return false; })) {
        if (stop.stop_requested()) return;
        if (mapping.sweepsIntegrated() == 0) continue;  // a map from the first sweep on
        std::string failure;
        try {
          writeLiveMapFiles(mapping.shownSnapshot(), outputs, mapping.origin());
        } catch (const std::exception& error) {  // the last good map stays
          failure = error.what();
        }
        const std::lock_guard guard(state_);
        if (failure != failure_) {
          note_ = failure.empty() ? "the periodic map writes work again" : "the periodic map write failed (the last good map stays): " + failure;
          failure_ = failure;
        }
      }
    });
  }
  /// A line for the user when a periodic write began to fail, failed otherwise, or works again
  /// since the last call; empty otherwise. Safe from any thread.
  std::string takeNote() {
    const std::lock_guard guard(state_);
    return std::exchange(note_, {});
  }
  /// Stops the thread (and waits for a write in progress).
  void stop() {
    if (thread_.joinable()) {
      thread_.request_stop();
      thread_.join();
    }
  }

 private:
  std::condition_variable_any wake_;
  std::mutex state_;
  std::string failure_;  ///< the last write's error ("" when it worked)
  std::string note_;     ///< not taken yet
  std::jthread thread_;  // last: stopped and joined first
};

}  // namespace sonarmap::live
