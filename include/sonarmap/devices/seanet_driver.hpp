#pragma once
/// @file seanet_driver.hpp
/// The host's side of a Tritech SeaNet imaging head (Micron, SeaKing) as a state machine without
/// I/O (head_driver.hpp), the conversation of the open drivers (seanet_protocol.hpp names them):
///
///  1. mtReBoot (mcgill, RobDos, rock), then wait for the head's mtAlive (it sends one a second);
///     no mtAlive for 5 s: mtReBoot again.
///  2. mtSendVersion → mtVersionData (RobDos repeats it every second until answered; so here).
///  3. mtSendBBUser → mtBBUserData (rock's isFullDuplex, ENSTA's iSonar; mcgill and RobDos skip
///     it): it says whether the head has two channels. Repeated every second; after 3 tries
///     without an answer the driver goes on without it (a note says so).
///  4. mtHeadCommand with the settings (below), then wait for an mtAlive whose HeadInf says the
///     parameters are in (NoParams clear, SentCfg set: mcgill's open(), ENSTA's "ready"). None
///     within 5 s, or one still saying NoParams 2 s after the command: the command again (RobDos
///     re-configures after 5 s).
///  5. One mtSendData per beam, the next sent when the mtHeadData of the last one arrives: one
///     request in flight, as all four drivers read do (a Micron answers one mtHeadData per
///     mtSendData; rock also reads a "full duplex" flag from mtBBUserData but still waits for each
///     reply, and no driver read keeps two requests in flight, so neither does this one). A reply
///     overdue by 1 s + twice the listening time: mtSendData again (mcgill waits 1 s, RobDos
///     1.5 s); 5 overdue in a row: the head command again (mcgill).
///  At any time, an mtAlive saying NoParams while scanning (the head rebooted or lost power), or an
///  mtHeadData whose head status says the motor lost sync (mcgill): the head command again.
///  stop() returns mtReBoot, as mcgill's close() does ("to clear the sonar of all parameters"):
///  the head forgets its parameters and stops its motor. SeaNet also has mtStopAlive (66), which
///  only silences the head's mtAlive messages, and HdCtrl motoff/txoff in a head command; neither
///  is sent. After stop() the driver sends nothing.
///
/// Settings (HeadSettings, physical units) → mtHeadCommand, every value rounded to the head's unit
/// and listed, with its unit, in applied():
///  - range_m (default 10 m, mcgill's default): RangeScale = round(10 · range) dm, (0, 1638.3] m.
///  - gain: percent as SeaNet Pro shows it, "0" … "100" or "40%" (default 40%, rock's MicronConfig
///    and Tritech's advice quoted there): IGain = round(2.1 · percent) on 0…210 (rock and mcgill
///    send gain × 210), both channels. ADSpan 149 and ADLow 14 (47 dB and 4.4 dB above 0 on
///    SeaNet's 80 dB scale) are fixed: SeaNet Pro's values in ../shared/data/seanet_sector_target
///    .V4LOG.
///  - sector: 2π (default) turns continuously (HdCtrl cont, limits 0 and 6399 as rock sends
///    them); less scans a sector: LeftLim = 3200 + round((centre − width/2) · 6400/2π) and
///    RightLim = 3200 + round((centre + width/2) · 6400/2π), modulo 6400 (ahead is 3200, the
///    mtHeadData decoder's convention). The width must hold one step.
///  - step_rad (default 1.8°, SeaNet's "Low", mcgill's and RobDos's default): rounded to whole
///    1/16 gradians (0.05625°), 1…255; the drivers name 32, 16, 8, 4 Low, Medium, High, Ultimate
///    (1.8°, 0.9°, 0.45°, 0.225°).
///  - bins (SeaNetDriverOptions, default 400: mcgill's): NBins; ADInterval = round(2 · range /
///    (sound speed · bins) / 640 ns) (RobDos; mcgill rounds up to even), ≥ 5 (the smallest an open
///    driver uses, 640 ns × 5 = 3.2 µs) and ≤ 65535; bins 1…1500 (rock's limit).
///  - frequency_khz: a head whose mtBBUserData says it has two channels (dual synthesiser) uses
///    the channel nearest: channel 1 at 325 kHz or channel 2 at 675 kHz (HdCtrl chan2), the
///    frequencies SeaNet Pro's commands set (TxN, RxN: RobDos's template, the V4LOG's TxN). A
///    single-channel head keeps its own frequency (mtVersionData's CPU code, libminiking's table);
///    a request more than 5% from it is ignored with a note. Unset: channel 1.
///  - sound_speed_m_s (1000…2000 m/s): converts range to ADInterval and back (the head knows no
///    sound speed).
///  Fixed fields, as the drivers agree: HdCtrl adc8on, scanright, raw, hasmot, replyASL (0x2305
///  sector, 0x2307 continuous: mcgill's default, the V4LOG's 0x230D without invert); head type 2;
///  V3BParams 0x1D with the V3B block repeating ADSpan, ADLow, IGain; TxN/RxN for 325 and 675 kHz;
///  TxPulseLen 25 + 2.5 · range µs (rock's profiler; 40 µs at 6 m as in RobDos's template); Slope
///  90 and 125 (SeaNet Pro); MoTime 25 (every driver); MaxADBuf 1000; Lockout 100 µs; MinorAxisDir
///  1600; MajorAxisPan 1; Ctl2 and ScanZ 0.
///
/// Packets not sent by the head's node (the host's own commands echoed on a half-duplex RS-485
/// line, another node) are ignored. Beams come from the mtHeadData decoder (seanet_protocol.hpp, decodeHeadData): bearings as
/// seanet_capture.hpp documents them, bin length = ADInterval · 640 ns · sound speed / 2.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/devices/head_driver.hpp"
#include "sonarmap/devices/head_settings.hpp"

namespace sonarmap {

/// What a SeaNet driver is asked (settings in physical units) and how it talks.
struct SeaNetDriverOptions {
  HeadSettings settings;
  std::optional<int> bins;          ///< bins per beam (NBins); default 400
  std::uint8_t head_node = 2;       ///< the head's node (2 for an imaging head)
  /// The 4-byte time of each mtSendData, ms since midnight (mcgill sends the local time of day;
  /// rock and RobDos send 0). Default: the UTC time of day from the system clock.
  std::function<std::uint32_t()> time_of_day_ms;
};

/// Drives one SeaNet imaging head.
class SeaNetDriver : public HeadDriver {
 public:
  /// @throws ValueError naming the option and its allowed values for a setting out of range
  ///         (range_m, gain, sector, step_rad, bins, frequency_khz, sound_speed_m_s).
  explicit SeaNetDriver(SeaNetDriverOptions options);
  ~SeaNetDriver() override;
  SeaNetDriver(SeaNetDriver&&) noexcept;
  SeaNetDriver& operator=(SeaNetDriver&&) noexcept;

  DriverOutput start(double now_s) override;
  DriverOutput receive(std::span<const std::uint8_t> bytes, double now_s) override;
  DriverOutput poll(double now_s) override;
  std::vector<std::uint8_t> stop() override;
  AppliedSettings applied() const override;
  std::string device() const override;
  bool heard() const override;

  /// Whether the head confirmed its parameters and the driver is asking for beams.
  bool scanning() const;
  /// mtHeadCommand packets sent so far (the first one and every repeat).
  int headCommandsSent() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
