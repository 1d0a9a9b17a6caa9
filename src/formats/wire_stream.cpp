/// @file wire_stream.cpp
/// WireStreamDecoder: raw SeaNet / Ping360 bytes fed in chunks → beams (see wire_stream.hpp).

#include "sonarmap/formats/wire_stream.hpp"

#include <optional>
#include <utility>

#include "sonarmap/core/errors.hpp"
#include "frame_scanner.hpp"
#include "reader_support.hpp"
#include "wire_protocols.hpp"

namespace sonarmap {

struct WireStreamDecoder::State {
  double beam_interval_s = 0.0;
  std::function<std::string(std::size_t)> where = [](std::size_t offset) { return "byte " + std::to_string(offset); };
  detail::Ping360Messages sink;  ///< beams and skip lines of the last call (beam_ends: Ping360 only)
  std::optional<detail::FrameStream> frames;
  std::size_t beams = 0;
  bool finished = false;

  /// The beams the last call decoded, timed, handed over.
  std::vector<Beam> take() {
    std::vector<Beam> beams_out = std::move(sink.log.beams);
    sink.log.beams.clear();
    sink.beam_ends.clear();
    for (Beam& beam : beams_out) beam.time_s = static_cast<double>(beams++) * beam_interval_s;
    return beams_out;
  }
};

WireStreamDecoder::WireStreamDecoder(LogFormat format, const CaptureOptions& options, std::string source)
    : state_(std::make_unique<State>()) {
  detail::checkSoundSpeed(options.sound_speed_m_s);
  detail::checkBeamInterval(options.beam_interval_s);
  state_->beam_interval_s = options.beam_interval_s;
  SonarLog& log = state_->sink.log;
  switch (format) {
    case LogFormat::kSeaNet:
      state_->frames.emplace(detail::seaNetFrameScan(source, options.sound_speed_m_s, log), source, log);
      break;
    case LogFormat::kPing360:
      state_->frames.emplace(detail::ping360FrameScan(source, options.sound_speed_m_s, state_->where, state_->sink),
                             source, log);
      break;
    default:
      throw ValueError("WireStreamDecoder: format '" + std::string(logFormatName(format)) +
                       "' is not a wire stream, expected seanet or ping360");
  }
}

WireStreamDecoder::~WireStreamDecoder() = default;
WireStreamDecoder::WireStreamDecoder(WireStreamDecoder&&) noexcept = default;
WireStreamDecoder& WireStreamDecoder::operator=(WireStreamDecoder&&) noexcept = default;

std::vector<Beam> WireStreamDecoder::feed(std::span<const std::uint8_t> bytes) {
  if (state_->finished) throw ValueError("WireStreamDecoder: bytes fed after finish()");
  state_->frames->feed(bytes);
  return state_->take();
}

std::vector<Beam> WireStreamDecoder::finish() {
  if (state_->finished) return {};
  state_->finished = true;
  state_->frames->finish();
  return state_->take();
}

std::size_t WireStreamDecoder::bytesFed() const { return state_->frames->bytesFed(); }
std::size_t WireStreamDecoder::beamsDecoded() const { return state_->beams; }
std::string WireStreamDecoder::device() const { return state_->sink.device; }
std::size_t WireStreamDecoder::skippedItems() const { return state_->sink.log.skipped_beams; }

std::vector<std::string> WireStreamDecoder::takeSkipReasons() {
  std::vector<std::string> reasons = std::move(state_->sink.log.skip_reasons);
  state_->sink.log.skip_reasons.clear();
  return reasons;
}

SonarLog WireStreamDecoder::decodeAll(std::span<const std::uint8_t> bytes) {
  SonarLog log;
  log.beams = feed(bytes);
  std::vector<Beam> last = finish();
  log.beams.insert(log.beams.end(), std::make_move_iterator(last.begin()), std::make_move_iterator(last.end()));
  log.skipped_beams = skippedItems();
  log.skip_reasons = takeSkipReasons();
  log.sonar = device();
  return log;
}

}  // namespace sonarmap
