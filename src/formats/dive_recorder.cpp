/// @file dive_recorder.cpp
/// A live run's beams and fixes written as they come (see dive_recorder.hpp).

#include "sonarmap/formats/dive_recorder.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "mcap_records.hpp"
#include "ros_message.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

const std::string kSonarBeam = detail::ros2SchemaWithHeader(
    "std_msgs/Header header\nfloat64 bearing_rad\nfloat64 bin_length_m\nint16 gain_setting\nfloat64 pulse_length_m\n"
    "float64 intensity_span_db\nfloat64 beam_width_rad\nfloat64 vertical_aperture_rad\nuint8[] intensities\n");
const std::string kNavFix = detail::ros2SchemaWithHeader(
    "std_msgs/Header header\nfloat64 north_m\nfloat64 east_m\nfloat64 down_m\nfloat64 roll_rad\nfloat64 pitch_rad\n"
    "float64 yaw_rad\n");

/// A stamp: int32 seconds since the epoch and uint32 nanoseconds.
struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::uint64_t nanoseconds() const { return static_cast<std::uint64_t>(sec) * 1000000000ULL + nanosec; }
};

Stamp stampOf(double time_s) {
  if (!std::isfinite(time_s) || time_s < 0.0 || time_s >= static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    throw ValueError("a recorded time must be seconds since 1970 within ROS's int32 stamps, got " + std::to_string(time_s));
  }
  double seconds = std::floor(time_s);
  double nanoseconds = std::round((time_s - seconds) * 1e9);
  if (nanoseconds >= 1e9) {
    seconds += 1.0;
    nanoseconds = 0.0;
  }
  return {static_cast<std::int32_t>(seconds), static_cast<std::uint32_t>(nanoseconds)};
}

}  // namespace

struct DiveRecorder::Writer {
  Writer(const std::string& partial, const DiveRecorderOptions& options)
      : file(partial, std::ios::binary | std::ios::trunc), records(file, options.compression, options.chunk_bytes) {
    sonar = records.channel(records.schema("sonarmap_msgs/msg/SonarBeam", kSonarBeam), options.sonar_topic);
    nav = records.channel(records.schema("sonarmap_msgs/msg/NavFix", kNavFix), options.nav_topic);
  }
  std::ofstream file;
  detail::McapRecordWriter records;
  std::uint16_t sonar = 0, nav = 0;
  NominalBeam beam;  ///< written with each beam (0, 0: not said)
};

DiveRecorder::DiveRecorder(std::string path, const DiveRecorderOptions& options) : path_(std::move(path)) {
  {
    std::ofstream probe(partialPath(), std::ios::binary | std::ios::trunc);
    if (!probe) throw FileError("cannot create '" + partialPath() + "' to record the dive");
  }
  writer_ = std::make_unique<Writer>(partialPath(), options);
  writer_->beam = options.nominal_beam.value_or(NominalBeam{});
}

DiveRecorder::~DiveRecorder() {
  if (finished_ || !writer_) return;
  try {
    writer_->records.flush();
  } catch (const std::exception&) {  // a destructor does not throw: the chunks already written stay
  }
}

double DiveRecorder::recordedTime(double time_s) {
  const Stamp stamp = stampOf(time_s);
  return detail::rosStampSeconds(stamp.sec, stamp.nanosec);
}

void DiveRecorder::addMetadata(const std::string& name, const std::map<std::string, std::string>& values) {
  writer_->records.metadata(name, values);
}

void DiveRecorder::addBeam(const Beam& beam) {
  if (!(beam.bin_length_m > 0.0) || !std::isfinite(beam.bin_length_m)) {
    throw ValueError("a recorded beam's bin length must be finite and > 0 m");
  }
  const Stamp stamp = stampOf(beam.time_s);
  detail::Cdr message;
  message.header(stamp.sec, stamp.nanosec, "sonar");
  message.put<double>(beam.bearing_rad);
  message.put<double>(beam.bin_length_m);
  message.put<std::int16_t>(static_cast<std::int16_t>(beam.gain_setting.value_or(-1)));
  message.put<double>(beam.pulse_length_m.value_or(0.0));
  message.put<double>(beam.intensity_span_db.value_or(0.0));
  message.put<double>(writer_->beam.width_rad);
  message.put<double>(writer_->beam.vertical_aperture_rad);
  message.bytes(beam.intensities);
  writer_->records.message(writer_->sonar, stamp.nanoseconds(), message.bytes());
  ++beams_;
}

void DiveRecorder::addNavFix(const NavSample& fix) {
  if (!isFinite(fix)) throw ValueError("a recorded navigation fix must be finite");
  const Stamp stamp = stampOf(fix.time_s);
  detail::Cdr message;
  message.header(stamp.sec, stamp.nanosec, "odom_ned");
  for (const double value : {fix.position_ned_m.x(), fix.position_ned_m.y(), fix.position_ned_m.z(), fix.roll_rad,
                             fix.pitch_rad, fix.yaw_rad}) {
    message.put<double>(value);
  }
  writer_->records.message(writer_->nav, stamp.nanoseconds(), message.bytes());
  ++fixes_;
}

void DiveRecorder::flush() { writer_->records.flush(); }

void DiveRecorder::finish() {
  if (finished_) return;
  writer_->records.finish();
  writer_->file.close();
  if (!writer_->file) throw FileError("cannot close '" + partialPath() + "' (is the disk full?)");
  std::error_code error;
  std::filesystem::rename(partialPath(), path_, error);
  if (error) throw FileError("cannot rename '" + partialPath() + "' to '" + path_ + "': " + error.message());
  finished_ = true;
}

}  // namespace sonarmap
