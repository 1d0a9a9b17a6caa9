/// @file heads.cpp
/// The drivers by protocol (see heads.hpp).

#include "sonarmap/devices/heads.hpp"

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

std::unique_ptr<HeadDriver> makeHeadDriver(LogFormat format, const HeadSettings& /*settings*/) {
  if (format != LogFormat::kPing360 && format != LogFormat::kSeaNet) {
    throw ValueError("a head is driven in the ping360 or seanet protocol");
  }
  return nullptr;
}

}  // namespace sonarmap
