#pragma once
/// @file rosbag2_sqlite.hpp
/// Private to formats: a rosbag2 log in its SQLite storage (`ros2 bag record`'s default before ROS 2
/// Iron: a folder with metadata.yaml and `NAME_0.db3`, `NAME_1.db3`, ... files), read through
/// Debian's libsqlite3: the `topics` table (id, name, type, serialization_format), the `messages`
/// table (topic_id, timestamp in nanoseconds, CDR data), and, where rosbag2 wrote it (Iron and
/// later), the `message_definitions` table (topic_type, encoding, encoded_message_definition).
/// Without it, a topic's definition is a built-in one (ros2_definitions.hpp) or none.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sonarmap::detail {

/// Whether `path` is a folder holding `.db3` files, a `.db3` file, or an SQLite file ("SQLite
/// format 3\0").
bool looksLikeRosbag2Sqlite(const std::string& path);

class Rosbag2Sqlite {
 public:
  struct Topic {
    std::string name, type, serialization_format;
    std::string definition;  ///< ros2msg; empty when neither the log nor the built-in ones have it
    std::size_t messages = 0;
    double first_s = 0.0, last_s = 0.0;
  };

  /// Opens every `.db3` file of the folder `path` (in name order), or the one file `path`. A
  /// topic's definition: the log's own (Iron's message_definitions), else the `.msg` files under
  /// `msg_path` (msgPathDefinition; a type whose files are incomplete gets none), else a built-in.
  /// @throws FileError naming the file for one that is no rosbag2 SQLite database.
  explicit Rosbag2Sqlite(const std::string& path, const std::string& msg_path = {});

  const std::vector<Topic>& topics() const { return topics_; }

  /// The messages of one topic in time order (over every file, one file after another), stepped
  /// through by SQLite one row at a time. The Rosbag2Sqlite must outlive it.
  class Cursor {
   public:
    Cursor(const Rosbag2Sqlite& log, std::string topic);
    ~Cursor();
    Cursor(Cursor&&) noexcept;
    Cursor& operator=(Cursor&&) noexcept;
    /// The next message's CDR data and time (seconds); false after the last.
    /// @throws FileError naming the file when SQLite cannot read it.
    bool next(std::vector<std::uint8_t>& data, double& time_s);

   private:
    struct Query;  ///< one file's open database and its statement
    const Rosbag2Sqlite* log_;
    std::string topic_;
    std::size_t file_ = 0;  ///< the next file to open
    std::unique_ptr<Query> query_;
  };

  /// Calls `use(data, time_s)` for each message of `topic` in time order (over every file).
  void forEachMessage(const std::string& topic, const std::function<void(const std::vector<std::uint8_t>&, double)>& use) const;

 private:
  std::string path_;
  std::vector<std::string> files_;
  std::vector<Topic> topics_;
};

}  // namespace sonarmap::detail
