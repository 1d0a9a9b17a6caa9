#pragma once
/// @file sonar_input.hpp
/// The sonar topic as roscpp gives it, for any driver's message type (topic_tools::ShapeShifter):
/// each message's type, definition and serialized bytes handed on; a publisher whose type cannot be
/// read, refused and the topic listened to again, so that a later publisher of a sonar type is
/// taken; beams lost before the node counted from the gaps in header.seq; the topic's silence said.
/// C++17 (the ROS side).
///
/// Why listen again: roscpp's Subscription takes the md5 of the first publisher it connects to when
/// it was made with "*" (ShapeShifter's), and drops every later publisher of another md5 (ros_comm,
/// subscription.cpp headerReceived; the publisher then logs "wants topic … to have datatype/md5sum
/// … Dropping connection"). A new Subscription starts again from "*".

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <ros/subscriber.h>
#include <topic_tools/shape_shifter.h>

namespace sonarmap_ros {

class SonarInput {
 public:
  /// Receives one message: publisher, type, definition, bytes, receipt time (ROS, s) and wall receipt (s).
  using Sink = std::function<void(const std::string& publisher, const std::string& type, const std::string& definition,
                                  const std::vector<std::uint8_t>& bytes, double receipt_s, double receipt_wall_s)>;
  SonarInput(ros::NodeHandle& node, std::string topic, Sink sink);

  /// The last message's publisher sent a type without a sonar beam's fields: said (throttled), and
  /// the topic listened to again every second (poll()) until a message is not refused.
  void refuse(const std::string& publisher, const std::string& type, const std::string& why);
  /// Each tick of the node (wall time `now_wall_s`): listens again after a refusal; says (throttled)
  /// when nothing has come on the topic for 10 s since the start or the last message.
  void poll(double now_wall_s);

  std::size_t messages() const { return messages_; }
  /// Messages lost before the node: the sum of the gaps in each publisher's header.seq.
  std::size_t lost() const { return lost_; }
  const std::string& topic() const { return topic_; }

 private:
  void receive(const ros::MessageEvent<const topic_tools::ShapeShifter>& event);
  void subscribe();
  /// Counts a gap in `publisher`'s header.seq (the message's first field a Header: its first 4 bytes).
  void noteSequence(const std::string& publisher, const std::string& type, const std::string& definition);

  ros::NodeHandle node_;
  std::string topic_;
  Sink sink_;
  ros::Subscriber subscriber_;
  std::vector<std::uint8_t> bytes_;
  std::size_t messages_ = 0, lost_ = 0, lost_said_ = 0;
  std::map<std::string, std::uint32_t> last_seq_;   ///< by publisher
  std::map<std::string, bool> type_has_header_;     ///< by type: the first field is a std_msgs/Header
  bool refused_ = false;
  double subscribed_wall_s_ = 0.0, last_message_wall_s_ = 0.0, silence_said_wall_s_ = 0.0;
};

}  // namespace sonarmap_ros
