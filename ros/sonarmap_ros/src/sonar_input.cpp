/// @file sonar_input.cpp
/// The sonar topic of any type (sonar_input.hpp).

#include "sonar_input.hpp"

#include <sstream>

#include <ros/console.h>

namespace sonarmap_ros {
namespace {

/// Whether a message definition's first field is a std_msgs/Header (its seq the first 4 bytes).
bool firstFieldIsHeader(const std::string& definition) {
  std::istringstream lines(definition);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string type;
    if (!(words >> type) || type.front() == '#') continue;
    return type == "Header" || type == "std_msgs/Header";
  }
  return false;
}

}  // namespace

SonarInput::SonarInput(ros::NodeHandle& node, std::string topic, Sink sink)
    : node_(node), topic_(std::move(topic)), sink_(std::move(sink)) {
  subscribe();
}

void SonarInput::subscribe() {
  subscriber_.shutdown();
  // A deep queue: a bag played fast delivers bursts while a sweep is integrated.
  subscriber_ = node_.subscribe(topic_, 100000, &SonarInput::receive, this);
  subscribed_wall_s_ = ros::WallTime::now().toSec();
}

void SonarInput::receive(const ros::MessageEvent<const topic_tools::ShapeShifter>& event) {
  const topic_tools::ShapeShifter& shape = *event.getConstMessage();
  const double now_wall_s = ros::WallTime::now().toSec();
  // When roscpp received it (under sim time, now): the queue delay is measured from there.
  const double receipt_wall_s = ros::Time::isSimTime() ? now_wall_s : event.getReceiptTime().toSec();
  bytes_.resize(shape.size());
  ros::serialization::OStream stream(bytes_.data(), static_cast<std::uint32_t>(bytes_.size()));
  shape.write(stream);
  ++messages_;
  last_message_wall_s_ = now_wall_s;
  refused_ = false;  // until the sink refuses this one too
  noteSequence(event.getPublisherName(), shape.getDataType(), shape.getMessageDefinition());
  sink_(event.getPublisherName(), shape.getDataType(), shape.getMessageDefinition(), bytes_,
        event.getReceiptTime().toSec(), receipt_wall_s);
}

void SonarInput::noteSequence(const std::string& publisher, const std::string& type, const std::string& definition) {
  auto known = type_has_header_.find(type);
  if (known == type_has_header_.end()) known = type_has_header_.emplace(type, firstFieldIsHeader(definition)).first;
  if (!known->second || bytes_.size() < 4) return;
  const std::uint32_t seq = static_cast<std::uint32_t>(bytes_[0]) | static_cast<std::uint32_t>(bytes_[1]) << 8 |
                            static_cast<std::uint32_t>(bytes_[2]) << 16 | static_cast<std::uint32_t>(bytes_[3]) << 24;
  const auto last = last_seq_.find(publisher);
  // a seq not after the last: the publisher started again (a new bag, a restarted driver)
  if (last != last_seq_.end() && seq > last->second + 1) lost_ += seq - last->second - 1;
  last_seq_[publisher] = seq;
  if (lost_ > lost_said_) {
    ROS_WARN_THROTTLE(10.0, "sonarmap: %zu messages on %s lost before the node so far (gaps in header.seq; %s "
                      "now at %u)", lost_, topic_.c_str(), publisher.c_str(), seq);
    lost_said_ = lost_;
  }
}

void SonarInput::refuse(const std::string& publisher, const std::string& type, const std::string& why) {
  ROS_WARN_THROTTLE(5.0, "sonarmap: %s publishes %s on %s, which is not a sonar's message (%s): listening again "
                    "for a publisher of a sonar type", publisher.c_str(), type.c_str(), topic_.c_str(), why.c_str());
  refused_ = true;
}

void SonarInput::poll(double now_wall_s) {
  // Every second until a sonar's message comes: the publisher refused may still be the first to
  // connect, and once it is gone the subscription it made keeps refusing the others.
  if (refused_ && now_wall_s - subscribed_wall_s_ >= 1.0) {
    last_seq_.clear();
    subscribe();
  }
  const double since = std::max(last_message_wall_s_, subscribed_wall_s_);
  if (messages_ == 0 && now_wall_s - since >= 10.0 && now_wall_s - silence_said_wall_s_ >= 30.0) {
    silence_said_wall_s_ = now_wall_s;
    ROS_WARN("sonarmap: no message on %s in %.0f s (%u publishers): is ~sonar_topic the driver's topic?",
             topic_.c_str(), now_wall_s - since, subscriber_.getNumPublishers());
  }
}

}  // namespace sonarmap_ros
