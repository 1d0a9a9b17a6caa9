#pragma once
/// @file silence_watch.hpp
/// Private to src/live: a stream that falls silent, said when it happens and then less and less
/// often while it lasts, and when it comes back. Silence is judged against the stream's own pace:
/// no item for kPeriods times its median interval (at least kMinSilence_s), so a 10 Hz autopilot is
/// lost after 2 s and a 0.5 Hz one after 20 s. While it lasts the note repeats each time the
/// silence has doubled (2, 4, 8… times the threshold), so a long loss is said a few times, never
/// every second.

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace sonarmap::live {

class SilenceWatch {
 public:
  static constexpr double kMinSilence_s = 2.0;
  static constexpr double kPeriods = 10.0;
  static constexpr std::size_t kIntervals = 32;  ///< the recent intervals the pace is taken from

  /// @param what  names the stream in the notes ("the navigation").
  explicit SilenceWatch(std::string what) : what_(std::move(what)) {}

  /// An item arrived at `now_s` (seconds, steady). Returns the note when it ends a silence.
  std::optional<std::string> heard(double now_s) {
    std::optional<std::string> note;
    if (said_ > 0) note = what_ + " is back after " + seconds(now_s - last_s_) + " of silence";
    if (last_s_ >= 0.0) {
      intervals_.push_back(now_s - last_s_);
      if (intervals_.size() > kIntervals) intervals_.pop_front();
    }
    last_s_ = now_s;
    said_ = 0;
    return note;
  }

  /// The silence's threshold now, seconds (kMinSilence_s before two items).
  double threshold_s() const {
    if (intervals_.empty()) return kMinSilence_s;
    std::vector<double> sorted(intervals_.begin(), intervals_.end());
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    return std::max(kMinSilence_s, kPeriods * sorted[sorted.size() / 2]);
  }

  /// The note due at `now_s`: the first when the silence passes the threshold, then each time it
  /// has doubled; nothing before the first item. `consequence` ends the note ("beams wait for it").
  std::optional<std::string> check(double now_s, const std::string& consequence) {
    if (last_s_ < 0.0) return std::nullopt;
    const double silent_s = now_s - last_s_;
    const double due_s = threshold_s() * static_cast<double>(1U << std::min<std::size_t>(said_, 20));
    if (silent_s < due_s) return std::nullopt;
    ++said_;
    return what_ + " lost: nothing for " + seconds(silent_s) + " (the last at " + seconds(last_s_) +
           " into the run)" + (consequence.empty() ? "" : "; " + consequence);
  }

 private:
  static std::string seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", s);
    return text;
  }

  std::string what_;
  std::deque<double> intervals_;
  double last_s_ = -1.0;
  std::size_t said_ = 0;  ///< notes said during the current silence
};

}  // namespace sonarmap::live
