#pragma once
/// @file octomap_message.hpp
/// octomap_msgs/Octomap without the octomap_msgs package (Debian has none): a struct of the
/// message's fields and roscpp's message traits for it (DataType, MD5Sum, Definition, Serializer:
/// wiki.ros.org/roscpp/Overview/MessagesSerializationAndAdaptingTypes), so that a publisher of it
/// announces the type, md5 and definition subscribers check (RViz's octomap plugin, octomap_server's
/// tools, rospy with the real package). The definition is octomap_msgs' msg/Octomap.msg
/// (OctoMap/octomap_msgs, melodic-devel) with std_msgs/Header as genmsg joins them; the md5 is
/// genmsg's (compute_md5) of that text, checked by tests/ros/test_sonarmap_ros.py with
/// /usr/bin/python3's genmsg. The same for the service octomap_msgs/BoundingBoxQuery (srv/
/// BoundingBoxQuery.srv: a request of two geometry_msgs/Point, an empty response), octomap_server's
/// ~clear_bbx, and octomap_msgs/GetOctomap (srv/GetOctomap.srv: an empty request, a response of one
/// octomap_msgs/Octomap), octomap_server's services octomap_binary and octomap_full, which
/// octomap_saver calls; its md5 is checked by tests/ros/test_ros_octomap_server_interface.py.

#include <cstdint>
#include <string>
#include <vector>

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <geometry_msgs/Point.h>
#include <ros/service_traits.h>
#include <std_msgs/Header.h>

namespace sonarmap_ros {

/// octomap_msgs/Octomap: `data` is an OctoMap tree's writeBinaryData (binary) or writeData (full)
/// stream, the `.bt`/`.ot` file's bytes after its text header (octomap_msgs/conversions.h).
struct OctomapMessage {
  std_msgs::Header header;
  bool binary = true;
  std::string id = "OcTree";
  double resolution = 0.0;  ///< metres
  std::vector<std::int8_t> data;
};

/// octomap_msgs/BoundingBoxQuery's request: the box's corners, metres, in the map's frame.
struct BoundingBoxQueryRequest {
  geometry_msgs::Point min, max;
};
/// octomap_msgs/BoundingBoxQuery's response: empty.
struct BoundingBoxQueryResponse {};

/// octomap_msgs/GetOctomap's request: empty.
struct GetOctomapRequest {};
/// octomap_msgs/GetOctomap's response: the map.
struct GetOctomapResponse {
  OctomapMessage map;
};

}  // namespace sonarmap_ros

namespace sonarmap_ros::definitions {

inline constexpr char kOctomapMd5[] = "9a45536b45c5e409cd49f04bb2d9999f";
// a macro, so that GetOctomap's response definition can contain it (string literals join)
#define SONARMAP_ROS_OCTOMAP_DEFINITION \
    "# A 3D map in binary format, as Octree\n" \
    "Header header\n" \
    "\n" \
    "# Flag to denote a binary (only free/occupied) or full occupancy octree (.bt/.ot file)\n" \
    "bool binary\n" \
    "\n" \
    "# Class id of the contained octree \n" \
    "string id\n" \
    "\n" \
    "# Resolution (in m) of the smallest octree nodes\n" \
    "float64 resolution\n" \
    "\n" \
    "# binary serialization of octree, use conversions.h to read and write octrees\n" \
    "int8[] data\n" \
    "\n" \
    "================================================================================\n" \
    "MSG: std_msgs/Header\n" \
    "# Standard metadata for higher-level stamped data types.\n" \
    "# This is generally used to communicate timestamped data \n" \
    "# in a particular coordinate frame.\n" \
    "# \n" \
    "# sequence ID: consecutively increasing ID \n" \
    "uint32 seq\n" \
    "#Two-integer timestamp that is expressed as:\n" \
    "# * stamp.sec: seconds (stamp_secs) since epoch (in Python the variable is called 'secs')\n" \
    "# * stamp.nsec: nanoseconds since stamp_secs (in Python the variable is called 'nsecs')\n" \
    "# time-handling sugar is provided by the client library\n" \
    "time stamp\n" \
    "#Frame this data is associated with\n" \
    "string frame_id\n"
inline constexpr char kOctomap[] = SONARMAP_ROS_OCTOMAP_DEFINITION;

/// genmsg's md5 of the service: of the request's text and the empty response's, so the request's own too.
inline constexpr char kBoundingBoxQueryMd5[] = "93aa3d73b866f04880927745f4aab303";
inline constexpr char kBoundingBoxQueryRequest[] =
    "# Clear a region specified by a global axis-aligned bounding box in stored OctoMap\n"
    "\n"
    "# minimum corner point of axis-aligned bounding box in global frame\n"
    "geometry_msgs/Point min\n"
    "# maximum corner point of axis-aligned bounding box in global frame\n"
    "geometry_msgs/Point max\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Point\n"
    "# This contains the position of a point in free space\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n";

/// genmsg's md5 of GetOctomap.srv: of its empty request's text and its response's ("<Octomap's md5>
/// map"), which is the response's own md5 too; the request's own is the empty text's.
inline constexpr char kGetOctomapMd5[] = "be9d2869d24fe40d6bc21ac21f6bb2c5";
inline constexpr char kEmptyMd5[] = "d41d8cd98f00b204e9800998ecf8427e";
inline constexpr char kGetOctomapResponse[] =
    "octomap_msgs/Octomap map\n"
    "\n"
    "================================================================================\n"
    "MSG: octomap_msgs/Octomap\n" SONARMAP_ROS_OCTOMAP_DEFINITION;
inline constexpr char kBoundingBoxQueryType[] = "octomap_msgs/BoundingBoxQuery";
inline constexpr char kGetOctomapType[] = "octomap_msgs/GetOctomap";

}  // namespace sonarmap_ros::definitions

// roscpp's own macro for messages whose traits are written by hand (ros/message_traits.h).
ROS_IMPLEMENT_SIMPLE_TOPIC_TRAITS(sonarmap_ros::OctomapMessage, sonarmap_ros::definitions::kOctomapMd5,
                                  "octomap_msgs/Octomap", sonarmap_ros::definitions::kOctomap)
ROS_IMPLEMENT_SIMPLE_TOPIC_TRAITS(sonarmap_ros::BoundingBoxQueryRequest,
                                  sonarmap_ros::definitions::kBoundingBoxQueryMd5,
                                  "octomap_msgs/BoundingBoxQueryRequest",
                                  sonarmap_ros::definitions::kBoundingBoxQueryRequest)
ROS_IMPLEMENT_SIMPLE_TOPIC_TRAITS(sonarmap_ros::BoundingBoxQueryResponse, sonarmap_ros::definitions::kEmptyMd5,
                                  "octomap_msgs/BoundingBoxQueryResponse", "\n")
ROS_IMPLEMENT_SIMPLE_TOPIC_TRAITS(sonarmap_ros::GetOctomapRequest, sonarmap_ros::definitions::kEmptyMd5,
                                  "octomap_msgs/GetOctomapRequest", "# Get the map as a octomap\n")
ROS_IMPLEMENT_SIMPLE_TOPIC_TRAITS(sonarmap_ros::GetOctomapResponse, sonarmap_ros::definitions::kGetOctomapMd5,
                                  "octomap_msgs/GetOctomapResponse", sonarmap_ros::definitions::kGetOctomapResponse)

namespace ros {
template <> struct message_traits::HasHeader<sonarmap_ros::OctomapMessage> : message_traits::TrueType {};
}  // namespace ros

namespace ros::service_traits {

/// A service's md5 or type, which its request and response both carry (ros/service_traits.h).
template <const char* Text>
struct ServiceText {
  static const char* value() { return Text; }
  template <class Part>
  static const char* value(const Part&) {
    return Text;
  }
};
template <>
struct MD5Sum<sonarmap_ros::BoundingBoxQueryRequest>
    : ServiceText<sonarmap_ros::definitions::kBoundingBoxQueryMd5> {};
template <>
struct MD5Sum<sonarmap_ros::BoundingBoxQueryResponse>
    : ServiceText<sonarmap_ros::definitions::kBoundingBoxQueryMd5> {};
template <>
struct DataType<sonarmap_ros::BoundingBoxQueryRequest>
    : ServiceText<sonarmap_ros::definitions::kBoundingBoxQueryType> {};
template <>
struct DataType<sonarmap_ros::BoundingBoxQueryResponse>
    : ServiceText<sonarmap_ros::definitions::kBoundingBoxQueryType> {};
template <>
struct MD5Sum<sonarmap_ros::GetOctomapRequest>
    : ServiceText<sonarmap_ros::definitions::kGetOctomapMd5> {};
template <>
struct MD5Sum<sonarmap_ros::GetOctomapResponse>
    : ServiceText<sonarmap_ros::definitions::kGetOctomapMd5> {};
template <>
struct DataType<sonarmap_ros::GetOctomapRequest>
    : ServiceText<sonarmap_ros::definitions::kGetOctomapType> {};
template <>
struct DataType<sonarmap_ros::GetOctomapResponse>
    : ServiceText<sonarmap_ros::definitions::kGetOctomapType> {};

}  // namespace ros::service_traits

namespace ros::serialization {

template <>
struct Serializer<sonarmap_ros::OctomapMessage> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.header);
    stream.next(m.binary);
    stream.next(m.id);
    stream.next(m.resolution);
    stream.next(m.data);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

template <>
struct Serializer<sonarmap_ros::BoundingBoxQueryRequest> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.min);
    stream.next(m.max);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

template <>
struct Serializer<sonarmap_ros::BoundingBoxQueryResponse> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream&, T) {}
  ROS_DECLARE_ALLINONE_SERIALIZER
};

template <>
struct Serializer<sonarmap_ros::GetOctomapRequest> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream&, T) {}
  ROS_DECLARE_ALLINONE_SERIALIZER
};

template <>
struct Serializer<sonarmap_ros::GetOctomapResponse> {
  template <typename Stream, typename T>
  inline static void allInOne(Stream& stream, T m) {
    stream.next(m.map);
  }
  ROS_DECLARE_ALLINONE_SERIALIZER
};

}  // namespace ros::serialization
