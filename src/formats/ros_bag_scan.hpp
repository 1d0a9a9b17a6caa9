#pragma once
/// @file ros_bag_scan.hpp
/// Private to formats: a ROS 1 bag walked record by record from its start, every length checked
/// (ros_bag_records.hpp), its chunks decompressed and their records listed, as `rosbag reindex`
/// reads a bag. Two uses:
///  - the check before Debian's rosbag_storage opens a bag: rosbag_storage trusts what the file
///    says (a header length of 2³² − 1 bytes is a 4 GiB allocation; it reads a message at whatever
///    offset of its chunk an index entry gives), so it reads only a bag that is whole and whose
///    index matches its records (indexProblem() is empty);
///  - the reading of any other bag: a bag cut short (a full disk, a pulled cable), one left
///    unindexed by a `rosbag record` that was stopped (the header's index position 0, no index or
///    chunk info records, the last chunk's sizes left 0), or one whose index or a chunk is damaged.
///    Its messages are read from the scan, up to the damage: the whole records of a chunk the file
///    ends in, or of an unterminated one, are read (a compressed one as far as it decompresses).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ros_bag_records.hpp"

namespace sonarmap::detail {

/// A connection record: a topic, its type and the message definition it stores (may be empty).
struct BagConnection {
  std::uint32_t id = 0;
  std::string topic, type, definition;
};

/// A message record found by the walk: its connection, record time, and where its data lies in
/// the records of its chunk (BagScan's chunk `chunk`).
struct BagMessage {
  std::uint32_t connection = 0;
  double time_s = 0.0;
  std::size_t chunk = 0;
  std::uint64_t data = 0, size = 0;
};

/// What the walk could not read past: the byte of the file, what is wrong there ("byte N: ...")
/// and what was skipped for it.
struct BagDamage {
  std::uint64_t at = 0;
  std::string what, skipped;
  std::string line() const { return what + "; " + skipped; }
};

class BagScan {
 public:
  /// Walks the bag at `path` (see the file's comment). A record that does not fit ends the walk
  /// (the rest of the file is skipped); damage inside a whole chunk skips the rest of that chunk.
  /// Each is one BagDamage. A compressed chunk is decompressed here and again when its messages
  /// are read.
  /// @throws FileError when the file cannot be opened or its first line is not "#ROSBAG V2.0".
  explicit BagScan(const std::string& path);

  /// Why rosbag_storage cannot read the bag by its index ("unindexed (...)", "its index ... lies
  /// past the end of the file", "damaged at byte N", "its index does not match its records: ...");
  /// empty when it can: the bag is whole and every index entry and chunk info points where a
  /// record or chunk starts, every connection they name defined.
  const std::string& indexProblem() const { return index_problem_; }
  const std::vector<BagDamage>& damage() const { return damage_; }
  /// The connections, each once, in the order the walk met them.
  const std::vector<BagConnection>& connections() const { return connections_; }
  /// Every message record of a whole record, in file order.
  const std::vector<BagMessage>& messages() const { return messages_; }
  /// The serialized message of `message` (one of messages()), into `out`.
  /// @throws FileError when the file can no longer be read as it was walked.
  void read(const BagMessage& message, std::vector<std::uint8_t>& out);

 private:
  /// A chunk of the walk: its record, and how many bytes of its data the file holds.
  struct Chunk {
    BagRecord record;
    std::uint64_t available = 0;
    bool whole = true;  ///< its data fits in the file and its sizes were written
  };
  void walk();
  void readChunk(const BagRecord& record, bool whole, std::uint64_t available);
  std::string chunkRecords(const Chunk& chunk, bool& ended);
  void addConnection(BagBytes& source, const BagRecord& record);
  void checkIndexEntries(const BagRecord& record);
  void checkChunkInfo(const BagRecord& record);
  void checkIndex(const std::optional<std::uint64_t>& index_pos);
  void damaged(std::uint64_t at, const std::string& what, const std::string& skipped);

  BagFile file_;
  std::string index_problem_;
  std::vector<BagDamage> damage_;
  std::vector<BagConnection> connections_;
  std::vector<BagMessage> messages_;
  std::vector<Chunk> chunks_;
  std::size_t loaded_ = SIZE_MAX;  ///< the chunk whose records `loaded_records_` holds
  std::string loaded_records_;
  // What the index is checked against: record and chunk starts, the record starts inside the chunk
  // the next index records describe, the chunk infos' chunks, the connections indexes name.
  std::vector<std::uint64_t> record_starts_, chunk_starts_, last_chunk_records_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunk_infos_;  ///< the info's place, its chunk's
  std::vector<std::pair<std::uint64_t, std::uint64_t>> indexed_;      ///< an index's or info's place, a connection
  std::string index_mismatch_;  ///< the first index or chunk info record that does not match the records
};

}  // namespace sonarmap::detail
