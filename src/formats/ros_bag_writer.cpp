/// @file ros_bag_writer.cpp
/// A sonar log as a ROS 1 bag of micron_driver_ros/ScanLine messages (see ros_bag_writer.hpp).

#include "sonarmap/formats/ros_bag_writer.hpp"

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <vector>

#include <unistd.h>

#include <rosbag/bag.h>
#include <ros/message_traits.h>
#include <ros/serialization.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "ros_frames.hpp"

namespace sonarmap {

const char* const kScanLineDefinition =
    "Header header\n"
    "float32 angle\n"
    "float32 bin_distance_step\n"
    "micron_driver_ros/IntensityBin[] bins\n"
    "\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n"
    "\n"
    "================================================================================\n"
    "MSG: micron_driver_ros/IntensityBin\n"
    "float32 distance\n"
    "uint8 intensity\n";

const char* const kOdometryDefinition =
    "Header header\n"
    "string child_frame_id\n"
    "geometry_msgs/PoseWithCovariance pose\n"
    "geometry_msgs/TwistWithCovariance twist\n"
    "\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/PoseWithCovariance\n"
    "geometry_msgs/Pose pose\n"
    "float64[36] covariance\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Pose\n"
    "geometry_msgs/Point position\n"
    "geometry_msgs/Quaternion orientation\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Point\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Quaternion\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n"
    "float64 w\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/TwistWithCovariance\n"
    "geometry_msgs/Twist twist\n"
    "float64[36] covariance\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Twist\n"
    "geometry_msgs/Vector3 linear\n"
    "geometry_msgs/Vector3 angular\n"
    "\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Vector3\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n";

namespace {

constexpr const char* kRule = "================================================================================\n";
constexpr const char* kHeaderSection = "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n";
constexpr const char* kQuaternionSection = "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n";
constexpr const char* kVector3Section = "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";

/// ROS's definitions (without their comments) of the raw navigation sensors' messages.
const std::string kImuDefinition = std::string(
    "Header header\n"
    "geometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
    "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
    "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n\n") +
    kRule + kHeaderSection + "\n" + kRule + kQuaternionSection + "\n" + kRule + kVector3Section;
const std::string kTwistStampedDefinition = std::string("Header header\ngeometry_msgs/Twist twist\n\n") + kRule +
    kHeaderSection + "\n" + kRule + "MSG: geometry_msgs/Twist\ngeometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n\n" +
    kRule + kVector3Section;
const std::string kFluidPressureDefinition = std::string("Header header\nfloat64 fluid_pressure\nfloat64 variance\n\n") +
    kRule + kHeaderSection;

/// The message types written: name, MD5 sum (as ROS computes it from the definition; the ScanLine's
/// as the driver's bags record it, micron_pool_ros1.bag) and definition.
struct ScanLineType {
  static constexpr const char* kName = "micron_driver_ros/ScanLine";
  static constexpr const char* kMd5 = "6798122952303f12e50da3a7e7eed1f0";
  static const char* definition() { return kScanLineDefinition; }
};
struct OdometryType {
  static constexpr const char* kName = "nav_msgs/Odometry";
  static constexpr const char* kMd5 = "cd5e73d190d741a2f92e81eda573aca7";
  static const char* definition() { return kOdometryDefinition; }
};

struct ImuType {
  static constexpr const char* kName = "sensor_msgs/Imu";
  static constexpr const char* kMd5 = "6a62c6daae103f4ff57a132d6f95cec2";
  static const char* definition() { return kImuDefinition.c_str(); }
};
struct TwistStampedType {
  static constexpr const char* kName = "geometry_msgs/TwistStamped";
  static constexpr const char* kMd5 = "98d34b0043a2093cf9d9345ab6eef12e";
  static const char* definition() { return kTwistStampedDefinition.c_str(); }
};
const std::string kTfMessageDefinition = std::string("geometry_msgs/TransformStamped[] transforms\n\n") + kRule +
    "MSG: geometry_msgs/TransformStamped\nHeader header\nstring child_frame_id\nTransform transform\n\n" + kRule +
    kHeaderSection + "\n" + kRule + "MSG: geometry_msgs/Transform\nVector3 translation\nQuaternion rotation\n\n" + kRule +
    kVector3Section + "\n" + kRule + kQuaternionSection;
struct TfMessageType {
  static constexpr const char* kName = "tf2_msgs/TFMessage";
  static constexpr const char* kMd5 = "94810edda583a504dfda3829e70d7eec";
  static const char* definition() { return kTfMessageDefinition.c_str(); }
};
struct FluidPressureType {
  static constexpr const char* kName = "sensor_msgs/FluidPressure";
  static constexpr const char* kMd5 = "804dc5cea1c5306d6a2eb80b9833befe";
  static const char* definition() { return kFluidPressureDefinition.c_str(); }
};

/// ROS's sensor_msgs/NavSatFix (its constants kept, its comments left out; the MD5 sum is ROS's).
const std::string kNavSatFixDefinition = std::string(
    "Header header\nNavSatStatus status\nfloat64 latitude\nfloat64 longitude\nfloat64 altitude\n"
    "float64[9] position_covariance\nuint8 COVARIANCE_TYPE_UNKNOWN=0\nuint8 COVARIANCE_TYPE_APPROXIMATED=1\n"
    "uint8 COVARIANCE_TYPE_DIAGONAL_KNOWN=2\nuint8 COVARIANCE_TYPE_KNOWN=3\nuint8 position_covariance_type\n\n") +
    kRule + kHeaderSection + "\n" + kRule +
    "MSG: sensor_msgs/NavSatStatus\nint8 STATUS_NO_FIX=-1\nint8 STATUS_FIX=0\nint8 STATUS_SBAS_FIX=1\n"
    "int8 STATUS_GBAS_FIX=2\nint8 status\nuint16 SERVICE_GPS=1\nuint16 SERVICE_GLONASS=2\nuint16 SERVICE_COMPASS=4\n"
    "uint16 SERVICE_GALILEO=8\nuint16 service\n";
struct NavSatFixType {
  static constexpr const char* kName = "sensor_msgs/NavSatFix";
  static constexpr const char* kMd5 = "2d3a8cd499b9b4a0249fb98fd05cfa48";
  static const char* definition() { return kNavSatFixDefinition.c_str(); }
};

/// A message already serialized, with what its connection records (as topic_tools' ShapeShifter
/// hands a message it does not know to rosbag).
template <class Type>
struct SerializedMessage {
  std::vector<std::uint8_t> bytes;
};

template <class T>
void append(std::vector<std::uint8_t>& out, T value) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(&value);  // ROS 1 and this machine: little-endian
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

void appendString(std::vector<std::uint8_t>& out, const std::string& text) {
  append<std::uint32_t>(out, static_cast<std::uint32_t>(text.size()));
  out.insert(out.end(), text.begin(), text.end());
}

void appendHeader(std::vector<std::uint8_t>& out, std::uint32_t seq, const ros::Time& stamp, const std::string& frame_id) {
  append<std::uint32_t>(out, seq);
  append<std::uint32_t>(out, stamp.sec);
  append<std::uint32_t>(out, stamp.nsec);
  appendString(out, frame_id);
}

constexpr const char* kSonarFrame = "sonar";

/// The body frame of the fixes written in the world frame `nav_frame` (REP 105's name; FRD for NED).
std::string bodyFrame(const std::string& nav_frame) { return detail::namesNedFrame(nav_frame) ? "base_link_frd" : "base_link"; }

/// One static transform: the pose of `child` in `parent`.
struct StaticTransform {
  std::string parent, child;
  Eigen::Isometry3d pose;
};

/// The mountings as one tf2_msgs/TFMessage: the sonar's (body → sonar: the body FLU, REP 103,
/// unless the world frame is NED) and the DVL's (imu_link → dvl_link, with imu_link at the body).
SerializedMessage<TfMessageType> tfStatic(const RosBagWriteOptions& options, const ros::Time& stamp) {
  std::vector<StaticTransform> transforms;
  if (options.sonar_to_body) {
    Eigen::Isometry3d frd_to_flu = Eigen::Isometry3d::Identity();
    frd_to_flu.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
    // The "sonar" tf frame is FLU (REP 103): our sonar frame (FRD, navigation.hpp) is turned into it.
    Eigen::Isometry3d pose = *options.sonar_to_body * frd_to_flu;
    if (!detail::namesNedFrame(options.nav_frame)) pose = frd_to_flu * pose;
    transforms.push_back({bodyFrame(options.nav_frame), kSonarFrame, pose});
  }
  if (options.raw_sensors && options.dvl_rotation_flu) {
    Eigen::Isometry3d dvl = Eigen::Isometry3d::Identity();
    dvl.linear() = options.dvl_rotation_flu->normalized().toRotationMatrix();
    transforms.push_back({"imu_link", "dvl_link", dvl});
  }
  SerializedMessage<TfMessageType> message;
  std::vector<std::uint8_t>& out = message.bytes;
  append<std::uint32_t>(out, static_cast<std::uint32_t>(transforms.size()));
  for (const StaticTransform& t : transforms) {
    const Eigen::Quaterniond q(t.pose.linear());
    appendHeader(out, 0, stamp, t.parent);
    appendString(out, t.child);
    for (const double value : {t.pose.translation().x(), t.pose.translation().y(), t.pose.translation().z(), q.x(), q.y(), q.z(), q.w()}) {
      append<double>(out, value);
    }
  }
  return message;
}

/// One beam as a serialized ScanLine (ros_message.hpp's layout).
SerializedMessage<ScanLineType> scanLine(const Beam& beam, std::uint32_t seq, const ros::Time& stamp) {
  SerializedMessage<ScanLineType> message;
  std::vector<std::uint8_t>& out = message.bytes;
  appendHeader(out, seq, stamp, kSonarFrame);
  append<float>(out, static_cast<float>(detail::clockwiseDegrees(beam.bearing_rad)));
  append<float>(out, static_cast<float>(beam.bin_length_m));
  append<std::uint32_t>(out, static_cast<std::uint32_t>(beam.intensities.size()));
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    append<float>(out, static_cast<float>((static_cast<double>(i) + 0.5) * beam.bin_length_m));
    append<std::uint8_t>(out, beam.intensities[i]);
  }
  return message;
}

/// One fix as a serialized nav_msgs/Odometry in the world frame `frame_id`: NED with a
/// forward-right-down body "base_link_frd" when the name contains "ned", else ROS's ENU with the
/// forward-left-up body "base_link" (REP 103, REP 105); covariances and twist zero.
SerializedMessage<OdometryType> odometry(const NavSample& fix, std::uint32_t seq, const ros::Time& stamp,
                                         const std::string& frame_id) {
  SerializedMessage<OdometryType> message;
  std::vector<std::uint8_t>& out = message.bytes;
  const bool ned = detail::namesNedFrame(frame_id);
  appendHeader(out, seq, stamp, frame_id);
  appendString(out, bodyFrame(frame_id));
  Eigen::Vector3d position = fix.position_ned_m;
  Eigen::Quaterniond orientation(bodyToNed(fix).linear());
  if (!ned) detail::nedToRosEnu(fix, position, orientation);
  for (const double value : {position.x(), position.y(), position.z(), orientation.x(), orientation.y(),
                             orientation.z(), orientation.w()}) {
    append<double>(out, value);
  }
  for (int i = 0; i < 36 + 6 + 36; ++i) append<double>(out, 0.0);  // pose covariance, twist, twist covariance
  return message;
}

/// The raw sensors' messages of fix `i` of `nav`, ENU and FLU (REP 103): the IMU's orientation,
/// the DVL's body velocity (the track's forward difference to the next fix turned into the body,
/// the last fix's the one before's) and the pressure at the fix's depth.
struct RawSensors {
  SerializedMessage<ImuType> imu;
  SerializedMessage<TwistStampedType> twist;
  SerializedMessage<FluidPressureType> pressure;
};

RawSensors rawSensors(const NavTrack& nav, std::size_t i, const ros::Time& stamp, const RosBagWriteOptions& options) {
  RawSensors out;
  Eigen::Vector3d position_enu;
  Eigen::Quaterniond flu_to_enu;
  detail::nedToRosEnu(nav[i], position_enu, flu_to_enu);
  appendHeader(out.imu.bytes, static_cast<std::uint32_t>(i), stamp, "imu_link");
  for (const double value : {flu_to_enu.x(), flu_to_enu.y(), flu_to_enu.z(), flu_to_enu.w()}) append<double>(out.imu.bytes, value);
  for (int k = 0; k < 9 + 3 + 9 + 3 + 9; ++k) append<double>(out.imu.bytes, 0.0);  // covariances, rates, accelerations

  Eigen::Vector3d velocity_ned = Eigen::Vector3d::Zero();
  const std::size_t from = i + 1 < nav.size() ? i : (i > 0 ? i - 1 : i);
  if (from + 1 < nav.size()) {
    velocity_ned = (nav[from + 1].position_ned_m - nav[from].position_ned_m) / (nav[from + 1].time_s - nav[from].time_s);
  }
  const Eigen::Vector3d frd = bodyToNed(nav[i]).linear().transpose() * velocity_ned;
  Eigen::Vector3d flu(frd.x(), -frd.y(), -frd.z());
  if (options.dvl_rotation_flu) flu = options.dvl_rotation_flu->normalized().conjugate() * flu;  // in the DVL's own frame
  appendHeader(out.twist.bytes, static_cast<std::uint32_t>(i), stamp, "dvl_link");
  for (const double value : {flu.x(), flu.y(), flu.z(), 0.0, 0.0, 0.0}) append<double>(out.twist.bytes, value);

  appendHeader(out.pressure.bytes, static_cast<std::uint32_t>(i), stamp, "pressure_link");
  append<double>(out.pressure.bytes, options.surface_pressure_pa + options.water_density_kg_m3 * 9.80665 * nav[i].position_ned_m.z());
  append<double>(out.pressure.bytes, 0.0);
  return out;
}

/// Fix `fix` as a sensor_msgs/NavSatFix about `origin` (RosBagWriteOptions::geodetic_origin).
SerializedMessage<NavSatFixType> navSatFix(const NavSample& fix, std::uint32_t seq, const ros::Time& stamp,
                                           const GeodeticPoint& origin) {
  SerializedMessage<NavSatFixType> message;
  std::vector<std::uint8_t>& out = message.bytes;
  appendHeader(out, seq, stamp, "gps");
  append<std::int8_t>(out, 0);     // STATUS_FIX
  append<std::uint16_t>(out, 1);   // SERVICE_GPS
  const GeodeticPoint point = nedToGeodetic(origin, fix.position_ned_m);
  for (const double value : {point.latitude_deg, point.longitude_deg, point.height_m}) append<double>(out, value);
  for (int i = 0; i < 9; ++i) append<double>(out, 0.0);
  append<std::uint8_t>(out, 0);  // COVARIANCE_TYPE_UNKNOWN
  return message;
}

}  // namespace
}  // namespace sonarmap

namespace ros::message_traits {
template <class Type>
struct MD5Sum<sonarmap::SerializedMessage<Type>> {
  static const char* value() { return Type::kMd5; }
  static const char* value(const sonarmap::SerializedMessage<Type>&) { return value(); }
};
template <class Type>
struct DataType<sonarmap::SerializedMessage<Type>> {
  static const char* value() { return Type::kName; }
  static const char* value(const sonarmap::SerializedMessage<Type>&) { return value(); }
};
template <class Type>
struct Definition<sonarmap::SerializedMessage<Type>> {
  static const char* value() { return Type::definition(); }
  static const char* value(const sonarmap::SerializedMessage<Type>&) { return value(); }
};
}  // namespace ros::message_traits

namespace ros::serialization {
template <class Type>
struct Serializer<sonarmap::SerializedMessage<Type>> {
  template <typename Stream>
  static void write(Stream& stream, const sonarmap::SerializedMessage<Type>& message) {
    std::memcpy(stream.advance(static_cast<std::uint32_t>(message.bytes.size())), message.bytes.data(), message.bytes.size());
  }
  static std::uint32_t serializedLength(const sonarmap::SerializedMessage<Type>& message) {
    return static_cast<std::uint32_t>(message.bytes.size());
  }
};
}  // namespace ros::serialization

namespace sonarmap {

std::vector<unsigned char> rosBagBytes(const SonarLog& log, const NavTrack& nav, const RosBagWriteOptions& options) {
  detail::checkWritable("rosBagBytes", log, nav);
  // rosbag writes to a path: a scratch file first, its bytes then put in place atomically.
  static std::atomic<unsigned> written{0};
  const std::filesystem::path scratch = std::filesystem::temp_directory_path() /
                                        ("sonarmap-" + std::to_string(::getpid()) + "-" + std::to_string(written++) + ".bag");
  std::vector<unsigned char> bytes;
  try {
    {
      rosbag::Bag bag(scratch.string(), rosbag::bagmode::Write);
      bag.setCompression(options.compression == BagCompression::kBz2   ? rosbag::compression::BZ2
                         : options.compression == BagCompression::kLz4 ? rosbag::compression::LZ4
                                                                       : rosbag::compression::Uncompressed);
      if (options.sonar_to_body || (options.raw_sensors && options.dvl_rotation_flu)) {  // latched first, as a recorder finds it
        double first_s = log.beams.empty() ? 0.0 : log.beams.front().time_s;
        if (!nav.empty()) first_s = std::min(first_s, nav.front().time_s);
        const ros::Time stamp(first_s);
        bag.write("/tf_static", std::max(stamp, ros::TIME_MIN), tfStatic(options, stamp));
      }
      // Both streams in time order, as a recorder writes them. A time of 0 s is stamped 1 ns (ros::TIME_MIN),
      // as it is recorded: a zero stamp says "none" in ROS, and a live subscriber has no record time to fall back on.
      std::size_t b = 0, f = 0;
      while (b < log.beams.size() || f < nav.size()) {
        if (f == nav.size() || (b < log.beams.size() && log.beams[b].time_s <= nav[f].time_s)) {
          const ros::Time stamp = std::max(ros::Time(log.beams[b].time_s), ros::TIME_MIN);
          bag.write(options.sonar_topic, stamp, scanLine(log.beams[b], static_cast<std::uint32_t>(b), stamp));
          ++b;
        } else {
          const ros::Time stamp = std::max(ros::Time(nav[f].time_s), ros::TIME_MIN);
          const ros::Time recorded = stamp;
          if (options.odometry) bag.write(options.nav_topic, recorded, odometry(nav[f], static_cast<std::uint32_t>(f), stamp, options.nav_frame));
          if (options.geodetic_origin) {
            bag.write("/gps/fix", recorded, navSatFix(nav[f], static_cast<std::uint32_t>(f), stamp, *options.geodetic_origin));
          }
          if (options.raw_sensors) {
            const RawSensors raw = rawSensors(nav, f, stamp, options);
            bag.write("/imu/data", recorded, raw.imu);
            if (options.raw_dvl) bag.write("/dvl/twist", recorded, raw.twist);
            bag.write("/pressure", recorded, raw.pressure);
          }
          ++f;
        }
      }
    }
    std::ifstream in(scratch, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& error) {
    std::filesystem::remove(scratch);
    throw FileError(std::string("cannot write the ROS bag: ") + error.what());
  }
  std::filesystem::remove(scratch);
  return bytes;
}

void writeRosBag(const std::string& path, const SonarLog& log, const NavTrack& nav, const RosBagWriteOptions& options) {
  std::vector<unsigned char> bytes;
  try {
    bytes = rosBagBytes(log, nav, options);
  } catch (const FileError& error) {
    throw FileError("'" + path + "': " + error.what());
  }
  writeBytesAtomically(path, bytes);
}

}  // namespace sonarmap
