#pragma once
/// @file mavlink_navigation.hpp
/// Navigation fixes from an ArduSub autopilot's MAVLink stream as it arrives (a BlueROV2 during a
/// dive: ArduSub streams to UDP 14550 through BlueOS, or over a serial line), for `sonarmap live`.
/// readMavlinkTlogNavigation (vehicle_log_navigation.hpp) is this decoder fed a whole `.tlog`.
///
/// **Which frames.** The vehicle is the system and component that sends the first ATTITUDE (a
/// ground station's own HEARTBEATs and a companion's messages are not read); its frames received
/// before that ATTITUDE are kept (the last 64) and read then. Read from it: ATTITUDE (#30),
/// LOCAL_POSITION_NED (#32), GLOBAL_POSITION_INT (#33), SCALED_PRESSURE (#29), SCALED_PRESSURE2
/// (#137), SCALED_PRESSURE3 (#143), PARAM_VALUE (#22, for the pressures' calibration, below); and
/// VISION_POSITION_DELTA (#11011) from whichever one sender
/// sends it first: BlueOS's Water Linked DVL extension posts it through mavlink2rest as system
/// 255, component 0, with time_usec 0, so it is timed by its arrival (below).
///
/// **A fix per ATTITUDE** (roll, pitch, yaw: Z-Y-X Euler angles of body FRD in NED, radians, as
/// NavSample), its position from the best source that covers its time:
///  - north, east: LOCAL_POSITION_NED x, y (metres; ArduSub sends it while its EKF has a position,
///    e.g. fusing a DVL with an EKF origin set), else the sum of VISION_POSITION_DELTA's
///    position_delta (metres in the body FRD frame at the message's arrival, turned into NED by the
///    latest ATTITUDE; the DVL extension sends dt × the DVL's velocity), carried on from the
///    previous fix's north and east (a sum of deltas is relative: from 0 at the first fix, and no
///    jump when LOCAL_POSITION_NED stops), else held: at 0 until a source appears, at the last
///    value when one stops;
///  - depth (down, metres): LOCAL_POSITION_NED z, else −GLOBAL_POSITION_INT.relative_alt (mm) (the
///    autopilot's own depths), else the external pressure sensor: SCALED_PRESSURE2, then
///    SCALED_PRESSURE3, then SCALED_PRESSURE. ArduSub sends its barometers 0, 1, 2 as
///    SCALED_PRESSURE, 2, 3 and makes the first water-type one its primary; on a BlueROV2 the
///    onboard barometer is 0 and the Bar30 is 1, hence SCALED_PRESSURE2 first. A press_abs that is
///    not above 0 is no reading (ArduSub fills SCALED_PRESSURE3 with 0 hPa to carry a temperature
///    sensor's reading).
/// A position is interpolated linearly between the two samples of its source around the fix's
/// time (MAVLink boot times). North and east follow a source while it keeps coming: one silent for
/// longer than max_hold_s gives way to the next (its last sample serves the fixes up to max_hold_s
/// after it); a source that begins less than max_hold_s after an attitude gives that attitude no
/// fix (no jump from a fallback at the start). The words of each change are in takeNotes().
///
/// **Depth** comes from one source at a time, with hysteresis, so that a slow autopilot depth
/// (ArduSub may send GLOBAL_POSITION_INT at 0.5 Hz beside its pressures at 10 Hz) does not
/// alternate with a pressure. The current source is kept while it is coming: its silence before a
/// fix's time is at most 3 × the median of its last 15 intervals, at least max_hold_s (6 s, at
/// least max_hold_s, before its second sample tells its rhythm); a fix past its last sample waits
/// for its next one up to max_hold_s, then takes its last one. Once it is silent for longer, the
/// most preferred source coming takes over; a more preferred one is taken back only after it has
/// come for as long again (its current run, since its last such silence, at least its silence
/// long). Each change is one note. The boot's first choice waits as north and east's does.
/// A pressure p (Pa) becomes a depth as ArduSub's water barometer does (ArduPilot's
/// AP_Baro::update), (p − ground) / (9800 Pa/m × specific gravity), with the autopilot's own
/// parameters when a PARAM_VALUE brought them (BARO1_GND_PRESS, BARO2_, BARO3_ for SCALED_PRESSURE,
/// 2, 3, and BARO_SPEC_GRAV; ArduSub 3.5's GND_ABS_PRESS, GND_ABS_PRESS2, 3 and GND_SPEC_GRAV);
/// without them, surface_pressure_pa and water_density_kg_m3 × 9.80665 stand in. And when the
/// autopilot's own depth came beside that barometer, the median of their last 15 differences (the
/// pressure interpolated at the depth's times) is added: the autopilot's calibration in practice,
/// whatever its ground pressure, so the hand-over does not jump. The calibration is fixed when the
/// pressure becomes the source and said in its note.
///
/// **What a live caller waits for.** A fix is made when the next sample of its source arrives
/// (e.g. the next LOCAL_POSITION_NED: SRx_POSITION, a few Hz), so it lags its ATTITUDE by up to the
/// source's period; never by more than max_hold_s of the autopilot's clock (measured by later
/// frames: when the stream stops, fixes wait for finish()). In the first max_hold_s after the
/// first frame, fixes also wait to learn which sources the vehicle sends. ATTITUDE comes at
/// SRx_EXTRA1, GLOBAL_POSITION_INT and LOCAL_POSITION_NED at SRx_POSITION, the pressures at
/// SRx_RAW_SENS (ArduPilot's stream groups).
///
/// **Clock.** A fix's time is its time_boot_ms on the caller's clock: plus the smallest (arrival −
/// boot time) over the vehicle's frames so far (the least-delayed frame), so reception jitter does
/// not move the fixes. Fixes come out strictly increasing: one not after the previous (the
/// smallest delay dropped, or a burst of buffered frames) is dropped and counted. A boot time more
/// than 10 s behind the latest starts a new boot (the autopilot rebooted): its clock offset is
/// found anew, and the previous boot's waiting fixes are made as finish() makes them.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/formats/mavlink.hpp"
#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {

struct MavlinkNavigationOptions {
  VehicleLogOptions pressure;  ///< water density and surface pressure for depths from pressure
  /// The longest a fix waits for its source's next sample, and how long a silent source keeps
  /// serving (seconds of the autopilot's clock); for depth, the shortest silence that gives its
  /// source up (above). > 0.
  double max_hold_s = 1.0;
};

/// The sender of a MAVLink frame.
struct MavlinkSender {
  std::uint8_t system = 0;
  std::uint8_t component = 0;
};

/// Fixes out of an autopilot's MAVLink stream, bytes or frames in, as they can be made.
class MavlinkNavigation {
 public:
  /// @param source  names the stream in notes ("udp://0.0.0.0:14550").
  /// @throws ValueError when the pressure options are not positive and finite or max_hold_s is not
  ///   a positive finite number.
  explicit MavlinkNavigation(std::string source = "MAVLink", const MavlinkNavigationOptions& options = {});
  ~MavlinkNavigation();
  MavlinkNavigation(MavlinkNavigation&&) noexcept;
  MavlinkNavigation& operator=(MavlinkNavigation&&) noexcept;

  /// The stream's next bytes (any chunk: a datagram, a serial read), received at `arrival_s` (the
  /// caller's clock, seconds). Returns the fixes they complete, on the caller's clock, after every
  /// fix returned before. Never throws for any bytes (only std::bad_alloc).
  /// @throws ValueError when arrival_s is not finite.
  std::vector<NavSample> feed(std::span<const std::uint8_t> bytes, double arrival_s);
  /// One frame already parsed (MavlinkFrameParser), received at `arrival_s`. Frames whose checksum
  /// was not checked (frame.checked false) are not read.
  std::vector<NavSample> feedFrame(const MavlinkFrame& frame, double arrival_s);
  /// The end of the stream: the waiting attitudes get a fix where their source's samples are on
  /// both sides of them; the others none. Later calls return nothing.
  std::vector<NavSample> finish();

  /// The frames, noise and bad frames of the bytes fed.
  const MavlinkStreamCounts& streamCounts() const;
  /// ATTITUDE messages of the vehicle that gave no fix (not finite, not after the previous one,
  /// before a source began, cut by the end, or dropped by the clock).
  std::size_t attitudesWithoutFix() const;
  /// The vehicle, once an ATTITUDE chose it.
  std::optional<MavlinkSender> vehicle() const;
  /// What the fixes so far were made from: "attitude ATTITUDE, position LOCAL_POSITION_NED".
  std::string description() const;
  /// Lines for the user not taken yet (the sources chosen and each change, a reboot), handed over
  /// and forgotten.
  std::vector<std::string> takeNotes();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
