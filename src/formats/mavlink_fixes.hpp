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
/// a depth source, a depth in z.
class SourceSeries {
 public:
  struct Sample {
    double time_s;
    Eigen::Vector3d value;
  };
  /// Adds a sample; one not after the last is ignored (false).
  bool add(double time_s, const Eigen::Vector3d& value);
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
  void clear() { samples_.clear(); }

 private:
  std::deque<Sample> samples_;
};

/// The sources of a fix's position, in order of preference within each chain.
enum class NavSource { kLocalPosition, kVisionDelta, kGlobalPosition, kPressure2, kPressure3, kPressure1 };
inline constexpr std::size_t kNavSources = 6;

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
    static Choice wait() { return Choice{}; }
    static Choice drop() { return Choice{Kind::kDrop, Eigen::Vector3d::Zero(), std::nullopt, false}; }
    static Choice of(const Eigen::Vector3d& value, std::optional<NavSource> source, bool stale = false) {
      return Choice{Kind::kValue, value, source, stale};
    }
  };
  enum Chain { kHorizontal = 0, kDepth = 1 };

  void takeVehicleFrame(const MavlinkFrame& frame, double arrival_s, std::vector<BootFix>& out);
  void takeVisionDelta(const MavlinkFrame& frame, double arrival_s);
  void startBoot(double time_s);
  void makeFixes(std::vector<BootFix>& out, bool final);
  Choice choose(Chain chain, double time_s, bool final) const;
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
  std::size_t without_fix_ = 0;
  std::size_t boot_notes_ = 0;
  std::vector<std::string> notes_;
};

}  // namespace sonarmap::detail
