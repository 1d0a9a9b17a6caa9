/// @file ros_bag_file.cpp
/// A ROS 1 bag opened for reading (see ros_bag_file.hpp).

#include "ros_bag_file.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <ros/serialization.h>

#include "ros_bag_scan.hpp"

#include <algorithm>
#include <filesystem>

namespace sonarmap::detail {

void failBag(const std::string& path, const std::string& what) { throw FileError("'" + path + "': ROS bag: " + what); }

namespace {

/// The file to read for `path`: a rosbag2 folder's only .mcap file, else `path` itself.
std::string mcapOfFolder(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_directory(path, error)) return path;
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(path, error)) {
    if (entry.path().extension() == ".mcap") found.push_back(entry.path().string());
  }
  if (found.size() != 1) {
    failBag(path, found.empty() ? "the folder holds no .db3 or .mcap file" : "the folder holds several .mcap files: give each one");
  }
  return found.front();
}

}  // namespace

RosBagFile::RosBagFile(const std::string& path, const std::string& msg_path) : path_(path) {
  if (looksLikeRosbag2Sqlite(path)) {
    sqlite_ = std::make_unique<Rosbag2Sqlite>(path, msg_path);
    for (const Rosbag2Sqlite::Topic& t : sqlite_->topics()) {
      topics_.push_back(RosBagTopic{t.name, t.type, t.messages, t.first_s, t.last_s});
      definitions_.push_back(t.serialization_format == "cdr" ? t.definition : std::string());
      encodings_.push_back(RosEncoding::kCdr);
      channels_.emplace_back();
    }
    return;
  }
  const std::string file = mcapOfFolder(path);
  if (startsLikeMcap(file)) {
    // MCAP: a topic's channels grouped; ROS 2 messages (a ros2msg schema, cdr) and ROS 1 ones
    // (ros1msg, ros1) are read; others (protobuf, JSON) are listed without a definition.
    mcap_ = std::make_unique<McapFile>(file);
    for (const auto& [id, channel] : mcap_->channels()) {
      const auto schema = mcap_->schemas().find(channel.schema_id);
      std::size_t index = topics_.size();
      for (std::size_t i = 0; i < topics_.size(); ++i) {
        if (topics_[i].topic == channel.topic) index = i;
      }
      if (index == topics_.size()) {
        RosBagTopic topic;
        topic.topic = channel.topic;
        topic.type = schema != mcap_->schemas().end() ? schema->second.name : std::string("(no schema)");
        topics_.push_back(topic);
        const bool ros2 = schema != mcap_->schemas().end() && schema->second.encoding == "ros2msg" && channel.message_encoding == "cdr";
        const bool ros1 = schema != mcap_->schemas().end() && schema->second.encoding == "ros1msg" && channel.message_encoding == "ros1";
        definitions_.push_back(ros1 || ros2 ? schema->second.data : std::string());
        encodings_.push_back(ros2 ? RosEncoding::kCdr : RosEncoding::kRos1);
        channels_.emplace_back();
      }
      RosBagTopic& topic = topics_[index];
      if (channel.messages > 0) {
        topic.first_s = topic.messages == 0 ? channel.first_s : std::min(topic.first_s, channel.first_s);
        topic.last_s = topic.messages == 0 ? channel.last_s : std::max(topic.last_s, channel.last_s);
      }
      topic.messages += channel.messages;
      channels_[index].push_back(id);
    }
    return;
  }
  auto scan = std::make_unique<BagScan>(path);
  if (!scan->indexProblem().empty()) {
    scan_ = std::move(scan);
    openScanned();
    return;
  }
  scan.reset();  // whole and indexed: rosbag_storage reads it
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
    encodings_.push_back(RosEncoding::kRos1);
    channels_.emplace_back();
  }
}

void RosBagFile::openScanned() {
  if (scan_->messages().empty() && !scan_->damage().empty()) {
    failBag(path_, scan_->damage().front().what + " (no whole message before it)");
  }
  notes_.push_back("the ROS bag " + scan_->indexProblem() + ": read by scanning its chunks from the start");
  for (const BagConnection& connection : scan_->connections()) {
    const auto known = std::find_if(topics_.begin(), topics_.end(), [&](const RosBagTopic& t) { return t.topic == connection.topic; });
    if (known != topics_.end()) {  // a topic recorded by several publishers: one connection's definition serves
      connection_ids_[static_cast<std::size_t>(known - topics_.begin())].push_back(connection.id);
      continue;
    }
    topics_.push_back(RosBagTopic{connection.topic, connection.type, 0, 0.0, 0.0});
    definitions_.push_back(connection.definition);
    encodings_.push_back(RosEncoding::kRos1);
    channels_.emplace_back();
    connection_ids_.push_back({connection.id});
  }
  for (const BagMessage& message : scan_->messages()) {
    for (std::size_t i = 0; i < topics_.size(); ++i) {
      const std::vector<std::uint32_t>& ids = connection_ids_[i];
      if (std::find(ids.begin(), ids.end(), message.connection) == ids.end()) continue;
      RosBagTopic& topic = topics_[i];
      topic.first_s = topic.messages == 0 ? message.time_s : std::min(topic.first_s, message.time_s);
      topic.last_s = topic.messages == 0 ? message.time_s : std::max(topic.last_s, message.time_s);
      ++topic.messages;
    }
  }
}

RosBagFile::~RosBagFile() = default;

std::size_t RosBagFile::indexOf(const std::string& topic) const {
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].topic == topic) return i;
  }
  fail("no topic " + topic);
}

const std::string& RosBagFile::definition(const RosBagTopic& topic) const { return definitions_[indexOf(topic.topic)]; }

RosSchema RosBagFile::schema(const RosBagTopic& topic) const {
  const std::size_t i = indexOf(topic.topic);
  return RosSchema(topic.type, definitions_[i], encodings_[i]);
}

void RosBagFile::fail(const std::string& what) const {
  if (mcap_) throw FileError("'" + path_ + "': MCAP: " + what);
  if (sqlite_) throw FileError("'" + path_ + "': rosbag2: " + what);
  failBag(path_, what);
}

std::string RosBagFile::listing() const {
  std::string out;
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    out += (out.empty() ? "" : ", ") + topics_[i].topic + " (" + topics_[i].type +
           (definitions_[i].empty() ? ", no message definition)" : ")");
  }
  return out.empty() ? "none" : out;
}

struct RosBagFile::MessageCursor::Bag1 {
  Bag1(rosbag::Bag& bag, const std::string& topic) : view(bag, rosbag::TopicQuery(topic)), at(view.begin()) {}
  rosbag::View view;
  rosbag::View::iterator at;
};

struct RosBagFile::MessageCursor::Scanned {
  /// The messages of the connections `ids` in time order (the order of the file for equal times).
  Scanned(BagScan& bag, const std::vector<std::uint32_t>& ids) : scan(bag) {
    const std::vector<BagMessage>& messages = scan.messages();
    for (std::size_t i = 0; i < messages.size(); ++i) {
      if (std::find(ids.begin(), ids.end(), messages[i].connection) != ids.end()) order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return messages[a].time_s < messages[b].time_s; });
  }
  BagScan& scan;
  std::vector<std::size_t> order;
  std::size_t next = 0;
};

RosBagFile::MessageCursor::MessageCursor(const RosBagFile& file, std::string topic, const RosSchema& schema)
    : topic_(std::move(topic)), schema_(&schema) {
  if (file.mcap_) {
    mcap_.emplace(*file.mcap_, file.channels_[file.indexOf(topic_)]);
  } else if (file.scan_) {
    scanned_ = std::make_unique<Scanned>(*file.scan_, file.connection_ids_[file.indexOf(topic_)]);
    for (const BagDamage& damage : file.scan_->damage()) {  // what the bag lost, in every topic's skips
      ++skipped_.count;
      skipped_.reasons.push_back(damage.line());
    }
  } else if (file.sqlite_) {
    sqlite_.emplace(*file.sqlite_, topic_);
  } else {
    bag_ = std::make_unique<Bag1>(*file.bag_, topic_);
  }
}
RosBagFile::MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;
RosBagFile::MessageCursor::~MessageCursor() = default;

void RosBagFile::MessageCursor::count(const std::string& why) {
  ++skipped_.count;
  skipped_.reasons.push_back("message " + std::to_string(index_) + " of " + topic_ + ": " + why);
}

void RosBagFile::MessageCursor::reject(const std::string& why) { count(why); }

bool RosBagFile::MessageCursor::next(RosValue& message, double& record_time_s) {
  for (;;) {
    if (mcap_) {
      if (!mcap_->next(bytes_, record_time_s)) return false;
    } else if (sqlite_) {
      if (!sqlite_->next(bytes_, record_time_s)) return false;
    } else if (scanned_) {
      if (scanned_->next == scanned_->order.size()) return false;
      const BagMessage& found = scanned_->scan.messages()[scanned_->order[scanned_->next++]];
      scanned_->scan.read(found, bytes_);
      record_time_s = found.time_s;
    } else {
      if (bag_->at == bag_->view.end()) return false;
      const rosbag::MessageInstance& instance = *bag_->at;  // valid until the iterator moves on
      bytes_.resize(instance.size());
      ros::serialization::OStream stream(bytes_.data(), static_cast<std::uint32_t>(bytes_.size()));
      instance.write(stream);
      record_time_s = instance.getTime().toSec();
      ++bag_->at;
    }
    ++index_;
    try {
      message = decodeRosMessage(*schema_, bytes_);
      return true;
    } catch (const Error& error) {
      count(error.what());
    }
  }
}

RosBagFile::MessageCursor RosBagFile::messages(const std::string& topic, const RosSchema& schema) const {
  return MessageCursor(*this, topic, schema);
}

RosSkipped RosBagFile::forEachMessage(const std::string& topic, const RosSchema& schema,
                                      const std::function<void(const RosValue&, double)>& use) {
  MessageCursor cursor = messages(topic, schema);
  RosValue message;
  double time_s = 0.0;
  while (cursor.next(message, time_s)) {
    try {
      use(message, time_s);
    } catch (const Error& error) {
      cursor.reject(error.what());
    }
  }
  return cursor.skipped();
}

}  // namespace sonarmap::detail
