#pragma once
/// @file dive_recorder.hpp
/// What a live run received, written as it arrives to a ROS 2 log in an MCAP file (mcap.dev/spec,
/// profile "ros2") that `sonarmap map` reads back to the same beams and fixes, bit for bit: the
/// log of a dive that can be replayed and mapped again (docs/formats.md, "Recorded dives").
///
/// Messages (CDR, each schema written into the file):
///  - `sonarmap_msgs/msg/SonarBeam` on /sonar/beam: `std_msgs/Header header` (the beam's time),
///    `float64 bearing_rad` (sonar frame, clockwise from ahead, beam.hpp), `float64 bin_length_m`,
///    `int16 gain_setting` (the head's own gain setting; −1: not reported), `float64
///    pulse_length_m` and `float64 intensity_span_db` (0: not reported), `float64 beam_width_rad`
///    and `float64 vertical_aperture_rad` (the beam the run was mapped with, so that `map` of the
///    file maps with it; 0: not said), `uint8[] intensities`.
///  - `sonarmap_msgs/msg/NavFix` on /navigation/fix: `std_msgs/Header header`, `float64 north_m`,
///    `east_m`, `down_m` (NED, metres), `float64 roll_rad`, `pitch_rad`, `yaw_rad` (body FRD in NED,
///    Z-Y-X, navigation.hpp).
///  - Metadata records (a name and string pairs): the head's settings, the program and its options.
/// Times are stored as ROS's stamps (int32 seconds, uint32 nanoseconds since the epoch):
/// recordedTime() is a time as it comes back, so a live mapper given recordedTime()s maps what
/// `map` of the file maps.
///
/// The file is written to PATH.part and renamed to PATH by finish(); chunks reach the disk at
/// least every flush() (the live run flushes every second), so a run that is killed leaves a
/// PATH.part holding all but its last chunk (readable once its end is cut off at the last whole
/// chunk; docs/formats.md).

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "sonarmap/formats/mcap_writer.hpp"
#include "sonarmap/nav/navigation.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Options of DiveRecorder.
struct DiveRecorderOptions {
  std::string sonar_topic = "/sonar/beam";
  std::string nav_topic = "/navigation/fix";
  McapCompression compression = McapCompression::kZstd;
  std::size_t chunk_bytes = 1u << 20;  ///< a chunk is written once its messages reach this many bytes
  /// The beam written with each beam (the one it is mapped with); unset: 0, not said.
  std::optional<NominalBeam> nominal_beam;
};

/// Writes a dive's beams, fixes and settings as they come (see the file's comment).
class DiveRecorder {
 public:
  /// Creates PATH.part (replacing one a killed run left).
  /// @throws FileError when it cannot be created (the folder is missing, not writable).
  DiveRecorder(std::string path, const DiveRecorderOptions& options = {});
  /// Without finish(): writes the last chunk and closes PATH.part, which stays (an error ended the
  /// run; nothing is renamed over PATH).
  ~DiveRecorder();
  DiveRecorder(const DiveRecorder&) = delete;
  DiveRecorder& operator=(const DiveRecorder&) = delete;

  /// `time_s` (seconds since the epoch) as the file gives it back: rounded to the nanosecond and
  /// read as int32 seconds + 1e-9 × uint32 nanoseconds, as the readers of ROS logs compute it.
  /// @throws ValueError when `time_s` is not finite or outside 1970 … 2038 (int32 seconds).
  static double recordedTime(double time_s);

  /// A Metadata record `name` holding `values` (e.g. "sonarmap.head": the settings applied).
  void addMetadata(const std::string& name, const std::map<std::string, std::string>& values);
  /// One beam; its time should be a recordedTime() (it is rounded so anyway).
  /// @throws ValueError for a beam whose time is out of range or bin length is not > 0.
  void addBeam(const Beam& beam);
  /// One fix (NED, body FRD); its time should be a recordedTime().
  /// @throws ValueError for a fix with a non-finite value or a time out of range.
  void addNavFix(const NavSample& fix);
  /// Writes the chunk being gathered and flushes the file to the system.
  /// @throws FileError when the file cannot be written (a full disk).
  void flush();
  /// Ends the file (DataEnd, footer, magic), closes it and renames PATH.part to PATH. Idempotent.
  /// @throws FileError when it cannot be written or renamed.
  void finish();

  const std::string& path() const { return path_; }
  /// PATH.part, where the file is written until finish().
  std::string partialPath() const { return path_ + ".part"; }
  std::size_t beams() const { return beams_; }
  std::size_t fixes() const { return fixes_; }

 private:
  struct Writer;
  std::string path_;
  std::unique_ptr<Writer> writer_;
  std::size_t beams_ = 0, fixes_ = 0;
  bool finished_ = false;
};

}  // namespace sonarmap
