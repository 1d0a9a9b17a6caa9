#pragma once
/// @file stage_latencies.hpp
/// A live run's latency bookkeeping: how long each beam took from its arrival to a stage (shown in the
/// map, or committed to it), in seconds on the live run's steady clock.

#include <deque>
#include <utility>
#include <vector>

namespace sonarmap {

/// The latencies of beams from their arrival to one stage (shown, or in the committed map). Beams
/// reach a stage in arrival order, so those still waiting are the newest.
class StageLatencies {
 public:
  void arrived(double arrival_s, bool calibrating) { waiting_.push_back({arrival_s, calibrating}); }
  /// `waiting`: how many of the beams that arrived have not reached the stage at `now_s`.
  void settle(std::size_t waiting, double now_s) {
    while (waiting_.size() > waiting) {
      const auto [arrival_s, calibrating] = waiting_.front();
      waiting_.pop_front();
      recent_.push_back(now_s - arrival_s);
      (calibrating ? first_sweep_ : all_).push_back(now_s - arrival_s);
    }
  }
  /// Latencies (s) since the last call.
  std::vector<double> takeRecent() { return std::exchange(recent_, {}); }
  /// Latencies (s) of the beams that arrived after the first sweep was integrated, and before.
  std::vector<double>& all() { return all_; }
  std::vector<double>& firstSweep() { return first_sweep_; }

 private:
  struct Arrival {
    double arrival_s = 0.0;
    bool calibrating = false;  ///< arrived before the first sweep was integrated
  };
  std::deque<Arrival> waiting_;
  std::vector<double> recent_;
  std::vector<double> all_;          ///< after the first sweep
  std::vector<double> first_sweep_;  ///< waiting for the first sweep's calibration
};

}  // namespace sonarmap
