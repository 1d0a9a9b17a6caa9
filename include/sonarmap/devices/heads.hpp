#pragma once
/// @file heads.hpp
/// The drivers of the heads `sonarmap live` drives, by the protocol they speak.

#include <memory>

#include "sonarmap/devices/head_driver.hpp"
#include "sonarmap/devices/head_settings.hpp"
#include "sonarmap/formats/log_reader.hpp"

namespace sonarmap {

/// A driver for a head speaking `format`'s protocol: LogFormat::kPing360 (ping360_driver.hpp) or
/// LogFormat::kSeaNet (seanet_driver.hpp), asking it for `settings`.
/// @throws ValueError for another format, or settings the head cannot take (naming the option and
///         what it can take).
std::unique_ptr<HeadDriver> makeHeadDriver(LogFormat format, const HeadSettings& settings);

}  // namespace sonarmap
