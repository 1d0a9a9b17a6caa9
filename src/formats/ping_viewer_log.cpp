/// @file ping_viewer_log.cpp
/// isPingViewerLog / parsePingViewerLog: Ping Viewer sensor logs (`.bin`) → SonarLog (layout in
/// ping360_reader.hpp, from Ping Viewer's LogSensorStruct and FileLink).

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ping360_messages.hpp"
#include "ping_viewer_time.hpp"
#include "reader_support.hpp"
#include "frame_scanner.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/ping360_reader.hpp"

namespace sonarmap {
namespace {

constexpr std::string_view kHeader = "PingViewer sensor log file";
constexpr std::int32_t kVersion = 1;
constexpr std::uint32_t kNull = 0xFFFFFFFFU;  // QDataStream's length of a null string or array
/// "hh:mm:ss.zzz" is 12 characters, 24 bytes in UTF-16 (36 in UTF-8 with 3-byte digits); a longer
/// time is no time stamp of Ping Viewer's and the reader has lost its place.
constexpr std::size_t kMaxTimeBytes = 64;
constexpr double kDay_s = 86400.0;

std::optional<std::uint32_t> beU32(std::span<const unsigned char> bytes, std::size_t at) {
  if (bytes.size() < 4 || at > bytes.size() - 4) return std::nullopt;
  return (std::uint32_t{bytes[at]} << 24) | (std::uint32_t{bytes[at + 1]} << 16) | (std::uint32_t{bytes[at + 2]} << 8) |
         bytes[at + 3];
}

/// `text` as Ping Viewer writes it: UTF-8 bytes, or UTF-16BE (each character after a zero byte).
bool sameText(std::span<const unsigned char> bytes, std::string_view text, bool utf16) {
  if (bytes.size() != text.size() * (utf16 ? 2 : 1)) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (utf16 ? (bytes[2 * i] != 0 || bytes[2 * i + 1] != static_cast<unsigned char>(text[i]))
              : bytes[i] != static_cast<unsigned char>(text[i])) {
      return false;
    }
  }
  return true;
}

/// What the header gives: where the records begin, the strings' encoding and the recorder.
struct Header {
  std::size_t first_record = 0;
  bool utf16 = false;
  std::string recorder;  ///< "Ping Viewer v2.1.0 on Windows 7 SP 1 (6.1)"
  std::int32_t sensor_type = 0;
};

/// Reads the header.
/// @throws FileError naming the byte and the field.
Header readHeader(std::span<const unsigned char> bytes, const std::string& source) {
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw FileError(source + ": byte " + std::to_string(at) + ": " + what);
  };
  const std::optional<std::uint32_t> length = beU32(bytes, 0);
  Header header;
  header.utf16 = length && *length == 2 * kHeader.size();
  if (!isPingViewerLog(bytes)) {
    fail(0, "no Ping Viewer header string '" + std::string(kHeader) + "' (not a Ping Viewer log)");
  }
  std::size_t at = 4 + *length;
  const std::optional<std::uint32_t> version = beU32(bytes, at);
  if (!version) fail(at, "file ends, expected the log version (int32)");
  if (static_cast<std::int32_t>(*version) != kVersion) {
    fail(at, "log version is " + std::to_string(static_cast<std::int32_t>(*version)) + ", expected 1");
  }
  at += 4;
  std::vector<std::string> texts;
  for (const char* field : {"git hash", "build date", "tag", "OS name", "OS version"}) {
    const std::optional<std::uint32_t> size = beU32(bytes, at);
    const std::size_t string_bytes = size && *size != kNull ? *size : 0;
    if (!size || string_bytes > bytes.size() - at - 4) fail(at, std::string("file ends inside the ") + field + " string");
    texts.push_back(detail::pingViewerText(bytes.subspan(at + 4, string_bytes), header.utf16));
    at += 4 + string_bytes;
  }
  if (bytes.size() - at < 8) fail(at, "file ends, expected the sensor family and type (two int32)");
  header.recorder = "Ping Viewer " + (texts[2].empty() ? texts[0] : texts[2]) + (texts[3].empty() ? "" : " on " + texts[3]);
  header.sensor_type = static_cast<std::int32_t>(*beU32(bytes, at + 4));
  header.first_record = at + 8;
  return header;
}

/// The data of the records as one stream, with where each record's data begins.
struct RecordStream {
  std::vector<unsigned char> stream;
  struct Chunk {
    std::size_t stream_at;  ///< where its data begin in `stream`
    std::size_t file_at;    ///< where its data begin in the file
    std::size_t record;     ///< record index
    double time_s;
  };
  std::vector<Chunk> chunks;

  const Chunk& chunkOf(std::size_t stream_offset) const {
    const auto after = std::upper_bound(chunks.begin(), chunks.end(), stream_offset,
                                        [](std::size_t offset, const Chunk& c) { return offset < c.stream_at; });
    return *(after - 1);
  }
};

/// Reads the records from `at`; stops (one skipped item for the rest) at a record cut short or
/// whose time is empty or too long.
RecordStream readRecords(std::span<const unsigned char> bytes, std::size_t at, bool utf16, const std::string& source,
                         SonarLog& log) {
  RecordStream records;
  std::optional<double> last_time_s;
  double day_offset_s = 0.0;
  std::size_t unreadable = 0;
  std::string first_unreadable;
  const auto note = [&] {
    if (unreadable == 0) return;
    log.notes.push_back(source + ": " + std::to_string(unreadable) + " record time(s) unreadable, their data kept at the previous record's time (the first: " +
                        first_unreadable + ")");
  };
  for (std::size_t index = 0; at < bytes.size(); ++index) {
    const std::string name = "record " + std::to_string(index) + " at byte " + std::to_string(at);
    const auto stop = [&](const std::string& why) {
      detail::addSkip(log, source, name + ": " + why + "; the last " + std::to_string(bytes.size() - at) + " bytes skipped");
      note();
    };
    const std::optional<std::uint32_t> time_bytes = beU32(bytes, at);
    if (!time_bytes) {
      stop("cut short in its time length");
      return records;
    }
    if (*time_bytes == 0 || *time_bytes == kNull) {
      stop("empty time (Ping Viewer stops reading here)");
      return records;
    }
    if (*time_bytes > kMaxTimeBytes) {
      stop("time of " + std::to_string(*time_bytes) + " bytes, expected hh:mm:ss.zzz");
      return records;
    }
    const std::size_t data_length_at = at + 4 + *time_bytes;
    const std::optional<std::uint32_t> data_bytes = beU32(bytes, data_length_at);
    if (!data_bytes) {
      stop("cut short before its data length");
      return records;
    }
    const std::size_t data_size = *data_bytes == kNull ? 0 : *data_bytes;
    if (data_size > bytes.size() - data_length_at - 4) {
      stop("data of " + std::to_string(data_size) + " bytes, the file ends " +
           std::to_string(bytes.size() - data_length_at - 4) + " bytes after their start");
      return records;
    }
    const std::span<const unsigned char> data = bytes.subspan(data_length_at + 4, data_size);
    const std::span<const unsigned char> time_text = bytes.subspan(at + 4, *time_bytes);
    std::optional<double> time_s = detail::pingViewerTime_s(time_text, utf16);
    if (time_s) {
      // QTime wraps at midnight: a log longer than a day starts again at 00:00:00.000.
      if (last_time_s && *time_s + day_offset_s < *last_time_s - kDay_s / 2.0) day_offset_s += kDay_s;
      *time_s += day_offset_s;
      last_time_s = time_s;
    } else {
      // The bytes are the sensor's stream, whatever the time says: a message may continue here.
      time_s = last_time_s.value_or(0.0);
      if (unreadable++ == 0) first_unreadable = name + ": '" + detail::pingViewerText(time_text, utf16) + "'";
    }
    if (!data.empty()) {
      records.chunks.push_back({records.stream.size(), data_length_at + 4, index, *time_s});
      records.stream.insert(records.stream.end(), data.begin(), data.end());
    }
    at = data_length_at + 4 + data_size;
  }
  note();
  return records;
}

}  // namespace

bool isPingViewerLog(std::span<const unsigned char> bytes) {
  const std::optional<std::uint32_t> length = beU32(bytes, 0);
  if (!length || (*length != kHeader.size() && *length != 2 * kHeader.size()) || bytes.size() - 4 < *length) return false;
  return sameText(bytes.subspan(4, *length), kHeader, *length != kHeader.size());
}

SonarLog parsePingViewerLog(std::span<const unsigned char> bytes, const std::string& source,
                            const CaptureOptions& options) {
  detail::checkSoundSpeed(options.sound_speed_m_s);
  const Header header = readHeader(bytes, source);
  SonarLog log;
  const RecordStream records = readRecords(bytes, header.first_record, header.utf16, source, log);
  const auto where = [&](std::size_t offset) {
    const RecordStream::Chunk& chunk = records.chunkOf(offset);
    return "byte " + std::to_string(chunk.file_at + offset - chunk.stream_at) + " (record " +
           std::to_string(chunk.record) + ")";
  };
  detail::Ping360Messages messages = detail::readPing360Messages(records.stream, source, options.sound_speed_m_s, where);
  for (std::size_t i = 0; i < messages.log.beams.size(); ++i) {
    Beam& beam = messages.log.beams[i];
    beam.time_s = records.chunkOf(messages.beam_ends[i] - 1).time_s;
    if (!log.beams.empty() && beam.time_s < log.beams.back().time_s) {
      detail::addSkip(log, source, "beam of the message ending at " + where(messages.beam_ends[i] - 1) +
                                       ": time before the previous beam's");
      continue;
    }
    log.beams.push_back(std::move(beam));
  }
  log.skipped_beams += messages.log.skipped_beams;
  log.skip_reasons.insert(log.skip_reasons.end(), messages.log.skip_reasons.begin(), messages.log.skip_reasons.end());
  // The header's sensor type: 2 is a Ping360, 1 a Ping echosounder (Ping Viewer's SensorInfo).
  const std::string device = !messages.device.empty() ? messages.device
                             : header.sensor_type == 2 ? "Ping360"
                                                       : "ping-protocol sensor type " + std::to_string(header.sensor_type);
  log.sonar = device + ", recorded by " + header.recorder;
  detail::requireBeams(log, bytes.size(), source, "Ping360 device_data messages in the records");
  return log;
}

}  // namespace sonarmap
