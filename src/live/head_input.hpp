#pragma once
/// @file head_input.hpp
/// Private to src/live: a head's link and its protocol: a driver (devices/heads.hpp) that commands
/// the head, or a decoder of what the head is made to send by another program (wire_stream.hpp).
/// Listening over a link to a server (BlueOS's ping proxy, `bridges`, at udp://HOST:9092), it
/// registers with a harmless request every kRegistrationPeriod_s (listenerRegistration): the
/// server sends the head's bytes only to clients it heard from in the last 10 s.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sonarmap/devices/head_driver.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/formats/wire_stream.hpp"
#include "sonarmap/live/byte_link.hpp"

namespace sonarmap::live {

/// What one read from the head gave.
struct HeadRead {
  std::vector<Beam> beams;  ///< in order, times unset
  bool ended = false;       ///< the link's stream ended
};

class HeadInput {
 public:
  /// Opens `spec`; drives the head when `drive` and the link can speak first (else listens:
  /// ByteLink::speaksFirst).
  /// @throws as ByteLink, and makeHeadDriver for settings the head cannot take.
  HeadInput(const std::string& spec, unsigned baud, LogFormat format, bool drive, const HeadSettings& settings);

  int fd() const { return link_.fd(); }
  const std::string& description() const { return link_.description(); }
  bool driving() const { return driver_ != nullptr; }

  /// Sends the driver's first bytes.
  void start(double now_s);
  /// Reads what the link has and hands it to the driver or decoder; sends the driver's replies.
  /// @throws FileError on a link error; ValueError when the link sends a Ping Viewer log.
  HeadRead read(double now_s);
  /// The driver's repeats of overdue commands; listening to a server, the registration when due
  /// (the first at once).
  void poll(double now_s);
  static constexpr double kRegistrationPeriod_s = 5.0;
  /// Tells the head to stop, where its protocol has a way (a write error is ignored: the run ends).
  void stop();
  /// The end of the stream: the decoder's last beams.
  std::vector<Beam> finish();

  /// Lines for the user since the last call (driver notes), handed over.
  std::vector<std::string> takeNotes();
  /// Skip lines since the last call, handed over.
  std::vector<std::string> takeSkipReasons();
  std::size_t bytes() const { return bytes_; }
  std::size_t skipped() const;
  std::string device() const;
  AppliedSettings applied() const;

 private:
  void send(const std::vector<std::uint8_t>& bytes);

  ByteLink link_;
  std::unique_ptr<HeadDriver> driver_;
  WireStreamDecoder decoder_;
  std::vector<std::string> notes_;
  std::size_t bytes_ = 0;
  std::vector<std::uint8_t> buffer_;
  std::vector<std::uint8_t> registration_;  ///< listening to a server: sent every kRegistrationPeriod_s
  double last_registration_s_ = -1e300;
};

}  // namespace sonarmap::live
