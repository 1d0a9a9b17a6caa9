#pragma once
/// @file wire_stream.hpp
/// Decoding a raw sonar wire stream as its bytes arrive (a serial port, a UDP or TCP socket): the
/// live side of the raw capture readers. The readers of whole captures (parseSeaNetCapture,
/// parsePing360Stream) are this decoder fed the whole buffer, then finished: bytes fed in chunks of
/// any size give the same beams and the same skip lines as the whole capture read at once.
///
/// Protocols and the conversion of head settings to beams: seanet_capture.hpp (Tritech SeaNet
/// mtHeadData packets) and ping360_reader.hpp (Blue Robotics ping-protocol device_data /
/// auto_device_data; a raw stream, not a Ping Viewer log).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sonarmap/formats/capture_options.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Beams out of a raw SeaNet or Ping360 byte stream fed in chunks.
class WireStreamDecoder {
 public:
  /// @param format   LogFormat::kSeaNet or LogFormat::kPing360 (a raw ping-protocol stream).
  /// @param options  sound speed (m/s) for the bin lengths; beam i gets time_s = i ×
  ///                 options.beam_interval_s (the protocols carry no clock: a live caller
  ///                 stamps beams with their arrival instead).
  /// @param source   names the stream in skip lines ("SOURCE: byte 120 to byte 130: ...").
  /// @throws ValueError for another format, a sound speed that is not positive and finite, or a
  ///         beam interval that is negative or not finite.
  explicit WireStreamDecoder(LogFormat format, const CaptureOptions& options = {}, std::string source = "stream");
  ~WireStreamDecoder();
  WireStreamDecoder(WireStreamDecoder&&) noexcept;
  WireStreamDecoder& operator=(WireStreamDecoder&&) noexcept;

  /// The stream's next bytes. Returns the beams whose frames they complete, in stream order; a
  /// frame not yet complete (or a candidate start the next bytes will decide) is kept for the next
  /// call. Noise, other messages and bad frames are counted (skippedItems) with one line each.
  /// Never throws for any bytes (only std::bad_alloc); @throws ValueError after finish().
  std::vector<Beam> feed(std::span<const std::uint8_t> bytes);
  /// The end of the stream: a frame cut short and the last run of noise become skip lines; beams
  /// of frames found in the bytes that were kept are returned. Idempotent (later calls return none).
  std::vector<Beam> finish();

  /// Bytes fed so far.
  std::size_t bytesFed() const;
  /// Beams returned so far.
  std::size_t beamsDecoded() const;
  /// What the stream said of its device so far (a Ping360's device_information: "Ping360 (firmware
  /// 3.1.1)"); empty when nothing.
  std::string device() const;
  /// Items skipped so far (as SonarLog::skipped_beams): runs of noise, other messages, frames cut
  /// short, device data out of range.
  std::size_t skippedItems() const;
  /// The skip lines not taken yet (as SonarLog::skip_reasons), handed over and forgotten, so a
  /// stream that runs for days does not keep them all.
  std::vector<std::string> takeSkipReasons();

  /// Feeds `bytes` at once, then finishes: the beams (timed as the constructor says), skipped
  /// count, skip lines and device (SonarLog::sonar) of the whole stream. Returns an empty log when it holds no beam.
  /// @throws ValueError after finish().
  SonarLog decodeAll(std::span<const std::uint8_t> bytes);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
