#pragma once
/// @file ping360_emulator.hpp
/// A Blue Robotics Ping360 emulated over ping-protocol (ping_protocol.hpp), its pings simulated in
/// a scene (sim/beam_simulator.hpp): what a Ping360 host (Ping360Driver, Ping Viewer, ping-python)
/// sees of the head. A state machine without I/O (head_emulator.hpp); `sonarmap emulate` serves it
/// on a pseudo-terminal or UDP.
///
/// What it answers (ping360.json, common.json; [A]: where the real firmware is not documented):
///  - general_request(device_information): its identity (device type 2, revision 67 as the head of
///    the shared logs, firmware 3.3.1 by default: newer than 3.3.0, the first version for which
///    Ping Viewer drives a Ping360 with auto_transmit; the shared logs' head runs 3.1.1);
///    general_request(protocol_version): 1.1.0 [A] (auto_transmit is marked "NEW (v1.1.0)");
///    general_request(device_data): a device_data of its settings without samples (ping-python's
///    Ping360.initialize() reads the settings so); other requests: a nack.
///  - transducer: one device_data at the commanded angle, gain, sample period, samples, frequency
///    and transmit duration, with the ping's samples when transmit is 1, none when 0. The transmit
///    duration is held within [5 µs, min(500 µs, 64 sample periods)] as Ping Viewer says the
///    firmware does, and the device_data reports it so. Fields outside the json's ranges (gain
///    0–2, angle 0–399, transmit duration 1–1000 µs, sample period 80–40000 ticks, frequency
///    500–1000 kHz, samples 200–1200) get a nack naming the field [A]. Every nack's text is 7-bit
///    ASCII ("angle 400 is outside 0..399"): hosts decode nack_message as ASCII. The mode is not checked
///    (ping-python's transmitAngle sends 0) and device_data says 1.
///  - auto_transmit: auto_device_data pings by themselves across the sector until motor_off, reset
///    or any other command but general_request: clockwise turns by num_steps when the sector is
///    the whole circle (stop + 1 ≡ start), else from start clockwise to stop and back, each limit
///    pinged once per reversal [A]; delay ms between pings.
///  - motor_off: an ack (it also ends an auto scan). set_device_id: an ack, its messages then come
///    from that id. reset: back to the firmware's boot settings, no answer. Any other id, or a
///    payload of the wrong length: a nack.
///  Bytes that are not messages (a break, the autobaud 'U' ping-python sends on connecting) are
///  ignored.
///
/// When: the head works one message at a time, in order. A reply is due after the motor's travel
/// (the shortest way, 400 gradians in 2.4 s, Ping Viewer), the listening time (samples × sample
/// period: 2R/c), and the reply's transfer at `baud` (10 bits a byte; 0: at once, as over UDP).
/// The ping is simulated at the time it is made (after the travel), from the trajectory's pose then.
///
/// The boot settings (Ping Viewer's "firmware defaults at boot"): gain 0, angle 0, transmit
/// duration 32 µs, sample period 80 ticks, 740 kHz, 1024 samples.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/devices/head_emulator.hpp"
#include "sonarmap/formats/ping_protocol.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sim/sonar_presets.hpp"
#include "sonarmap/sim/trajectory.hpp"

namespace sonarmap {

struct Ping360EmulatorOptions {
  /// Bits per second of the link the replies travel (10 bits a byte); 0: no transfer time (UDP).
  unsigned baud = 115200;
  double sound_speed_m_s = 1500.0;  ///< the water's, m/s: a sample spans period × c / 2
  std::uint8_t device_id = 2;       ///< source id of its messages (the head of the shared logs: 2)
  ping_protocol::DeviceInformation identity{2, 67, 3, 3, 1, 0};
  ping_protocol::ProtocolVersion protocol{1, 1, 0, 0};
};

/// The head and echo model of a ping at `settings` (a device_data's fields; its data unused), for
/// water of `sound_speed_m_s`. From the sim presets (sonar_presets.hpp), the one nearest in range
/// on a log scale ("ping360-2m" below 3.16 m, "ping360-5m" below 15.8 m, "ping360" beyond: their
/// ringing, noise and mapping differ with range), then:
///  - range = samples × sample period × c / 2 in `samples` bins; the pulse's length from the
///    transmit duration, c · τ / 2 (the device_data records it: logs_pulse_length);
///  - the noise 10 log(τ/τ₀) lower for a pulse τ longer than the preset's τ₀ (the presets' rule:
///    the same electronics' noise against τ times the energy);
///  - speckle looks: the pulse's length in samples, 2–64 (the presets' rule);
///  - the gain folded into the A/D mapping: ad_low_db lower by 4 dB a gain step above the preset's
///    gain (0 for ping360-2m and -5m, 2 assumed for ping360) [L, A]: in the shared basin log, the
///    same bearings at 10 m gave 2.5 times the counts at gain 2 as at gain 0 (median ratio of
///    10 cm block means of 20–90 counts), 8 dB if the samples are proportional to the echo's
///    amplitude, so 4 dB a step;
///  - both beam widths scaled by 750 kHz / frequency (a fixed aperture's beam narrows with the
///    wavelength) [C].
SonarPreset ping360EchoModel(const ping_protocol::DeviceData& settings, double sound_speed_m_s);

/// The emulated head: Scene, trajectory and mounting as MsisBeamSimulator takes them.
class Ping360Emulator final : public HeadEmulator {
 public:
  /// @throws ValueError for an invalid scene, an empty trajectory, a mounting that is not rigid,
  ///         or a sound speed that is not positive and finite.
  Ping360Emulator(Scene scene, Trajectory trajectory, const Eigen::Isometry3d& sonar_to_body, std::uint64_t seed,
                  const Ping360EmulatorOptions& options = {});
  ~Ping360Emulator() override;
  Ping360Emulator(Ping360Emulator&&) noexcept;
  Ping360Emulator& operator=(Ping360Emulator&&) noexcept;

  std::vector<TimedBytes> receive(std::span<const std::uint8_t> bytes, double now_s) override;
  /// The auto-transmit pings the head has begun by `now_s`, each due when its samples are sent.
  std::vector<TimedBytes> poll(double now_s) override;
  std::size_t beamsSent() const override;
  /// "range 19.98 m (1200 samples of 888 ticks), gain 1, angle 133 grad, transmit 107 us, 750 kHz"
  /// (and ", auto-transmit 0..399 grad by 1" while it scans by itself).
  std::string settingsText() const override;
  /// The head's settings now (a device_data without samples).
  ping_protocol::DeviceData state() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
