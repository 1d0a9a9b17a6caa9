#pragma once
/// @file ping360_settings.hpp
/// A Blue Robotics Ping360's settings in its own units (the fields of a `transducer` command) from
/// what a user asks (head_settings.hpp), by the rules of Blue Robotics' Ping Viewer
/// (`src/sensor/ping360.{h,cpp}`), and the head's limits and timings. Used by Ping360Driver and
/// Ping360Emulator. Angles are the head's: gradians 0–399, clockwise seen from above, bearing
/// 2π · angle / 400 in the sonar frame (beam.hpp, ping_protocol::ping360Beam).
///
/// Defaults, when a HeadSettings field is unset:
///  - range 20 m: a 2° beam is 0.7 m wide there (1.7 m at the rated 50 m), and a full turn takes
///    400 × (27 ms listening + 6 ms motor + 6 ms transfer) ≈ 16 s over Ethernet or at 2 MBd (31 s
///    at 50 m), 55 s at 115,200 Bd; the users of the shared logs mapped a basin at 10–20 m. Ping
///    Viewer's power-on 2 m is a bench range, too short to map from a vehicle.
///  - gain "normal" (1): the middle setting. In the shared basin log (10 m, the same bearings at
///    both settings) going from low to high multiplied the echoes' counts by ≈ 2.5 (echoes of
///    20–90 counts at low), bringing the strongest to saturation; low leaves weak returns near 0.
///    (The head boots at low.)
///  - step 1 gradian (0.9°), the head's finest, as Ping Viewer's default angular resolution.
///  - frequency 750 kHz, Ping Viewer's (the firmware boots at 740).
///  - full turns (HeadSettings' sector default).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sonarmap/devices/head_settings.hpp"

namespace sonarmap {

// ---- The head's limits and timings, each with its source ------------------------------------------
inline constexpr int kPing360GradiansPerTurn = 400;
inline constexpr double kPing360Tick_s = 25e-9;  ///< sample period unit (ping360.json)
/// Samples a ping: at most 1200 (Ping Viewer `_firmwareMaxNumberOfPoints`); json: 200–1200.
inline constexpr int kPing360MaxSamples = 1200;
inline constexpr int kPing360MinSamples = 200;
/// Sample period, 25 ns ticks: 80 (2 µs, Ping Viewer `_firmwareMinSamplePeriod`) to 40000 (json).
inline constexpr int kPing360MinSamplePeriodTicks = 80;
inline constexpr int kPing360MaxSamplePeriodTicks = 40000;
/// Transmit duration the firmware applies, µs: ≥ 5 and ≤ min(500, 64 sample periods) (Ping Viewer
/// `_firmwareMinTransmitDuration`, `_firmwareMaxTransmitDuration`, transmitDurationMax()); json 1–1000.
inline constexpr int kPing360MinTransmitDuration_us = 5;
inline constexpr int kPing360MaxTransmitDuration_us = 500;
inline constexpr int kPing360MinFrequency_khz = 500;  ///< ping360.json: 500–1000 kHz
inline constexpr int kPing360MaxFrequency_khz = 1000;
/// The motor turns 400 gradians in 2.4 s (Ping Viewer `_angularSpeedGradPerMs` = 400 / 2400).
inline constexpr double kPing360MotorTurn_s = 2.4;
/// Ping Viewer's other figure, "the motor takes 4 s to run a full circle": the driver's timeouts
/// use it, the slower of the two.
inline constexpr double kPing360SlowMotorTurn_s = 4.0;
/// The longest a transducer command may take to answer (ping360.json: "the command timeout should
/// be set to 4000 msec").
inline constexpr double kPing360MaxReply_s = 4.0;
/// Ranges the driver takes, metres: Blue Robotics' 0.75 m minimum to Ping Viewer's largest range
/// choice, 60 m.
inline constexpr double kPing360MinRange_m = 0.75;
inline constexpr double kPing360MaxRange_m = 60.0;
/// Step between pings, gradians: 1–10 (Ping Viewer's angular resolution; auto_transmit num_steps).
inline constexpr int kPing360MaxStepGradians = 10;
/// Sound speeds the driver takes, m/s (Ping Viewer offers 1450–1550; cold fresh water is 1403).
inline constexpr double kPing360MinSoundSpeed_m_s = 1400.0;
inline constexpr double kPing360MaxSoundSpeed_m_s = 1600.0;

/// Samples and sample period of a range scale.
struct Ping360Sampling {
  std::uint16_t samples = kPing360MaxSamples;
  std::uint16_t sample_period_ticks = kPing360MinSamplePeriodTicks;
  /// samples × sample period × c / 2, metres.
  double range_m(double sound_speed_m_s) const;
};

/// Ping Viewer's Ping360::set_range: 1200 samples, the sample period 2R / (N · c · 25 ns)
/// truncated to whole ticks (computed in single precision as Ping Viewer does); while it is under
/// 80 ticks, one sample fewer. So R = 20 m at 1500 m/s gives 1200 samples of 888 ticks (19.98 m),
/// 2 m gives 88 ticks (1.98 m), 0.75 m gives 500 samples of 80 ticks. Valid for the driver's range
/// and sound-speed bounds (callers check them).
Ping360Sampling ping360Sampling(double range_m, double sound_speed_m_s);

/// The longest transmit duration the firmware applies at a sample period: min(500 µs, 64 sample
/// periods), µs (Ping Viewer transmitDurationMax()).
int ping360MaxTransmitDuration_us(int sample_period_ticks);

/// Ping Viewer's automatic transmit duration ("per firmware engineer", adjustTransmitDuration):
/// round(8000 · R / c) µs for the range R of `sampling`, at least 2.5 sample periods, then within
/// [5 µs, ping360MaxTransmitDuration_us]: 107 µs at 20 m, 11 µs at 2 m, 267 µs at 50 m. (Ping
/// Viewer's step 2 divides a period in seconds by 1000 and so never applies; it would change
/// nothing from 0.75 m on, where the 5 µs floor covers it.)
int ping360TransmitDuration_us(const Ping360Sampling& sampling, double sound_speed_m_s);

/// A gain word as HeadSettings::gain takes it: "low", "normal" (or Ping Viewer's "medium"),
/// "high", "0", "1", "2" (any case) → 0, 1, 2.
/// @throws ValueError naming --gain and the allowed words.
int ping360GainSetting(const std::string& gain);
/// "low", "normal", "high" for 0, 1, 2 (else the number).
std::string ping360GainWord(int gain_setting);

/// The shortest way between two head angles, gradians 0–200.
int ping360AngleDistance(int from_grad, int to_grad);

/// What a Ping360Driver asks of the head, in its units, and the angles of its scan.
struct Ping360Settings {
  std::uint8_t gain_setting = 1;
  Ping360Sampling sampling;
  std::uint16_t transmit_duration_us = 0;
  std::uint16_t transmit_frequency_khz = 750;
  double sound_speed_m_s = 1500.0;
  int step_grad = 1;
  bool full_turns = true;
  /// Full turns: the first angle (the sector centre's). Sector: its first limit, counter-clockwise
  /// end: the sector runs clockwise from it over sector_steps × step_grad gradians.
  int first_grad = 0;
  int sector_steps = 0;  ///< sector: steps from one limit to the other (≥ 1)
  int center_grad = 0;   ///< the sector's centre as asked, rounded to a gradian
  /// What was rounded to the head's units and how, a line each for the user ("--step 1 degrees
  /// rounded to 1 gradian = 0.9 degrees ..."); Ping360Driver says them when it starts.
  std::vector<std::string> notes;

  double range_m() const { return sampling.range_m(sound_speed_m_s); }
  /// The angle of the scan's ping `index` (0 the first), gradians 0–399. Full turns: first + index
  /// × step, clockwise without end. Sector: from the first limit clockwise to the other and back,
  /// each limit pinged once per reversal (as Ping Viewer's sector scan): a period of 2 ·
  /// sector_steps pings.
  int angleOf(std::size_t index) const;
  /// "Ping360" and range_m, gain, sector_deg (360 for full turns), sector_center_deg, step_deg,
  /// frequency_khz, transmit_duration_us, sample_period_ns, samples, sound_speed_m_s.
  AppliedSettings applied() const;
};

/// The Ping360 settings of `settings`: defaults for unset fields (the file's comment), the range
/// by ping360Sampling, the transmit duration by ping360TransmitDuration_us, the step rounded to the
/// nearest whole gradian, at least 1 (a step that is not whole is said in `notes`: 1° gives
/// 1 gradian, 0.9°), a sector's limits centre ± its whole steps (first = centre − ⌊steps · step / 2⌋).
/// @throws ValueError naming the option (as `sonarmap live` spells it) and the allowed values: a
///         range outside 0.75–60 m; an unknown gain word; a step that is not above 0 or rounds to
///         more than 10 gradians (9.45° and up; 10 is Ping Viewer's coarsest and auto_transmit's
///         largest num_steps); a frequency outside 500–1000 kHz; a sound speed outside 1400–1600
///         m/s; a sector that is not finite, narrower than one step or wider than 360°; a centre that is
///         not finite.
Ping360Settings ping360Settings(const HeadSettings& settings);

}  // namespace sonarmap
