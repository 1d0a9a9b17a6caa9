/// @file receiver_model.cpp
/// The receiver: pulse, noise, floor and A/D mapping (see receiver_model.hpp).

#include "sonarmap/acoustics/receiver_model.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

void require(bool valid, const std::string& what) {
  if (!valid) throw ValueError(what);
}

}  // namespace

void ReceiverScale::validate() const {
  require(std::isfinite(ad_low_db), "receiver scale: ad_low_db must be finite");
  require(std::isfinite(ad_span_db) && ad_span_db > 0.0,
          "receiver scale: ad_span_db must be > 0, got " + std::to_string(ad_span_db));
}

double intensityOfLevel(const ReceiverScale& scale, double level_db) {
  scale.validate();
  require(!std::isnan(level_db), "receiver scale: level_db is NaN");
  return 255.0 * (level_db - scale.ad_low_db) / scale.ad_span_db;
}

double levelOfIntensity(const ReceiverScale& scale, double intensity) {
  scale.validate();
  require(std::isfinite(intensity), "receiver scale: intensity must be finite");
  return scale.ad_low_db + intensity / 255.0 * scale.ad_span_db;
}

std::uint8_t countsOfLevel(const ReceiverScale& scale, double level_db) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(intensityOfLevel(scale, level_db), 0.0, 255.0)));
}

std::uint8_t countsOfPower(const ReceiverScale& scale, double power) {
  scale.validate();
  if (!(power > 0.0)) return 0;
  return countsOfLevel(scale, levelOfPower(power));
}

void ReceiverNoise::validate() const {
  require(std::isfinite(noise_level_db), "receiver noise: noise_level_db must be finite");
  require(std::isfinite(tvg_absorption_db_per_m) && tvg_absorption_db_per_m >= 0.0,
          "receiver noise: tvg_absorption_db_per_m must be >= 0, got " + std::to_string(tvg_absorption_db_per_m));
}

double meanNoisePower(const ReceiverNoise& noise, double range_m) {
  noise.validate();
  require(std::isfinite(range_m) && range_m > 0.0, "receiver noise: range_m must be > 0, got " + std::to_string(range_m));
  return powerOfLevel(noise.noise_level_db) * tvgGain(range_m, noise.tvg_absorption_db_per_m);
}

double receiverFloorPower(const ReceiverNoise& noise, const ReceiverScale& scale, double range_m) {
  scale.validate();
  return std::max(meanNoisePower(noise, range_m), powerOfLevel(scale.ad_low_db));
}

int pulseBins(double pulse_length_m, double bin_length_m) {
  require(std::isfinite(pulse_length_m) && pulse_length_m > 0.0,
          "receiver: pulse_length_m must be > 0, got " + std::to_string(pulse_length_m));
  require(std::isfinite(bin_length_m) && bin_length_m > 0.0,
          "receiver: bin_length_m must be > 0, got " + std::to_string(bin_length_m));
  return std::max(1, static_cast<int>(std::lround(pulse_length_m / bin_length_m)));
}

void pulseSum(const std::vector<double>& energy, int pulse_bins, std::vector<double>& pulse) {
  require(pulse_bins >= 1, "receiver: pulse_bins must be >= 1, got " + std::to_string(pulse_bins));
  const auto bins = static_cast<std::size_t>(pulse_bins);
  pulse.assign(energy.size(), 0.0);
  double window = 0.0;  // a running sum
  for (std::size_t i = 0; i < energy.size(); ++i) {
    window += energy[i];
    if (i >= bins) window -= energy[i - bins];
    pulse[i] = std::max(window, 0.0);
  }
}

}  // namespace sonarmap
