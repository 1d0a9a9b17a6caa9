/// @file nav_input.cpp
/// Streamed navigation (see nav_input.hpp).

#include "nav_input.hpp"

namespace sonarmap::live {

NavInput::NavInput(const std::string& spec, unsigned baud)
    : link_(spec, baud), stream_(link_.description()), buffer_(65536) {}

std::vector<NavSample> NavInput::read(double now_s, bool& ended) {
  ended = false;
  const long got = link_.read(buffer_);
  if (got == 0) {
    ended = true;
    return stream_.finish();
  }
  if (got < 0) return {};
  return stream_.feed(std::span(buffer_.data(), static_cast<std::size_t>(got)), now_s);
}

}  // namespace sonarmap::live
