/// @file mavlink_tlog.cpp
/// readMavlinkTlogNavigation: a ground station's MAVLink telemetry log → NavTrack (see
/// vehicle_log_navigation.hpp). The records' frames are read by readMavlinkFrame (mavlink.hpp) and
/// made into fixes by the live decoder's rules (MavlinkFixMaker, mavlink_navigation.hpp); only the
/// clock differs: every fix of a boot is put on the least delay of the whole boot, known at the end.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "mavlink_fixes.hpp"
#include "reader_support.hpp"
#include "vehicle_track.hpp"

namespace sonarmap {
namespace {

constexpr std::size_t kStampBytes = 8;

class TlogNavigation {
 public:
  TlogNavigation(std::string source, const VehicleLogOptions& options)
      : source_(std::move(source)), maker_(MavlinkNavigationOptions{options}) {}

  NavigationSource read(std::span<const std::uint8_t> bytes) {
    std::size_t offset = 0, record = 0;
    while (offset < bytes.size()) {
      ++record;
      if (!readRecord(bytes, offset, record)) break;
    }
    maker_.finish(fixes_);
    return finish(record);
  }

 private:
  /// Reads the record at `offset` and moves past it; false (with a note) where the log stops.
  bool readRecord(std::span<const std::uint8_t> bytes, std::size_t& offset, std::size_t record) {
    const std::size_t left = bytes.size() - offset;
    const auto stop = [&](const std::string& why) {
      stop_note_ = "'" + source_ + "': record " + std::to_string(record) + " at byte " + std::to_string(offset) + ": " +
                   why + "; the " + std::to_string(record - 1) + " records before it are kept";
      return false;
    };
    if (left < kStampBytes + 1) {
      return stop("cut short (" + std::to_string(left) + " bytes, expected an 8-byte time stamp and a frame)");
    }
    const std::uint8_t* p = bytes.data() + offset;
    std::uint64_t received_us = 0;
    for (std::size_t i = 0; i < kStampBytes; ++i) received_us = (received_us << 8) | p[i];
    const MavlinkFrameRead read = readMavlinkFrame(bytes.subspan(offset + kStampBytes));
    if (read.status == MavlinkFrameStatus::kNoMagic) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", p[kStampBytes]);
      return stop(std::string("no MAVLink frame after the time stamp (") + hex + " where 0xFE or 0xFD starts one)");
    }
    if (read.size == 0) return stop("a frame header cut short");
    if (read.size > left - kStampBytes) {
      return stop("a frame cut short (" + std::to_string(left - kStampBytes) + " of its " + std::to_string(read.size) +
                  " bytes)");
    }
    offset += kStampBytes + read.size;
    switch (read.status) {
      case MavlinkFrameStatus::kFrame: {
        // Arrival in seconds from the first record: small numbers keep the clock's microseconds.
        if (!first_us_) first_us_ = received_us;
        const double arrival_s = (static_cast<double>(received_us) - static_cast<double>(*first_us_)) / 1e6;
        maker_.take(read.frame, arrival_s, fixes_);
        break;
      }
      case MavlinkFrameStatus::kBadChecksum:
      case MavlinkFrameStatus::kBadLength:
      case MavlinkFrameStatus::kBadFlags:
        ++skipped_;
        break;
      default:  // an unknown message: not read (its CRC_EXTRA is not known here)
        break;
    }
    return true;
  }

  NavigationSource finish(std::size_t records) {
    if (!maker_.sawAttitude()) {
      throw FileError("'" + source_ + "': no ATTITUDE message in " + std::to_string(records) + " records" +
                      (stop_note_.empty() ? std::string() : " (" + stop_note_ + ")"));
    }
    NavigationSource nav;
    nav.clock_utc_s = 0.0;
    nav.skipped = skipped_;
    if (!stop_note_.empty()) nav.notes.push_back(stop_note_);
    const double first_s = static_cast<double>(first_us_.value_or(0)) / 1e6;
    nav.track.reserve(fixes_.size());
    for (detail::BootFix& f : fixes_) {
      f.fix.time_s = first_s + (f.fix.time_s + maker_.clockOffset_s(f.boot));
      nav.track.push_back(f.fix);
    }
    // Boots put on their own least delays may overlap: the track keeps time order, the first of equal times.
    std::stable_sort(nav.track.begin(), nav.track.end(),
                     [](const NavSample& a, const NavSample& b) { return a.time_s < b.time_s; });
    nav.track.erase(std::unique(nav.track.begin(), nav.track.end(),
                                [](const NavSample& a, const NavSample& b) { return a.time_s == b.time_s; }),
                    nav.track.end());
    for (const detail::MavlinkFixMaker::BootGeodeticFix& g : maker_.geodeticFixes()) {
      GeodeticFix fix = g.fix;
      fix.time_s = first_s + (fix.time_s + maker_.clockOffset_s(g.boot));
      nav.geodetic_fixes.push_back(fix);
    }
    std::stable_sort(nav.geodetic_fixes.begin(), nav.geodetic_fixes.end(),
                     [](const GeodeticFix& a, const GeodeticFix& b) { return a.time_s < b.time_s; });
    if (!nav.geodetic_fixes.empty()) nav.geodetic_description = "GLOBAL_POSITION_INT (lat, lon)";
    if (maker_.geodeticRejected() > 0) {
      nav.notes.push_back(std::to_string(maker_.geodeticRejected()) + " GLOBAL_POSITION_INT positions skipped, the first: " +
                          maker_.geodeticReason());
    }
    nav.description = "MAVLink telemetry " + std::filesystem::path(source_).filename().string() + " (" +
                      maker_.description() + ")";
    if (nav.track.empty()) {
      throw FileError("'" + source_ + "': no ATTITUDE message within the span of its position or depth messages");
    }
    return nav;
  }

  std::string source_;
  detail::MavlinkFixMaker maker_;
  std::vector<detail::BootFix> fixes_;
  std::optional<std::uint64_t> first_us_;
  std::size_t skipped_ = 0;
  std::string stop_note_;
};

}  // namespace

NavigationSource parseMavlinkTlogNavigation(std::span<const std::uint8_t> bytes, const std::string& source,
                                            const VehicleLogOptions& options) {
  detail::checkVehicleLogOptions(options, "parseMavlinkTlogNavigation");
  return TlogNavigation(source, options).read(bytes);
}

NavigationSource readMavlinkTlogNavigation(const std::string& path, const VehicleLogOptions& options) {
  const std::vector<unsigned char> bytes = detail::readFileBytes(path);
  return parseMavlinkTlogNavigation(bytes, path, options);
}

}  // namespace sonarmap
