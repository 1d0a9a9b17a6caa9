/// @file heads.cpp
/// The drivers by protocol (see heads.hpp).

#include "sonarmap/devices/heads.hpp"

#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/seanet_driver.hpp"

namespace sonarmap {

std::unique_ptr<HeadDriver> makeHeadDriver(LogFormat format, const HeadSettings& settings) {
  if (format == LogFormat::kSeaNet) return std::make_unique<SeaNetDriver>(SeaNetDriverOptions{.settings = settings});
  if (format == LogFormat::kPing360) return nullptr;
  throw ValueError("a head is driven in the ping360 or seanet protocol");
}

}  // namespace sonarmap
