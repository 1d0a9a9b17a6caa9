#pragma once
/// @file bag_bytes.hpp
/// Test helper: a ROS 1 bag's bytes walked and damaged as a recorder leaves them (the ROS wiki's
/// "Bags/Format/2.0": records of a uint32 header length, NAME=VALUE fields, a uint32 data length
/// and the data; op 0x05 a chunk, whose data holds records, 0x02 a message). Independent of the
/// library's own walk, so that the tests check it.

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sonarmap::test {

/// One whole record: its first byte, where its data starts and ends, its op.
struct BagBytesRecord {
  std::size_t at = 0, data = 0, end = 0;
  int op = -1;
};

inline std::uint32_t bagU32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);  // little-endian, as the bag and the machine
  return value;
}

/// The whole records of `bytes` from `at` to `end`, up to the first that does not fit.
inline std::vector<BagBytesRecord> bagRecords(const std::string& bytes, std::size_t at, std::size_t end) {
  std::vector<BagBytesRecord> records;
  while (at + 4 <= end) {
    const std::size_t header_end = at + 4 + bagU32(bytes, at);
    if (header_end + 4 > end) break;
    const std::size_t data = header_end + 4;
    if (bagU32(bytes, header_end) > end - data) break;
    const std::size_t op = bytes.find("op=", at + 4);
    records.push_back({at, data, data + bagU32(bytes, header_end), op < header_end ? static_cast<unsigned char>(bytes[op + 3]) : -1});
    at = records.back().end;
  }
  return records;
}

/// A message record of a chunk: the file byte where it ends and its connection.
struct BagBytesMessage {
  std::size_t end = 0;
  std::uint32_t connection = 0;
};

/// The messages of an uncompressed bag, in file order; a chunk the file ends in gives its whole
/// messages.
inline std::vector<BagBytesMessage> bagMessages(const std::string& bytes) {
  std::vector<BagBytesMessage> messages;
  for (std::size_t at = 13; at + 4 <= bytes.size();) {
    const std::size_t header_end = at + 4 + bagU32(bytes, at);
    if (header_end + 4 > bytes.size()) break;
    const std::size_t data = header_end + 4;
    const std::size_t end = data + bagU32(bytes, header_end);
    if (bytes.find("op=\x05", at + 4) < header_end) {
      for (const BagBytesRecord& inner : bagRecords(bytes, data, std::min(end, bytes.size()))) {
        if (inner.op == 0x02) messages.push_back({inner.end, bagU32(bytes, bytes.find("conn=", inner.at) + 5)});
      }
    }
    at = end;
  }
  return messages;
}

/// How many messages of `messages` end by byte `cut`, of `connection` only unless it is -1.
inline std::size_t bagMessagesBefore(const std::vector<BagBytesMessage>& messages, std::size_t cut, long connection = -1) {
  std::size_t count = 0;
  for (const BagBytesMessage& message : messages) {
    count += message.end <= cut && (connection < 0 || message.connection == static_cast<std::uint32_t>(connection));
  }
  return count;
}

/// `bag` as a stopped `rosbag record` leaves it, cut at byte `cut` inside its last chunk: its
/// header's index position 0, the last chunk's sizes 0 (rosbag writes them when it closes the
/// chunk), nothing after the cut.
inline std::string stoppedRecording(const std::string& bag, std::size_t cut) {
  std::string out = bag;
  const std::size_t index_pos = out.find("index_pos=") + 10;
  out.replace(index_pos, 8, std::string(8, '\0'));
  std::size_t last_chunk = 0;
  for (const BagBytesRecord& record : bagRecords(bag, 13, bag.size())) {
    if (record.op == 0x05 && record.at < cut) last_chunk = record.at;
  }
  const std::size_t size = out.find("size=", last_chunk) + 5;
  out.replace(size, 4, std::string(4, '\0'));
  const std::size_t data_length = last_chunk + 4 + bagU32(bag, last_chunk);
  out.replace(data_length, 4, std::string(4, '\0'));
  return out.substr(0, cut);
}

}  // namespace sonarmap::test
