/// @file mavlink_tlog.cpp
/// readMavlinkTlogNavigation: a ground station's MAVLink telemetry log → NavTrack (see
/// vehicle_log_navigation.hpp). Frame layout and checksum: MAVLink's serialization spec
/// (mavlink.io/en/guide/serialization.html); message fields and CRC_EXTRA: common.xml as
/// generated into mavlink/c_library_v2 (a payload's fields sorted by size, largest first).

#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "reader_support.hpp"
#include "vehicle_track.hpp"

namespace sonarmap {
namespace {

constexpr std::uint8_t kMagicV1 = 0xFE;
constexpr std::uint8_t kMagicV2 = 0xFD;
constexpr std::uint8_t kSignedFlag = 0x01;
constexpr std::size_t kSignatureBytes = 13;

/// A message this reader decodes: id, CRC_EXTRA and full payload length (common.xml).
struct KnownMessage {
  std::uint32_t id;
  std::uint8_t crc_extra;
  std::size_t length;
};
constexpr std::uint32_t kAttitude = 30, kLocalPositionNed = 32, kGlobalPositionInt = 33, kScaledPressure2 = 137;
constexpr std::array<KnownMessage, 4> kKnown{{{kAttitude, 39, 28},
                                              {kLocalPositionNed, 185, 28},
                                              {kGlobalPositionInt, 104, 28},
                                              {kScaledPressure2, 195, 16}}};

const KnownMessage* known(std::uint32_t id) {
  for (const KnownMessage& m : kKnown) {
    if (m.id == id) return &m;
  }
  return nullptr;
}

/// CRC-16/MCRF4XX (X.25) accumulation, as MAVLink's checksum.h defines it.
std::uint16_t crcAccumulate(std::uint8_t byte, std::uint16_t crc) {
  std::uint8_t tmp = static_cast<std::uint8_t>(byte ^ (crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ (tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

template <typename T>
T little(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);  // MAVLink is little-endian, as every target of this project
  return value;
}

/// One decoded message: its sender, boot time, reception time and payload (zero-extended).
struct Frame {
  std::uint32_t id = 0;
  std::uint8_t system = 0, component = 0;
  std::uint64_t received_us = 0;
  std::array<std::uint8_t, 255> payload{};
};

/// A sample's boot time (ms) and reception (µs since 1970), before the boot clock is put on UTC.
struct Stamped {
  std::uint32_t boot_ms = 0;
  std::uint64_t received_us = 0;
};

class TlogNavigation {
 public:
  TlogNavigation(std::string source, const VehicleLogOptions& options) : source_(std::move(source)), options_(options) {}

  NavigationSource read(std::span<const std::uint8_t> bytes) {
    std::size_t offset = 0, record = 0;
    while (offset < bytes.size()) {
      ++record;
      if (!readRecord(bytes, offset, record)) break;
    }
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
    if (left < 9) return stop("cut short (" + std::to_string(left) + " bytes, expected an 8-byte time stamp and a frame)");
    const std::uint8_t* p = bytes.data() + offset;
    std::uint64_t received_us = 0;
    for (int i = 0; i < 8; ++i) received_us = (received_us << 8) | p[i];
    const std::uint8_t magic = p[8];
    if (magic != kMagicV1 && magic != kMagicV2) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", magic);
      return stop(std::string("no MAVLink frame after the time stamp (") + hex + " where 0xFE or 0xFD starts one)");
    }
    const bool v2 = magic == kMagicV2;
    const std::size_t header = v2 ? 10 : 6;
    if (left < 8 + header) return stop("a frame header cut short");
    const std::size_t length = p[9];
    const bool signed_frame = v2 && (p[10] & kSignedFlag) != 0;
    const std::size_t frame_bytes = header + length + 2 + (signed_frame ? kSignatureBytes : 0);
    if (left < 8 + frame_bytes) {
      return stop("a frame cut short (" + std::to_string(left - 8) + " of its " + std::to_string(frame_bytes) + " bytes)");
    }
    offset += 8 + frame_bytes;
    const std::uint8_t* frame = p + 8;
    Frame f;
    f.received_us = received_us;
    f.id = v2 ? static_cast<std::uint32_t>(frame[7] | (frame[8] << 8) | (frame[9] << 16)) : frame[5];
    f.system = v2 ? frame[5] : frame[3];
    f.component = v2 ? frame[6] : frame[4];
    const KnownMessage* message = known(f.id);
    if (message == nullptr) return true;  // not read; its CRC_EXTRA is not known here
    std::uint16_t crc = 0xFFFF;
    for (std::size_t i = 1; i < header + length; ++i) crc = crcAccumulate(frame[i], crc);
    crc = crcAccumulate(message->crc_extra, crc);
    if (crc != (frame[header + length] | (frame[header + length + 1] << 8)) || length > message->length) {
      ++skipped_;
      return true;
    }
    std::memcpy(f.payload.data(), frame + header, length);  // the rest stays zero (MAVLink 2 truncation)
    take(f);
    return true;
  }

  void take(const Frame& f) {
    if (f.id == kAttitude && !sender_) sender_ = {f.system, f.component};
    if (!sender_ || sender_->first != f.system || sender_->second != f.component) return;
    const std::uint8_t* q = f.payload.data();
    const Stamped stamp{little<std::uint32_t>(q), f.received_us};
    stamps_.push_back(stamp);
    switch (f.id) {
      case kAttitude:
        attitude_.push_back({stamp, {0.0, little<float>(q + 4), little<float>(q + 8), little<float>(q + 12)}});
        break;
      case kLocalPositionNed:
        positions_.push_back({stamp, {0.0, Eigen::Vector3d(little<float>(q + 4), little<float>(q + 8), little<float>(q + 12))}});
        break;
      case kGlobalPositionInt:
        relative_alt_.push_back({stamp, {0.0, Eigen::Vector3d(0.0, 0.0, -little<std::int32_t>(q + 16) / 1000.0)}});
        break;
      case kScaledPressure2:
        pressure_.push_back(
            {stamp, {0.0, Eigen::Vector3d(0.0, 0.0, detail::depthOfPressure_m(little<float>(q + 4) * 100.0, options_))}});
        break;
      default: break;
    }
  }

  /// Boot time → seconds since 1970: per boot (a boot time more than 10 s behind the last one
  /// starts another), the smallest reception − boot difference over its frames.
  double utcOf(const Stamped& s) const {
    for (const Boot& b : boots_) {
      if (s.received_us >= b.first_received_us && s.received_us <= b.last_received_us) {
        return (static_cast<double>(s.boot_ms) * 1000.0 + b.offset_us) / 1e6;
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

  void findBoots() {
    std::optional<std::uint32_t> last_boot_ms;
    for (const Stamped& s : stamps_) {
      if (!last_boot_ms || s.boot_ms + 10000.0 < *last_boot_ms) {
        boots_.push_back({s.received_us, s.received_us, std::numeric_limits<double>::infinity()});
      }
      Boot& b = boots_.back();
      b.last_received_us = s.received_us;
      b.offset_us = std::min(b.offset_us, static_cast<double>(s.received_us) - s.boot_ms * 1000.0);
      last_boot_ms = s.boot_ms;
    }
  }

  template <typename Sample>
  std::vector<Sample> onUtc(const std::vector<std::pair<Stamped, Sample>>& stamped) const {
    std::vector<Sample> samples;
    samples.reserve(stamped.size());
    for (const auto& [stamp, sample] : stamped) {
      samples.push_back(sample);
      samples.back().time_s = utcOf(stamp);
    }
    return samples;
  }

  NavigationSource finish(std::size_t records) {
    if (attitude_.empty()) {
      throw FileError("'" + source_ + "': no ATTITUDE message in " + std::to_string(records) + " records" +
                      (stop_note_.empty() ? std::string() : " (" + stop_note_ + ")"));
    }
    findBoots();
    NavigationSource nav;
    nav.clock_utc_s = 0.0;
    nav.skipped = skipped_;
    if (!stop_note_.empty()) nav.notes.push_back(stop_note_);
    std::vector<detail::PositionSample> depths = onUtc(relative_alt_);
    std::string depth_words = depths.empty() ? "" : "GLOBAL_POSITION_INT.relative_alt";
    if (depths.empty() && !pressure_.empty()) {
      depths = onUtc(pressure_);
      depth_words = "SCALED_PRESSURE2";
    }
    nav.track = detail::joinVehicleTrack(onUtc(attitude_), onUtc(positions_), std::move(depths));
    nav.description = "MAVLink telemetry " + std::filesystem::path(source_).filename().string() + " (" +
                      detail::vehicleTrackWords("ATTITUDE", positions_.empty() ? "" : "LOCAL_POSITION_NED", depth_words) +
                      ")";
    if (nav.track.empty()) {
      throw FileError("'" + source_ + "': no ATTITUDE message within the span of its position or depth messages");
    }
    return nav;
  }

  struct Boot {
    std::uint64_t first_received_us, last_received_us;
    double offset_us;
  };

  std::string source_;
  VehicleLogOptions options_;
  std::optional<std::pair<std::uint8_t, std::uint8_t>> sender_;
  std::vector<Stamped> stamps_;
  std::vector<Boot> boots_;
  std::vector<std::pair<Stamped, detail::AttitudeSample>> attitude_;
  std::vector<std::pair<Stamped, detail::PositionSample>> positions_, relative_alt_, pressure_;
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
