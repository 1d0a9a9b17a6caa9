#pragma once
/// @file ros_bag_file.hpp
/// Private to formats: a ROS 1 bag opened for reading, shared by the sonar reader
/// (ros_bag_reader.cpp) and the navigation reader (ros_bag_navigation.cpp). The file is checked
/// first (ros_bag_check.hpp), then opened with Debian's rosbag_storage; each topic's messages are
/// decoded from the definition its connection stores (ros_message.hpp).

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ros_message.hpp"
#include "sonarmap/formats/ros_bag_navigation.hpp"

namespace rosbag {
class Bag;
}

namespace sonarmap::detail {

/// What readers skipped: how many messages and why (one reason per message).
struct RosSkipped {
  std::size_t count = 0;
  std::vector<std::string> reasons;
};

class RosBagFile {
 public:
  /// Checks and opens the bag at `path`.
  /// @throws FileError naming the file for a file that is no readable ROS 1 bag (format 2.0).
  explicit RosBagFile(const std::string& path);
  ~RosBagFile();
  RosBagFile(const RosBagFile&) = delete;
  RosBagFile& operator=(const RosBagFile&) = delete;

  /// Every topic, in the bag's connection order, with its message definition (empty when the
  /// connection stores none).
  const std::vector<RosBagTopic>& topics() const { return topics_; }
  const std::string& definition(const RosBagTopic& topic) const;

  /// Calls `use(message, record_time_s)` for each message of `topic`, in the bag's time order,
  /// each decoded with `schema`. A message that does not decode, or that `use` rejects by throwing
  /// Error, is skipped and its reason ("message N of TOPIC: ...") kept.
  RosSkipped forEachMessage(const std::string& topic, const RosSchema& schema,
                            const std::function<void(const RosValue&, double)>& use);

  /// Throws FileError("'PATH': ROS bag: WHAT").
  [[noreturn]] void fail(const std::string& what) const;
  /// "TOPIC (TYPE), ..." of every topic (for errors that list them).
  std::string listing() const;

 private:
  std::string path_;
  std::unique_ptr<rosbag::Bag> bag_;
  std::vector<RosBagTopic> topics_;
  std::vector<std::string> definitions_;
};

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
