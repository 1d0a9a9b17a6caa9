#pragma once
/// @file ros_bag_file.hpp
/// Private to formats: a ROS log opened for reading, shared by the sonar reader
/// (ros_bag_reader.cpp) and the navigation readers (ros_bag_navigation.cpp,
/// ros_inertial_navigation.cpp): a ROS 1 bag (walked first, ros_bag_scan.hpp, then opened with
/// Debian's rosbag_storage), an MCAP file (ROS 2's storage, mcap_file.hpp) or a rosbag2 SQLite log
/// (a folder of .db3 files or one of them, rosbag2_sqlite.hpp), told apart by their first bytes; a
/// rosbag2 folder holding one .mcap file is read as that file. Each topic's messages are decoded from the definition the file stores with it
/// (ros_message.hpp), ROS 1 serialized or CDR. A ROS 1 bag that rosbag_storage cannot read by its
/// index (cut short, unindexed, damaged: ros_bag_scan.hpp) is read from the walk of its records, up
/// to the damage.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "mcap_file.hpp"
#include "ros_message.hpp"
#include "rosbag2_sqlite.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

namespace rosbag {
class Bag;
}

namespace sonarmap::detail {

class BagScan;

/// What readers skipped: how many messages and why (one reason per message).
struct RosSkipped {
  std::size_t count = 0;
  std::vector<std::string> reasons;
};

class RosBagFile {
 public:
  /// Checks and opens the ROS 1 bag or MCAP file at `path`.
  /// @throws FileError naming the file for a file that is neither a readable ROS 1 bag (format
  ///         2.0) nor a readable MCAP file; for a ROS 1 bag damaged before its first whole message,
  ///         naming the damage.
  /// `msg_path`: `.msg` files for the types a rosbag2 SQLite log names without definitions
  /// (msgPathDefinition).
  explicit RosBagFile(const std::string& path, const std::string& msg_path = {});
  ~RosBagFile();
  RosBagFile(const RosBagFile&) = delete;
  RosBagFile& operator=(const RosBagFile&) = delete;

  /// Every topic, in the bag's connection order, with its message definition (empty when the
  /// connection stores none).
  const std::vector<RosBagTopic>& topics() const { return topics_; }
  const std::string& definition(const RosBagTopic& topic) const;
  /// The topic's message types parsed from its definition, in its encoding (ROS 1 or CDR).
  /// @throws Error when the definition does not parse.
  RosSchema schema(const RosBagTopic& topic) const;

  /// The messages of one topic in the log's time order, each decoded with its schema, read from
  /// the file as they are asked for (one chunk, or one SQLite row, at a time). The RosBagFile and
  /// the schema must outlive it.
  class MessageCursor {
   public:
    MessageCursor(MessageCursor&&) noexcept;
    ~MessageCursor();
    /// The next message that decodes and its record time (seconds since the epoch); false after
    /// the last. A message that does not decode is skipped and its reason kept ("message N of
    /// TOPIC: ...").
    /// @throws what the container's reader throws (rosbag_storage's errors; FileError).
    bool next(RosValue& message, double& record_time_s);
    /// Skips the message next() gave last, for `why` (a check of the caller's that it failed).
    void reject(const std::string& why);
    const RosSkipped& skipped() const { return skipped_; }

   private:
    friend class RosBagFile;
    struct Bag1;     ///< a ROS 1 bag's view and where it is
    struct Scanned;  ///< a scanned ROS 1 bag's messages of the topic and where the cursor is
    MessageCursor(const RosBagFile& file, std::string topic, const RosSchema& schema);
    void count(const std::string& why);

    std::string topic_;
    const RosSchema* schema_;
    std::size_t index_ = 0;  ///< messages read so far
    RosSkipped skipped_;
    std::optional<McapFile::Cursor> mcap_;
    std::optional<Rosbag2Sqlite::Cursor> sqlite_;
    std::unique_ptr<Bag1> bag_;
    std::unique_ptr<Scanned> scanned_;
    std::vector<std::uint8_t> bytes_;
  };
  /// A cursor over the messages of `topic`, decoded with `schema`.
  MessageCursor messages(const std::string& topic, const RosSchema& schema) const;

  /// Calls `use(message, record_time_s)` for each message of `topic`, in the bag's time order,
  /// each decoded with `schema`. A message that does not decode, or that `use` rejects by throwing
  /// Error, is skipped and its reason ("message N of TOPIC: ...") kept.
  RosSkipped forEachMessage(const std::string& topic, const RosSchema& schema,
                            const std::function<void(const RosValue&, double)>& use);

  /// Throws FileError("'PATH': ROS bag: WHAT") (or "MCAP:").
  [[noreturn]] void fail(const std::string& what) const;
  /// "TOPIC (TYPE), ..." of every topic (for errors that list them).
  std::string listing() const;
  /// What the reader had to do to read the file, for the log's notes ("the ROS bag is unindexed
  /// (...): read by scanning its chunks from the start"); the damage it read around is in each
  /// cursor's skips.
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  std::size_t indexOf(const std::string& topic) const;
  /// The topics of a ROS 1 bag read from the walk of its records (scan_).
  void openScanned();

  std::string path_;
  std::unique_ptr<rosbag::Bag> bag_;  ///< a ROS 1 bag's, read by its index
  std::unique_ptr<BagScan> scan_;     ///< a ROS 1 bag's, read from the walk of its records
  std::unique_ptr<McapFile> mcap_;    ///< an MCAP file's
  std::unique_ptr<Rosbag2Sqlite> sqlite_;  ///< a rosbag2 SQLite log's
  std::vector<RosBagTopic> topics_;
  std::vector<std::string> definitions_;
  std::vector<RosEncoding> encodings_;
  std::vector<std::vector<std::uint16_t>> channels_;  ///< an MCAP topic's channels
  std::vector<std::vector<std::uint32_t>> connection_ids_;  ///< a scanned bag topic's connections
  std::vector<std::string> notes_;
};

/// A chain of a log's static transforms (/tf_static, tf2_msgs/TFMessage): the pose of frame `to`
/// in frame `from` (both without a leading '/'), and the frames it passes, "from -> ... -> to".
struct StaticTransform {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::string chain;
};

/// The chain of the bag's /tf_static transforms (a transform given twice: the last) from `from` to
/// `to`, found breadth-first both ways; nullopt when either is empty or none joins them (a message
/// that does not decode is skipped). Implemented in ros_bag_mounting.cpp.
std::optional<StaticTransform> staticTransform(RosBagFile& bag, const std::string& from, const std::string& to);

/// Runs `read` and turns what rosbag_storage, boost and the decoder throw into FileError naming
/// `path` ("'PATH': ROS bag: ..."); FileError passes through.
template <class Read>
auto withBagErrors(const std::string& path, Read&& read) -> decltype(read());

[[noreturn]] void failBag(const std::string& path, const std::string& what);

}  // namespace sonarmap::detail

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
template <class Read>
auto withBagErrors(const std::string& path, Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& error) {  // sonarmap's Error, rosbag's BagException and its kin, boost's
    failBag(path, error.what());
  }
}
}  // namespace sonarmap::detail
