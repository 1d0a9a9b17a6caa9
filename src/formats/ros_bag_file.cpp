/// @file ros_bag_file.cpp
/// A ROS 1 bag opened for reading (see ros_bag_file.hpp).

#include "ros_bag_file.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/serialization.h>

#include "ros_bag_check.hpp"

namespace sonarmap::detail {

void failBag(const std::string& path, const std::string& what) { throw FileError("'" + path + "': ROS bag: " + what); }

RosBagFile::RosBagFile(const std::string& path) : path_(path) {
  checkBagRecords(path);
  bag_ = std::make_unique<rosbag::Bag>(path, rosbag::bagmode::Read);
  rosbag::View everything(*bag_);
  for (const rosbag::ConnectionInfo* connection : everything.getConnections()) {
    bool known = false;
    for (const RosBagTopic& topic : topics_) known = known || topic.topic == connection->topic;
    if (known) continue;  // a topic recorded by several publishers: one connection's definition serves
    rosbag::View view(*bag_, rosbag::TopicQuery(connection->topic));
    RosBagTopic topic;
    topic.topic = connection->topic;
    topic.type = connection->datatype;
    topic.messages = view.size();
    if (topic.messages > 0) {
      topic.first_s = view.getBeginTime().toSec();
      topic.last_s = view.getEndTime().toSec();
    }
    topics_.push_back(topic);
    definitions_.push_back(connection->msg_def);
  }
}

RosBagFile::~RosBagFile() = default;

const std::string& RosBagFile::definition(const RosBagTopic& topic) const {
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].topic == topic.topic) return definitions_[i];
  }
  fail("no topic " + topic.topic);
}

void RosBagFile::fail(const std::string& what) const { failBag(path_, what); }

std::string RosBagFile::listing() const {
  std::string out;
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    out += (out.empty() ? "" : ", ") + topics_[i].topic + " (" + topics_[i].type +
           (definitions_[i].empty() ? ", no message definition)" : ")");
  }
  return out.empty() ? "none" : out;
}

RosSkipped RosBagFile::forEachMessage(const std::string& topic, const RosSchema& schema,
                                      const std::function<void(const RosValue&, double)>& use) {
  RosSkipped skipped;
  std::vector<std::uint8_t> bytes;
  std::size_t index = 0;
  for (const rosbag::MessageInstance& message : rosbag::View(*bag_, rosbag::TopicQuery(topic))) {
    ++index;
    try {
      bytes.resize(message.size());
      ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
      message.write(stream);
      use(decodeRosMessage(schema, bytes), message.getTime().toSec());
    } catch (const Error& error) {
      ++skipped.count;
      skipped.reasons.push_back("message " + std::to_string(index) + " of " + topic + ": " + error.what());
    }
  }
  return skipped;
}

}  // namespace sonarmap::detail
