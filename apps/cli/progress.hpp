#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal.

#include <cstddef>
#include <string>

namespace sonarmap::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  /// Redraws the bar at done / total (when it moved by at least 0.1 % since the last drawing).
  void update(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::size_t last_per_mille_ = 0;
};

}  // namespace sonarmap::cli
