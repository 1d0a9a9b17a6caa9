/// @file ros_bag_scan.cpp
/// A ROS 1 bag walked record by record from its start (see ros_bag_scan.hpp).

#include "ros_bag_scan.hpp"

#include <algorithm>

namespace sonarmap::detail {
namespace {

/// Bytes of one index entry (format 2.0, index version 1: a uint64 time and a uint32 offset).
constexpr std::uint64_t kIndexEntry = 12;

}  // namespace

BagScan::BagScan(const std::string& path) : file_(path) {
  if (file_.read(0, std::min<std::uint64_t>(file_.size(), kBagVersionLine.size())) != kBagVersionLine) {
    file_.fail(0, "the first line is not '#ROSBAG V2.0' (format 2.0 is read)");
  }
  walk();
}

void BagScan::damaged(std::uint64_t at, const std::string& what, const std::string& skipped) {
  damage_.push_back({at, what, skipped});
}

void BagScan::walk() {
  std::optional<std::uint64_t> index_pos;
  for (std::uint64_t at = kBagVersionLine.size(); at < file_.size();) {
    BagRecord record;
    try {
      record = readBagRecord(file_, at, /*data_may_run_past=*/true);
    } catch (const BagRecordError& error) {
      damaged(at, error.reason(), "the last " + std::to_string(file_.size() - at) + " bytes skipped");
      break;
    }
    record_starts_.push_back(at);
    const std::uint64_t left = file_.size() - record.data;
    bool to_the_end = false;  // a chunk whose data is the rest of the file
    try {
      if (record.op() == kBagChunk) {
        // A stopped `rosbag record` leaves its last chunk's sizes 0, its records after the header.
        const bool unterminated = record.data_length == 0 && bagNumber(file_, record, "size") == 0;
        to_the_end = unterminated || record.data_length > left;
        chunk_starts_.push_back(at);
        readChunk(record, !to_the_end, to_the_end ? left : record.data_length);
        if (to_the_end) break;
      } else if (record.data_length > left) {
        damaged(at, "byte " + std::to_string(at) + ": record data of " + std::to_string(record.data_length) +
                        " bytes runs past its end",
                "the last " + std::to_string(file_.size() - at) + " bytes skipped");
        break;
      } else if (record.op() == kBagHeader) {
        index_pos = bagNumber(file_, record, "index_pos");
      } else if (record.op() == kBagConnection) {
        addConnection(file_, record);
      }
    } catch (const BagRecordError& error) {  // the walk goes on after a whole record
      const std::uint64_t skipped = to_the_end ? left : std::min(record.data_length, left);
      damaged(at, error.reason(), "its " + std::to_string(skipped) + " bytes of data skipped");
      if (to_the_end) break;
    }
    try {
      if (record.op() == kBagIndex) checkIndexEntries(record);
      if (record.op() == kBagChunkInfo) checkChunkInfo(record);
    } catch (const BagRecordError& error) {  // the index only: no message is lost
      if (index_mismatch_.empty()) index_mismatch_ = error.reason();
    }
    at = record.end();
  }
  checkIndex(index_pos);
}

void BagScan::readChunk(const BagRecord& record, bool whole, std::uint64_t available) {
  chunks_.push_back({record, available, whole});
  bool ended = true;
  ChunkBytes records(file_, record.at, chunkRecords(chunks_.back(), ended));  // throws for a chunk that gives none
  last_chunk_records_.clear();
  std::uint64_t at = 0;
  std::string stopped;  // why its records end before its bytes do
  while (at < records.size()) {
    try {
      const BagRecord inner = readBagRecord(records, at);
      if (inner.op() == kBagConnection) addConnection(records, inner);
      if (inner.op() == kBagMessage) {
        const std::string& time = bagField(records, inner, "time");
        if (time.size() != 8) records.fail(at, "its 'time' field is not 8 bytes");
        const double time_s = static_cast<double>(littleEndian(time.substr(0, 4))) +
                              static_cast<double>(littleEndian(time.substr(4, 4))) * 1e-9;  // as ros::Time::toSec
        messages_.push_back({static_cast<std::uint32_t>(bagNumber(records, inner, "conn")), time_s, chunks_.size() - 1,
                             inner.data, inner.data_length});
      }
      last_chunk_records_.push_back(at);
      at = inner.end();
    } catch (const BagRecordError& error) {
      stopped = error.reason();
      break;
    }
  }
  if (whole) {
    if (!stopped.empty()) damaged(record.at, stopped, "the chunk's records from there skipped");
    return;
  }
  const std::string where = "byte " + std::to_string(record.at) + ": ";
  const std::string what =
      record.data_length == 0
          ? where + "a chunk left unterminated (its sizes 0, as a stopped `rosbag record` leaves it)"
          : where + "the file ends " + std::to_string(available) + " bytes into the chunk's " +
                std::to_string(record.data_length) + " bytes of data (cut short)";
  if (bagField(file_, record, "compression") == "none") {
    // A cut chunk lost what its size says; an unterminated one, only a record the file ends in.
    const std::uint64_t read_to = record.data + at;  // the end of its last whole record
    if (read_to < file_.size() || record.data_length > 0) {
      damaged(record.at, what,
              "its records read to byte " + std::to_string(read_to) +
                  (read_to < file_.size() ? ", the last " + std::to_string(file_.size() - read_to) + " bytes skipped"
                                          : ", where the file ends"));
    }
  } else if (!ended || at < records.size()) {
    damaged(record.at, what, "the " + std::to_string(at) + " bytes of whole records that decompress from it read, the rest skipped");
  }
}

std::string BagScan::chunkRecords(const Chunk& chunk, bool& ended) {
  ended = true;
  if (chunk.whole) return uncompressedChunk(file_, chunk.record);
  const std::uint64_t size = bagChunkSize(file_, chunk.record);
  const std::string data = file_.read(chunk.record.data, std::min(chunk.available, kMaxBagChunk));
  return decompressAvailable(file_, chunk.record, data, size > 0 ? size : kMaxBagChunk, ended);
}

void BagScan::addConnection(BagBytes& source, const BagRecord& record) {
  const auto id = static_cast<std::uint32_t>(bagNumber(source, record, "conn"));
  const std::string& topic = bagField(source, record, "topic");
  const auto header = bagFields(source, record.at, source.read(record.data, record.data_length));
  const auto type = header.find("type");
  if (type == header.end()) source.fail(record.at, "a connection header lacks its 'type' field");
  for (const BagConnection& known : connections_) {
    if (known.id == id) return;  // the connection is recorded again in every chunk that uses it
  }
  const auto definition = header.find("message_definition");
  connections_.push_back({id, topic, type->second, definition != header.end() ? definition->second : std::string()});
}

void BagScan::checkIndexEntries(const BagRecord& record) {
  if (bagNumber(file_, record, "ver") != 1) file_.fail(record.at, "an index of a version other than 1");
  const std::uint64_t count = bagNumber(file_, record, "count");
  if (count > record.data_length / kIndexEntry) file_.fail(record.at, "an index holds fewer entries than it declares");
  indexed_.emplace_back(record.at, bagNumber(file_, record, "conn"));
  const std::string entries = file_.read(record.data, kIndexEntry * count);
  for (std::uint64_t entry = 0; entry < count; ++entry) {
    const std::uint64_t offset = littleEndian(entries.substr(entry * kIndexEntry + 8, 4));
    if (!std::binary_search(last_chunk_records_.begin(), last_chunk_records_.end(), offset)) {
      file_.fail(record.at, "an index entry points at byte " + std::to_string(offset) + " of its chunk, where no record starts");
    }
  }
}

void BagScan::checkChunkInfo(const BagRecord& record) {
  const std::uint64_t count = bagNumber(file_, record, "count");
  if (count > record.data_length / 8) file_.fail(record.at, "a chunk info holds fewer entries than it declares");
  chunk_infos_.emplace_back(record.at, bagNumber(file_, record, "chunk_pos"));
  const std::string entries = file_.read(record.data, 8 * count);  // a uint32 connection, a uint32 count
  for (std::uint64_t entry = 0; entry < count; ++entry) indexed_.emplace_back(record.at, littleEndian(entries.substr(entry * 8, 4)));
}

void BagScan::checkIndex(const std::optional<std::uint64_t>& index_pos) {
  const auto starts = [](const std::vector<std::uint64_t>& places, std::uint64_t at) {
    return std::binary_search(places.begin(), places.end(), at);
  };
  if (!index_pos) {
    index_problem_ = "has no bag header record giving its index position";
  } else if (*index_pos == 0) {
    index_problem_ = "is unindexed (its header's index position is 0, as a stopped `rosbag record` leaves it)";
  } else if (*index_pos >= file_.size()) {
    index_problem_ = "has its index at byte " + std::to_string(*index_pos) + ", past the end of the file (" +
                     std::to_string(file_.size()) + " bytes)";
  } else if (!damage_.empty()) {
    index_problem_ = "is damaged at byte " + std::to_string(damage_.front().at);
  } else if (!starts(record_starts_, *index_pos)) {
    index_problem_ = "has its index position " + std::to_string(*index_pos) + " where no record starts";
  } else if (!index_mismatch_.empty()) {
    index_problem_ = "has an index that does not match its records (" + index_mismatch_ + ")";
  }
  if (!index_problem_.empty()) return;
  for (const auto& [info, chunk] : chunk_infos_) {
    if (!starts(chunk_starts_, chunk)) {
      index_problem_ = "has an index that does not match its records (byte " + std::to_string(info) +
                       ": a chunk info points at byte " + std::to_string(chunk) + ", where no chunk starts)";
      return;
    }
  }
  for (const auto& [index, connection] : indexed_) {
    const std::uint64_t id = connection;  // a structured binding is not captured (clang 14)
    const bool defined =
        std::any_of(connections_.begin(), connections_.end(), [&](const BagConnection& c) { return c.id == id; });
    if (!defined) {
      index_problem_ = "has an index that does not match its records (byte " + std::to_string(index) +
                       ": an index or chunk info names connection " + std::to_string(connection) +
                       ", which the bag never defines)";
      return;
    }
  }
}

void BagScan::read(const BagMessage& message, std::vector<std::uint8_t>& out) {
  if (loaded_ != message.chunk) {
    loaded_ = SIZE_MAX;
    bool ended = true;
    loaded_records_ = chunkRecords(chunks_.at(message.chunk), ended);
    loaded_ = message.chunk;
  }
  if (message.size > loaded_records_.size() || message.data > loaded_records_.size() - message.size) {
    file_.fail(chunks_[message.chunk].record.at, "the chunk no longer holds the records it held when walked");
  }
  const auto begin = loaded_records_.begin() + static_cast<std::ptrdiff_t>(message.data);
  out.assign(begin, begin + static_cast<std::ptrdiff_t>(message.size));
}

}  // namespace sonarmap::detail
