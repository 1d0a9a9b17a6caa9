/// @file nav_input.cpp
/// Streamed navigation (see nav_input.hpp).

#include "nav_input.hpp"

namespace sonarmap::live {

NavInput::NavInput(const std::string& spec, unsigned baud) : link_(spec, baud), csv_(link_.description()), buffer_(65536) {}

std::vector<NavSample> NavInput::read(double now_s, bool& ended) {
  ended = false;
  const long got = link_.read(buffer_);
  if (got == 0) ended = true;
  if (got <= 0) return {};
  std::vector<NavSample> fixes = csv_.feed(std::span(buffer_.data(), static_cast<std::size_t>(got)));
  // CSV rows carry their sender's clock: put on the arrival clock by the first row's arrival.
  for (NavSample& fix : fixes) {
    if (!offset_s_) offset_s_ = now_s - fix.time_s;
    fix.time_s += *offset_s_;
  }
  return fixes;
}

}  // namespace sonarmap::live
