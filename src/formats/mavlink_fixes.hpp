#pragma once
/// @file mavlink_fixes.hpp
/// Private to src/formats: fixes made from an autopilot's MAVLink frames on its own boot clock, the
/// rules of mavlink_navigation.hpp without the last step (the caller's clock). MavlinkNavigation
/// puts each fix on the arrival clock as it is made, with the clock offset known then; the `.tlog`
/// reader puts them all on the offset of the whole boot at the end.

#include <array>
#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/mavlink_navigation.hpp"
#include "sonarmap/nav/geodetic.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::detail {

/// A fix whose time_s is seconds since the autopilot's boot number `boot` (0, then 1 after a
/// reboot…).
struct BootFix {
  NavSample fix;
  std::size_t boot = 0;
};

/// Samples of one source on the boot clock, strictly increasing in time: a position (NED) or, for
/// a depth source, a depth in z (metres) or, for a pressure source, the absolute pressure in z
/// (pascals); and the source's rhythm: its recent intervals and the start of its current run.
class SourceSeries {
 public:
  struct Sample {
    double time_s;
    Eigen::Vector3d value;
  };
  /// The shortest silence_s() (seconds, > 0): MavlinkNavigationOptions::max_hold_s.
  void setMinSilence_s(double seconds) { min_silence_s_ = seconds; }
  /// Adds a sample; one not after the last is ignored (false). A sample after a silence longer
  /// than silence_s() starts a new run.
  bool add(double time_s, const Eigen::Vector3d& value);
  /// How long the source may be silent and still be followed, seconds: 3 × the median of its last
  /// 15 intervals, at least the minimum silence; before its second sample, 6 s (3 intervals of a
  /// 0.5 Hz stream), at least the minimum.
  double silence_s() const;
  /// The time of the first sample of the current run (after the last silence longer than silence_s()).
  double runStart_s() const { return run_start_s_; }
  /// The time of the last sample at or before `time_s`; nullopt when none is kept.
  std::optional<double> lastTimeAtOrBefore(double time_s) const;
  /// Sets the last sample's value (a sample for the same time, already taken).
  void setLast(const Eigen::Vector3d& value) { samples_.back().value = value; }
  /// The value at `time_s`, linear between the samples around it; nullopt outside them.
  std::optional<Eigen::Vector3d> at(double time_s) const;
  /// Whether a sample came since the last clear() (it keeps one once it had one).
  bool seen() const { return !samples_.empty(); }
  double firstTime_s() const { return samples_.front().time_s; }
  double lastTime_s() const { return samples_.back().time_s; }
  const Eigen::Vector3d& lastValue() const { return samples_.back().value; }
  /// Forgets the samples before the last one at or before `time_s` (no later time is asked for).
  void forgetBefore(double time_s);
  void clear() {
    samples_.clear();
    intervals_s_.clear();
    run_start_s_ = 0.0;
  }

 private:
  std::deque<Sample> samples_;
  std::deque<double> intervals_s_;  ///< the last 15 intervals between samples, seconds
  double min_silence_s_ = 1.0;
  double run_start_s_ = 0.0;
};

/// The sources of a fix's position, in order of preference within each chain.
enum class NavSource { kLocalPosition, kVisionDelta, kGlobalPosition, kPressure2, kPressure3, kPressure1 };
inline constexpr std::size_t kNavSources = 6;
/// The sources of depth, most preferred first: the autopilot's own depths, then its barometers.
inline constexpr std::array<NavSource, 5> kDepthChain{NavSource::kLocalPosition, NavSource::kGlobalPosition,
                                                      NavSource::kPressure2, NavSource::kPressure3, NavSource::kPressure1};
/// The message (and field) a source is read from: "GLOBAL_POSITION_INT.relative_alt".
const char* navSourceName(NavSource source);

class MavlinkFixMaker {
 public:
  /// The options are taken as given (MavlinkNavigation and the `.tlog` reader check them).
  explicit MavlinkFixMaker(const MavlinkNavigationOptions& options);

  /// Reads one frame received at `arrival_s` (any clock, seconds); appends the fixes it completes.
  /// Frames not checked (unknown messages) are not read.
  void take(const MavlinkFrame& frame, double arrival_s, std::vector<BootFix>& out);
  /// The end of the frames: the waiting attitudes whose source's samples are on both sides of them
  /// get a fix, the others none.
  void finish(std::vector<BootFix>& out);

  /// The smallest (arrival − boot time) over boot `boot`'s frames so far, seconds.
  double clockOffset_s(std::size_t boot) const { return offsets_s_.at(boot); }
  bool sawAttitude() const { return vehicle_.has_value(); }
  std::optional<MavlinkSender> vehicle() const { return vehicle_; }
  std::size_t attitudesWithoutFix() const { return without_fix_; }
  /// "attitude ATTITUDE, position LOCAL_POSITION_NED": the sources of the fixes made so far.
  std::string description() const;
  std::vector<std::string> takeNotes() { return std::exchange(notes_, {}); }
  /// GLOBAL_POSITION_INT's latitudes and longitudes so far (lat = lon = 0, ArduPilot's "no
  /// position", left out), on boot `BootGeodeticFix::boot`'s clock; a NaN-free but out-of-range one
  /// is left out and counted (geodeticRejected, with the first reason).
  struct BootGeodeticFix {
    std::size_t boot = 0;
    GeodeticFix fix;
  };
  const std::vector<BootGeodeticFix>& geodeticFixes() const { return geodetic_; }
  std::size_t geodeticRejected() const { return geodetic_rejected_; }
  const std::string& geodeticReason() const { return geodetic_reason_; }

 private:
  struct Attitude {
    double time_s;
    double roll_rad, pitch_rad, yaw_rad;
  };
  /// A chain's verdict on one attitude: wait for more frames, no fix, or this value.
  struct Choice {
    enum class Kind { kWait, kDrop, kValue } kind = Kind::kWait;
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    std::optional<NavSource> source;  ///< unset: the chain's last value held
    bool stale = false;               ///< the source's last sample, the source having stopped
    std::string calibration;          ///< a pressure's: how it was made a depth ("" for the others)
    static Choice wait() { return Choice{}; }
    static Choice drop() { return Choice{Kind::kDrop, Eigen::Vector3d::Zero(), std::nullopt, false, {}}; }
    static Choice of(const Eigen::Vector3d& value, std::optional<NavSource> source, bool stale = false,
                     std::string calibration = {}) {
      return Choice{Kind::kValue, value, source, stale, std::move(calibration)};
    }
  };
  /// A depth of the autopilot's own: LOCAL_POSITION_NED z or −GLOBAL_POSITION_INT.relative_alt.
  struct AutopilotDepth {
    NavSource source;
    double time_s;
    double depth_m;
  };
  /// An autopilot depth beside a pressure at its time: what calibrates that pressure.
  struct DepthPair {
    NavSource autopilot;
    double depth_m;
    double pressure_pa;
  };
  /// How a pressure becomes a depth: (p − surface) / pascals_per_metre + offset.
  struct PressureCalibration {
    double surface_pa = 0.0;
    double pascals_per_metre = 1.0;
    double offset_m = 0.0;
    std::string words;
  };
  enum Chain { kHorizontal = 0, kDepth = 1 };

  void takeVehicleFrame(const MavlinkFrame& frame, double arrival_s, std::vector<BootFix>& out);
  void takeVisionDelta(const MavlinkFrame& frame, double arrival_s);
  void startBoot(double time_s);
  void makeFixes(std::vector<BootFix>& out, bool final);
  Choice choose(Chain chain, double time_s, bool final) const;
  // Depth (mavlink_depth_choice.cpp).
  void takeParameter(const MavlinkFrame& frame);
  void addAutopilotDepth(NavSource source, double time_s, double depth_m);
  void addPressure(NavSource source, double time_s, double pressure_pa);
  void pairDepths();
  bool depthAlive(NavSource source, double time_s) const;
  PressureCalibration pressureCalibration(NavSource source) const;
  Choice chooseDepth(double time_s, bool final);
  void noteChoice(Chain chain, const Choice& choice, double time_s);
  SourceSeries& series(NavSource s) { return series_[static_cast<std::size_t>(s)]; }
  const SourceSeries& series(NavSource s) const { return series_[static_cast<std::size_t>(s)]; }

  MavlinkNavigationOptions options_;
  std::optional<MavlinkSender> vehicle_;
  std::optional<MavlinkSender> vision_sender_;
  /// Frames received before the vehicle was known (the last 64), read once it is.
  std::deque<std::pair<MavlinkFrame, double>> early_;
  std::array<SourceSeries, kNavSources> series_;
  std::deque<Attitude> waiting_;
  std::optional<Attitude> latest_attitude_;  ///< turns a VISION_POSITION_DELTA into NED
  Eigen::Vector2d vision_ne_m_ = Eigen::Vector2d::Zero();  ///< the sum of VISION_POSITION_DELTAs in NED
  /// Added to that sum where fixes use it: the position it continues from.
  Eigen::Vector3d vision_anchor_m_ = Eigen::Vector3d::Zero();
  std::optional<NavSource> last_horizontal_;  ///< the source of the last fix's north and east
  std::vector<double> offsets_s_;  ///< per boot
  std::vector<BootGeodeticFix> geodetic_;
  std::size_t geodetic_rejected_ = 0;
  std::string geodetic_reason_;
  bool in_boot_ = false;
  double boot_first_s_ = 0.0;  ///< the boot's first frame's time
  double boot_now_s_ = 0.0;    ///< the boot's latest frame's time
  double last_attitude_s_ = -std::numeric_limits<double>::infinity();
  std::array<Eigen::Vector3d, 2> chain_value_{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<std::string, 2> chain_words_;  ///< the last fix's source words, per chain
  std::array<bool, 2> sourced_{};  ///< whether a fix of this boot had a source, per chain
  std::array<std::vector<std::string>, 2> used_;  ///< source names the fixes used, per chain
  std::optional<NavSource> depth_source_;  ///< the source of the last fix's depth, this boot
  PressureCalibration depth_calibration_;  ///< fixed when a pressure became depth_source_
  std::deque<AutopilotDepth> unpaired_;  ///< autopilot depths awaiting a pressure at their time
  std::array<std::deque<DepthPair>, 3> depth_pairs_;  ///< per barometer (SCALED_PRESSURE, 2, 3): the last 15
  std::array<std::optional<double>, 3> ground_pressure_pa_;  ///< BARO1..3_GND_PRESS (or GND_ABS_PRESS, 2, 3)
  std::optional<double> specific_gravity_;                   ///< BARO_SPEC_GRAV (or GND_SPEC_GRAV)
  std::vector<std::string> parameters_said_;
  std::size_t without_fix_ = 0;
  std::size_t boot_notes_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace sonarmap::detail
