#pragma once
/// @file ping360_driver.hpp
/// A Blue Robotics Ping360 driven over ping-protocol (ping_protocol.hpp) as Ping Viewer and
/// ping-python drive it: one `transducer` command a ping, the next angle sent when the previous
/// ping's device_data arrives. A state machine without I/O (head_driver.hpp). The settings'
/// defaults, their rounding to the head's units and the settings refused: ping360_settings.hpp.
///
/// The conversation:
///  1. start(): the settings' rounding notes (Ping360Settings::notes), then
///     general_request(protocol_version) and general_request(device_information) (the
///     protocol's discovery, docs/index.md; Ping Viewer asks for device_information). Repeated
///     every 0.5 s (ping-python's request timeout) until device_information arrives; a nack of the
///     request also ends the wait (the head is there).
///  2. One transducer command (mode 1, transmit 1) at Ping360Settings::angleOf(0), then at each
///     next index when the device_data of the pending angle arrives: full turns by `step`, or a
///     sector back and forth between its limits.
///  3. A command without its device_data in time is sent again: the timeout is the motor's travel
///     at 4 s a turn (the unknown start: half a turn), the listening time 2R/c and the transmit
///     duration, the reply's transfer at the link's baud rate, and 200 ms (Ping Viewer's
///     allowance for latency), at most 4 s (ping360.json). A nack of the command (the head
///     refused it) is retried after 1 s.
///  4. stop(): motor_off (Ping Viewer sends it on closing); the driver sends nothing after it (a
///     reply already on its way still gives its beam).
///
/// Beams: every device_data with samples (ping_protocol::ping360Beam at the driver's sound speed,
/// the reader's decoding), including auto_device_data a head still in auto-transmit mode sends (the
/// driver then also sends motor_off, at most once a second, to stop it, as the protocol allows). A
/// device_data at another angle than the pending command's answers an earlier, repeated command:
/// its beam is dropped (it would repeat a bearing out of turn) and noted. Notes: the device found,
/// the protocol version, a command repeated, a nack, a device that is not a Ping360, the head
/// applying other settings than asked, skipped bytes (at most one note a second).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/devices/head_driver.hpp"
#include "sonarmap/devices/ping360_settings.hpp"

namespace sonarmap {

struct Ping360DriverOptions {
  /// Bits per second of the link, for the reply's transfer in the timeout (10 bits a byte); 0 for
  /// a network link. The default, 115,200, is the slowest rate Ping Viewer's baud detection tries.
  unsigned link_baud = 115200;
};

class Ping360Driver final : public HeadDriver {
 public:
  /// @throws ValueError for settings the Ping360 cannot take (ping360Settings).
  explicit Ping360Driver(const HeadSettings& settings, const Ping360DriverOptions& options = {});
  ~Ping360Driver() override;

  DriverOutput start(double now_s) override;
  DriverOutput receive(std::span<const std::uint8_t> bytes, double now_s) override;
  DriverOutput poll(double now_s) override;
  std::vector<std::uint8_t> stop() override;
  /// The settings sent (Ping360Settings::applied); once a device_data arrived, its gain, transmit
  /// duration, sample period, samples and frequency as the head reports them.
  AppliedSettings applied() const override;
  std::string device() const override;
  bool heard() const override;

  const Ping360Settings& settings() const;
  /// Commands sent again after a timeout or a nack.
  std::size_t repeats() const;
  /// The timeout of a transducer command moving the head `travel_grad` gradians (step 3 above).
  double replyTimeout_s(int travel_grad) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
