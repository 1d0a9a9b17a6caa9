#pragma once
/// @file seanet_emulator.hpp
/// A Tritech SeaNet imaging head (Micron or SeaKing) answering its host from the simulator
/// (head_emulator.hpp, sim/beam_simulator.hpp), as the open drivers expect it to answer
/// (seanet_protocol.hpp names them):
///  - powered from the first call: an mtAlive every second (HeadInf: NoParams until a head
///    command; then SentCfg, InCentre, motor on, clockwise or not; in scan once asked for beams);
///    its head time counts ms since power-up. Bits as rock, RobDos and ENSTA number them (bit 0
///    InCentre … bit 7 SentCfg). mcgill reads the byte most significant bit first (bitstring), so
///    its "has config" is bit 0 and its "no params" bit 1; the head sets InCentre and leaves
///    Centred clear once it has parameters, so that both readings see the parameters in. After mtReBoot it forgets its parameters and its
///    next mtAlive comes 1 s later (a guess: how long a real head takes is not known here).
///  - mtSendVersion → mtVersionData, mtSendBBUser → mtBBUserData (the identity below).
///  - mtHeadCommand: applies range (NBins · ADInterval · 640 ns · 1500 m/s / 2), NBins, adc8on,
///    limits, step, cont and scanright, IGain, ADSpan, ADLow; answers at once with an mtAlive
///    saying the parameters are in (an assumption: the drivers wait for the next mtAlive anyway).
///    Gain and AD mapping fold into the echo model: ad_low_db moves by −(IGain − 84) · 80/210 dB
///    + (ADLow − 14) · 80/255 dB and ad_span_db by (ADSpan − 149) · 80/255 dB (at least 1 dB), so the
///    driver's default command (seanet_driver.hpp) gives the preset's own levels. A command with
///    the wrong size, no bins, more than 1500 (rock's limit), ADInterval or Step 0, or a range past
///    1638.3 m (RangeScale's limit) is ignored.
///  - mtSendData (with parameters): one mtHeadData at the head's next bearing. The head steps
///    itself as MsisHeadOptions::bearingOf does: continuous turns (cont set, or LeftLim = RightLim
///    as RobDos's driver sends for a full turn) from ahead, clockwise when scanright is set; else
///    back and forth across the sector between the limits, pinging at each limit and again there.
///    The reply is due after the beam before it (requests arriving while busy queue), plus the
///    motor's step (MoTime · 10 µs: assumed), the listening time (NBins · ADInterval · 640 ns) and
///    the packet's transfer (10 bits a byte at `baud`). 4-bit mode packs two bins a byte, high
///    nibble first. Without parameters mtSendData is ignored.
///  - anything else (other message types, bytes outside packets) is ignored; nothing throws.
///
/// Identities (mtVersionData CPU code by libminiking's table; mtBBUserData's long layout):
///  - `micron`: a Micron DST, one channel: CPU code 3 (675 kHz, the table's nearest to the
///    Micron's ≈700 kHz), serial 1001, device type 0x11 in mtHeadData (mcgill's check).
///  - `seaking-30`, `seaking-50`: a SeaKing imaging head with two channels (dual synthesiser):
///    CPU code 1 (325 kHz), serial 2001, device type 2 (the shared V4LOG).
/// Channel 2 of a SeaKing is reported but not simulated differently (the preset's 325 kHz echo).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/devices/head_emulator.hpp"
#include "sonarmap/sim/beam_simulator.hpp"

namespace sonarmap {

/// How the emulated head presents itself and talks.
struct SeaNetEmulatorOptions {
  std::string preset = "micron";  ///< "micron", "seaking-30", "seaking-50" (its identity)
  unsigned baud = 115200;         ///< the serial line's rate, for the transfer time (> 0)
  std::uint8_t node = 2;          ///< the head's node
  double alive_period_s = 1.0;    ///< between unprompted mtAlive messages (> 0)
};

/// One emulated SeaNet head over a beam simulator (built with the preset's head and echo options:
/// those are the levels of the default command).
class SeaNetEmulator : public HeadEmulator {
 public:
  /// @throws ValueError for an unknown preset (naming the known ones), a baud rate of 0 or an
  ///         alive period that is not > 0.
  SeaNetEmulator(MsisBeamSimulator simulator, SeaNetEmulatorOptions options);
  ~SeaNetEmulator() override;
  SeaNetEmulator(SeaNetEmulator&&) noexcept;
  SeaNetEmulator& operator=(SeaNetEmulator&&) noexcept;

  std::vector<TimedBytes> receive(std::span<const std::uint8_t> bytes, double now_s) override;
  std::vector<TimedBytes> poll(double now_s) override;
  std::size_t beamsSent() const override;
  std::string settingsText() const override;

  /// Whether the head has parameters (a head command since power-up or the last reboot).
  bool hasParameters() const;
  /// Packets of each kind received: mtReBoot, mtHeadCommand, mtSendData.
  std::size_t reboots() const;
  std::size_t headCommands() const;
  std::size_t dataRequests() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
