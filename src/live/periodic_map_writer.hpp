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

#include "sonarmap/live/live_mapping.hpp"
#include "sonarmap/live/live_map_files.hpp"
#include "sonarmap/live/live_session.hpp"
#include "sonarmap/mapping/map_frame.hpp"

namespace sonarmap::live {

class PeriodicMapWriter {
 public:
  /// Writes `mapping`'s map as shown to outputs.map_path (and its GeoTIFF: writeLiveMapFiles) every
  /// outputs.write_every_s seconds once a sweep is integrated (nothing when map_path is empty). A failed write keeps the last good map; the final write, the
  /// caller's, reports for good.
  PeriodicMapWriter(const LiveMapping& mapping, LiveOutputs outputs) {
    if (outputs.map_path.empty()) return;
    const double every_s = outputs.write_every_s;
    thread_ = std::jthread([this, &mapping, outputs = std::move(outputs), every_s](std::stop_token stop) {
      std::mutex mutex;
      std::unique_lock lock(mutex);
      while (!wake_.wait_for(lock, stop, std::chrono::duration<double>(every_s), [] { return false; })) {
        if (stop.stop_requested()) return;
        if (mapping.sweepsIntegrated() == 0) continue;  // a map from the first sweep on
        try {
          writeLiveMapFiles(mapping.shownSnapshot(), outputs, mapping.origin());
        } catch (const std::exception&) {  // the last good map stays
        }
      }
    });
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
  std::jthread thread_;  // last: stopped and joined first
};

}  // namespace sonarmap::live
