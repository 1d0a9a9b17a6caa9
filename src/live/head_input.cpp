/// @file head_input.cpp
/// A head's link and protocol (see head_input.hpp).

#include "head_input.hpp"

#include "sonarmap/core/errors.hpp"
#include "sonarmap/devices/heads.hpp"
#include "sonarmap/formats/ping360_reader.hpp"

namespace sonarmap::live {

HeadInput::HeadInput(const std::string& spec, unsigned baud, LogFormat format, bool drive, const HeadSettings& settings)
    : link_(spec, baud), decoder_(format, {settings.sound_speed_m_s, 0.0}, spec), buffer_(65536) {
  if (drive && link_.speaksFirst()) driver_ = makeHeadDriver(format, settings, link_.serial() ? baud : 0);
  if (!driver_ && link_.networkClient() && (format == LogFormat::kPing360 || format == LogFormat::kSeaNet)) {
    registration_ = listenerRegistration(format);
  }
}

void HeadInput::send(const std::vector<std::uint8_t>& bytes) {
  if (!bytes.empty()) link_.write(bytes);
}

void HeadInput::start(double now_s) {
  if (!driver_) return;
  DriverOutput out = driver_->start(now_s);
  send(out.send);
  for (std::string& note : out.notes) notes_.push_back(std::move(note));
}

HeadRead HeadInput::read(double now_s) {
  HeadRead result;
  const long got = link_.read(buffer_);
  if (got == 0) {
    result.ended = true;
    return result;
  }
  if (got < 0) return result;
  const std::span<const std::uint8_t> bytes(buffer_.data(), static_cast<std::size_t>(got));
  if (bytes_ == 0 && isPingViewerLog(bytes)) {
    throw ValueError(link_.description() + " sends a Ping Viewer log, not the sonar's wire bytes: give the log's file "
                     "path to replay it as `map` reads it");
  }
  bytes_ += bytes.size();
  if (driver_) {
    DriverOutput out = driver_->receive(bytes, now_s);
    send(out.send);
    for (std::string& note : out.notes) notes_.push_back(std::move(note));
    result.beams = std::move(out.beams);
  } else {
    result.beams = decoder_.feed(bytes);
  }
  return result;
}

void HeadInput::poll(double now_s) {
  if (!driver_) {
    if (!registration_.empty() && now_s - last_registration_s_ >= kRegistrationPeriod_s) {
      last_registration_s_ = now_s;
      send(registration_);
    }
    return;
  }
  DriverOutput out = driver_->poll(now_s);
  send(out.send);
  for (std::string& note : out.notes) notes_.push_back(std::move(note));
}

void HeadInput::stop() {
  if (!driver_) return;
  try {
    send(driver_->stop());
  } catch (const FileError&) {  // the link is gone: the run ends anyway
  }
}

std::vector<Beam> HeadInput::finish() { return driver_ ? std::vector<Beam>{} : decoder_.finish(); }

std::vector<std::string> HeadInput::takeNotes() { return std::exchange(notes_, {}); }

std::vector<std::string> HeadInput::takeSkipReasons() { return driver_ ? std::vector<std::string>{} : decoder_.takeSkipReasons(); }

std::size_t HeadInput::skipped() const { return driver_ ? 0 : decoder_.skippedItems(); }

std::string HeadInput::device() const { return driver_ ? driver_->device() : decoder_.device(); }

AppliedSettings HeadInput::applied() const { return driver_ ? driver_->applied() : AppliedSettings{}; }

}  // namespace sonarmap::live
