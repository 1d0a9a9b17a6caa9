/// @file receiver_model.cpp
/// The receiver: pulse, noise, floor and A/D mapping (see receiver_model.hpp).

#include "sonarmap/acoustics/receiver_model.hpp"

#include <algorithm>
#include <cmath>

#include "checks.hpp"
#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/propagation.hpp"

namespace sonarmap {

using acoustics_checks::nonNegative;
using acoustics_checks::positive;
using acoustics_checks::require;

void detail::throwInvalidReceiverScale(double ad_low_db, double ad_span_db) {
  require(std::isfinite(ad_low_db), "receiver scale: ad_low_db must be finite");
  require(positive(ad_span_db), "receiver scale: ad_span_db must be > 0", ad_span_db);
  throw ValueError("receiver scale: invalid");  // not reached: one of the checks above fails
}

namespace {

// The A/D mapping for a scale already validated (the public functions check it once).
double intensityOf(const ReceiverScale& scale, double level_db) {
  require(!std::isnan(level_db), "receiver scale: level_db is NaN");
  return 255.0 * (level_db - scale.ad_low_db) / scale.ad_span_db;
}

std::uint8_t countsOf(const ReceiverScale& scale, double level_db) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(intensityOf(scale, level_db), 0.0, 255.0)));
}

}  // namespace

double intensityOfLevel(const ReceiverScale& scale, double level_db) {
  scale.validate();
  return intensityOf(scale, level_db);
}

double levelOfIntensity(const ReceiverScale& scale, double intensity) {
  scale.validate();
  require(std::isfinite(intensity), "receiver scale: intensity must be finite");
  return scale.ad_low_db + intensity / 255.0 * scale.ad_span_db;
}

std::uint8_t countsOfLevel(const ReceiverScale& scale, double level_db) {
  scale.validate();
  return countsOf(scale, level_db);
}

std::uint8_t countsOfPower(const ReceiverScale& scale, double power) {
  scale.validate();
  if (!(power > 0.0)) return 0;
  return countsOf(scale, levelOfPower(power));
}

void ReceiverNoise::validate() const {
  require(std::isfinite(noise_level_db), "receiver noise: noise_level_db must be finite");
  require(nonNegative(tvg_absorption_db_per_m), "receiver noise: tvg_absorption_db_per_m must be >= 0",
          tvg_absorption_db_per_m);
}

double meanNoisePower(const ReceiverNoise& noise, double range_m) {
  noise.validate();
  require(positive(range_m), "receiver noise: range_m must be > 0", range_m);
  return powerOfLevel(noise.noise_level_db) * tvgGain(range_m, noise.tvg_absorption_db_per_m);
}

double receiverFloorPower(const ReceiverNoise& noise, const ReceiverScale& scale, double range_m) {
  scale.validate();
  return std::max(meanNoisePower(noise, range_m), powerOfLevel(scale.ad_low_db));
}

int pulseBins(double pulse_length_m, double bin_length_m) {
  require(positive(pulse_length_m), "receiver: pulse_length_m must be > 0", pulse_length_m);
  require(positive(bin_length_m), "receiver: bin_length_m must be > 0", bin_length_m);
  return std::max(1, static_cast<int>(std::lround(pulse_length_m / bin_length_m)));
}

void pulseSum(const std::vector<double>& energy, int pulse_bins, std::vector<double>& pulse) {
  require(pulse_bins >= 1, "receiver: pulse_bins must be >= 1", pulse_bins);
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
