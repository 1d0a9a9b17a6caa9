/// @file mavlink.cpp
/// MAVLink frames: checksum, the known messages, readMavlinkFrame, MavlinkFrameParser,
/// MavlinkEncoder (see mavlink.hpp).

#include "sonarmap/formats/mavlink.hpp"

#include <algorithm>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

std::uint16_t crcAccumulate(std::uint8_t byte, std::uint16_t crc) {
  auto tmp = static_cast<std::uint8_t>(byte ^ (crc & 0xFF));
  tmp = static_cast<std::uint8_t>(tmp ^ (tmp << 4));
  return static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

std::uint16_t crcOfText(std::string_view text, std::uint16_t crc) {
  for (const char c : text) crc = crcAccumulate(static_cast<std::uint8_t>(c), crc);
  return crc;
}

// CRC_EXTRA of each message as mavlinkCrcExtra computes it from the XML definitions (the tests
// recompute them from the field lists; node-mavlink's MAGIC_NUMBERs agree). Lengths: the fields'
// sizes, extensions counted in max_length only.
constexpr std::array<MavlinkMessageInfo, 9> kMessages{{
    {0, "HEARTBEAT", 50, 9, 9},
    {22, "PARAM_VALUE", 220, 25, 25},
    {29, "SCALED_PRESSURE", 115, 14, 16},
    {30, "ATTITUDE", 39, 28, 28},
    {32, "LOCAL_POSITION_NED", 185, 28, 28},
    {33, "GLOBAL_POSITION_INT", 104, 28, 28},
    {137, "SCALED_PRESSURE2", 195, 14, 16},
    {143, "SCALED_PRESSURE3", 131, 14, 16},
    {11011, "VISION_POSITION_DELTA", 106, 44, 44},
}};

constexpr std::size_t kHeaderV1 = 6, kHeaderV2 = 10, kChecksumBytes = 2;

}  // namespace

std::uint16_t mavlinkCrc(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes) crc = crcAccumulate(b, crc);
  return crc;
}

std::uint8_t mavlinkCrcExtra(std::string_view message_name, std::span<const std::string_view> fields) {
  std::uint16_t crc = crcOfText(std::string(message_name) + " ", 0xFFFF);
  for (const std::string_view field : fields) {
    const std::size_t space = field.find(' ');
    std::string_view type = field.substr(0, space);
    const std::string_view name = space == std::string_view::npos ? std::string_view() : field.substr(space + 1);
    int array_length = 0;
    if (const std::size_t bracket = type.find('['); bracket != std::string_view::npos) {
      for (std::size_t i = bracket + 1; i < type.size() && type[i] >= '0' && type[i] <= '9'; ++i) {
        array_length = array_length * 10 + (type[i] - '0');
      }
      type = type.substr(0, bracket);
    }
    if (type == "uint8_t_mavlink_version") type = "uint8_t";
    crc = crcOfText(std::string(type) + " ", crc);
    crc = crcOfText(std::string(name) + " ", crc);
    if (array_length > 0) crc = crcAccumulate(static_cast<std::uint8_t>(array_length), crc);
  }
  return static_cast<std::uint8_t>((crc & 0xFF) ^ (crc >> 8));
}

std::span<const MavlinkMessageInfo> mavlinkMessages() { return kMessages; }

const MavlinkMessageInfo* findMavlinkMessage(std::uint32_t id) {
  for (const MavlinkMessageInfo& m : kMessages) {
    if (m.id == id) return &m;
  }
  return nullptr;
}

MavlinkFrameRead readMavlinkFrame(std::span<const std::uint8_t> bytes) {
  MavlinkFrameRead read;
  if (bytes.empty() || (bytes[0] != kMavlinkMagicV1 && bytes[0] != kMavlinkMagicV2)) {
    read.status = bytes.empty() ? MavlinkFrameStatus::kCutShort : MavlinkFrameStatus::kNoMagic;
    return read;
  }
  const bool v2 = bytes[0] == kMavlinkMagicV2;
  const std::size_t header = v2 ? kHeaderV2 : kHeaderV1;
  if (bytes.size() < header) {
    read.status = MavlinkFrameStatus::kCutShort;
    return read;
  }
  MavlinkFrame& f = read.frame;
  f.version = v2 ? 2 : 1;
  f.payload_length = bytes[1];
  if (v2) {
    f.incompat_flags = bytes[2];
    f.compat_flags = bytes[3];
    f.sequence = bytes[4];
    f.system = bytes[5];
    f.component = bytes[6];
    f.message_id = static_cast<std::uint32_t>(bytes[7] | (bytes[8] << 8) | (bytes[9] << 16));
    f.is_signed = (f.incompat_flags & kMavlinkFlagSigned) != 0;
  } else {
    f.sequence = bytes[2];
    f.system = bytes[3];
    f.component = bytes[4];
    f.message_id = bytes[5];
  }
  const std::size_t body = header + f.payload_length;  // the bytes the checksum follows
  read.size = body + kChecksumBytes + (f.is_signed ? kMavlinkSignatureBytes : 0);
  if ((f.incompat_flags & ~kMavlinkFlagSigned) != 0) {  // refused at once: the frame's layout is unknown
    read.status = MavlinkFrameStatus::kBadFlags;
    return read;
  }
  if (bytes.size() < read.size) {
    read.status = MavlinkFrameStatus::kCutShort;
    return read;
  }
  std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(header), f.payload_length, f.payload.begin());
  const MavlinkMessageInfo* info = findMavlinkMessage(f.message_id);
  if (info == nullptr) {
    read.status = MavlinkFrameStatus::kUnknownMessage;
    return read;
  }
  std::uint16_t crc = mavlinkCrc(bytes.subspan(1, body - 1));
  crc = crcAccumulate(info->crc_extra, crc);
  const auto sent = static_cast<std::uint16_t>(bytes[body] | (bytes[body + 1] << 8));
  if (crc != sent) {
    read.status = MavlinkFrameStatus::kBadChecksum;
  } else if (f.payload_length > info->max_length) {
    read.status = MavlinkFrameStatus::kBadLength;
  } else {
    read.status = MavlinkFrameStatus::kFrame;
    f.checked = true;
  }
  return read;
}

std::vector<MavlinkFrame> MavlinkFrameParser::feed(std::span<const std::uint8_t> bytes) {
  std::vector<MavlinkFrame> out;
  feed(bytes, out);
  return out;
}

void MavlinkFrameParser::feed(std::span<const std::uint8_t> bytes, std::vector<MavlinkFrame>& out) {
  counts_.bytes += bytes.size();
  held_.insert(held_.end(), bytes.begin(), bytes.end());
  const std::span<const std::uint8_t> all(held_);
  std::size_t at = 0;
  while (at < all.size()) {
    const std::uint8_t first = all[at];
    if (first != kMavlinkMagicV1 && first != kMavlinkMagicV2) {
      ++counts_.noise_bytes;
      ++at;
      continue;
    }
    const MavlinkFrameRead read = readMavlinkFrame(all.subspan(at));
    bool wait = false, take = false;
    switch (read.status) {
      case MavlinkFrameStatus::kFrame:
        take = true;
        break;
      case MavlinkFrameStatus::kUnknownMessage:
        // Unchecked: believed a frame when another frame starts right after it.
        if (at + read.size == all.size()) {
          wait = true;
        } else {
          const std::uint8_t next = all[at + read.size];
          take = next == kMavlinkMagicV1 || next == kMavlinkMagicV2;
        }
        break;
      case MavlinkFrameStatus::kCutShort:
        wait = true;
        break;
      case MavlinkFrameStatus::kBadChecksum:
      case MavlinkFrameStatus::kBadLength:
      case MavlinkFrameStatus::kBadFlags:
        ++counts_.bad_frames;
        break;
      case MavlinkFrameStatus::kNoMagic:
        break;
    }
    if (wait) break;
    if (take) {
      out.push_back(read.frame);
      ++(read.frame.checked ? counts_.frames : counts_.unknown_frames);
      at += read.size;
    } else {
      ++counts_.noise_bytes;  // the false start's magic byte; the search resumes after it
      ++at;
    }
  }
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(at));
}

MavlinkEncoder::MavlinkEncoder(std::uint8_t system, std::uint8_t component, int version)
    : system_(system), component_(component), version_(version) {
  if (version != 1 && version != 2) {
    throw ValueError("MavlinkEncoder: MAVLink version " + std::to_string(version) + ", expected 1 or 2");
  }
}

std::vector<std::uint8_t> MavlinkEncoder::encode(std::uint32_t message_id, std::span<const std::uint8_t> payload) {
  const MavlinkMessageInfo* info = findMavlinkMessage(message_id);
  if (info == nullptr) {
    throw ValueError("MavlinkEncoder: message " + std::to_string(message_id) + " is not one sonarmap knows");
  }
  if (payload.size() > info->max_length) {
    throw ValueError("MavlinkEncoder: " + std::string(info->name) + " payload of " + std::to_string(payload.size()) +
                     " bytes, expected at most " + std::to_string(info->max_length));
  }
  if (version_ == 1 && message_id > 255) {
    throw ValueError("MavlinkEncoder: " + std::string(info->name) + " (id " + std::to_string(message_id) +
                     ") cannot be sent in MAVLink 1 (ids 0-255)");
  }
  std::array<std::uint8_t, 255> full{};
  std::copy(payload.begin(), payload.end(), full.begin());
  std::size_t length = info->min_length;
  if (version_ == 2) {
    length = info->max_length;
    while (length > 1 && full[length - 1] == 0) --length;
  }
  std::vector<std::uint8_t> frame;
  frame.reserve(kHeaderV2 + length + kChecksumBytes);
  frame.push_back(version_ == 2 ? kMavlinkMagicV2 : kMavlinkMagicV1);
  frame.push_back(static_cast<std::uint8_t>(length));
  if (version_ == 2) {
    frame.push_back(0);  // incompat flags: unsigned
    frame.push_back(0);  // compat flags
  }
  frame.push_back(sequence_);
  frame.push_back(system_);
  frame.push_back(component_);
  frame.push_back(static_cast<std::uint8_t>(message_id & 0xFF));
  if (version_ == 2) {
    frame.push_back(static_cast<std::uint8_t>((message_id >> 8) & 0xFF));
    frame.push_back(static_cast<std::uint8_t>((message_id >> 16) & 0xFF));
  }
  frame.insert(frame.end(), full.begin(), full.begin() + static_cast<std::ptrdiff_t>(length));
  const std::uint16_t crc = crcAccumulate(info->crc_extra, mavlinkCrc(std::span(frame).subspan(1)));
  frame.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  frame.push_back(static_cast<std::uint8_t>(crc >> 8));
  ++sequence_;
  return frame;
}

}  // namespace sonarmap
