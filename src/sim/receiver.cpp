/// @file receiver.cpp
/// Pulse, gain, speckle, noise, self-reflection band and quantisation (see receiver.hpp).

#include "receiver.hpp"

#include <algorithm>
#include <cmath>

#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/sim/acoustic_parameters.hpp"

namespace sonarmap::sim {

Receiver::Receiver(const MsisHeadOptions& head, const EchoModelOptions& echo)
    : head_(head), echo_(echo), scale_(receiverScaleOf(echo)) {
  const double bin_m = head.binLength_m();
  const ReceiverNoise noise = receiverNoiseOf(echo);
  pulse_bins_ = pulseBins(echo.pulse_length_m, bin_m);
  const auto bins = static_cast<std::size_t>(head.bins);
  gain_.resize(bins);
  mean_noise_.resize(bins);
  self_reflection_.assign(bins, 0.0);
  self_reflection_db_.assign(bins, -INFINITY);
  const double band_power = powerOfLevel(levelOfIntensity(scale_, echo.self_reflection_intensity));
  for (std::size_t i = 0; i < bins; ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * bin_m;
    gain_[i] = tvgGain(range_m, echo.tvg_absorption_db_per_m);
    mean_noise_[i] = meanNoisePower(noise, range_m);
    const double past_end_m = range_m - echo.self_reflection_end_m;
    if (echo.self_reflection_end_m > 0.0 && echo.self_reflection_intensity > 0.0 &&
        past_end_m < echo.self_reflection_taper_m) {
      const double remaining = std::clamp(1.0 - past_end_m / echo.self_reflection_taper_m, 0.0, 1.0);
      self_reflection_[i] =
          echo.self_reflection_taper_db
              ? (remaining > 0.0 ? powerOfLevel(levelOfIntensity(scale_, echo.self_reflection_intensity * remaining)) : 0.0)
              : band_power * remaining;
    }
    // The dB taper's line carried on past its end: a ping that rings louder rings longer.
    if (echo.self_reflection_taper_db && echo.self_reflection_end_m > 0.0 && echo.self_reflection_intensity > 0.0) {
      const double remaining = std::min(1.0, 1.0 - past_end_m / echo.self_reflection_taper_m);
      self_reflection_db_[i] = levelOfIntensity(scale_, echo.self_reflection_intensity * remaining);
    }
  }
}

const std::vector<double>& Receiver::selfReflection(Random& random) {
  if (!(echo_.self_reflection_spread_db > 0.0)) return self_reflection_;
  const double shift_db = echo_.self_reflection_spread_db * random.gaussian();
  band_.resize(self_reflection_.size());
  for (std::size_t i = 0; i < band_.size(); ++i) {
    if (echo_.self_reflection_taper_db) {  // the level's line, 0 where it falls below the A/D's floor
      const double level_db = self_reflection_db_[i] + shift_db;
      band_[i] = level_db > scale_.ad_low_db ? powerOfLevel(level_db) : 0.0;
    } else {
      band_[i] = self_reflection_[i] * powerOfLevel(shift_db);
    }
  }
  return band_;
}

void Receiver::fluctuation(Random& random, std::vector<double>& factors) {
  const auto bins = static_cast<std::size_t>(head_.bins);
  const auto looks = static_cast<std::size_t>(std::max(echo_.speckle_looks, 0));
  factors.assign(bins, 1.0);
  if (looks == 0) return;
  draws_.resize(bins + looks - 1);
  for (double& draw : draws_) draw = random.exponential();
  double sum = 0.0;  // running sum of the window draws_[i, i + looks)
  for (std::size_t k = 0; k + 1 < looks; ++k) sum += draws_[k];
  for (std::size_t i = 0; i < bins; ++i) {
    sum += draws_[i + looks - 1];
    factors[i] = sum / static_cast<double>(looks);
    sum -= draws_[i];
  }
}

void Receiver::waterScatterers(Random& random, std::vector<double>& clutter) const {
  const std::size_t bins = gain_.size();
  clutter.assign(bins, 0.0);
  if (!(echo_.water_scatterers_per_m > 0.0)) return;
  const double bin_m = head_.binLength_m();
  const double reach_m = static_cast<double>(bins) * bin_m;
  // A Poisson process along the beam: exponential gaps of mean 1 / density.
  for (double range_m = random.exponential() / echo_.water_scatterers_per_m; range_m < reach_m;
       range_m += random.exponential() / echo_.water_scatterers_per_m) {
    const auto first = static_cast<std::size_t>(range_m / bin_m);
    const double level_db = echo_.water_scatterer_level_db * random.exponential();
    const double speckle = random.exponential();
    const std::size_t last = std::min(bins, first + static_cast<std::size_t>(pulse_bins_));
    for (std::size_t i = first; i < last; ++i) clutter[i] += mean_noise_[i] * powerOfLevel(level_db) * speckle;
  }
}

void Receiver::receive(const std::vector<double>& energy, Random& random, std::vector<std::uint8_t>& intensities,
                       std::optional<double> reverberation_db, double reverberation_from_m) {
  const std::size_t bins = energy.size();
  pulseSum(energy, pulse_bins_, pulse_);
  fluctuation(random, speckle_);
  fluctuation(random, noise_);
  waterScatterers(random, clutter_);
  const std::vector<double>& band = selfReflection(random);
  const double reverberation_power = reverberation_db ? powerOfLevel(*reverberation_db) : 0.0;
  const double bin_m = head_.binLength_m();
  intensities.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) {
    const bool reverberant = reverberation_db && (static_cast<double>(i) + 0.5) * bin_m >= reverberation_from_m;
    const double background = mean_noise_[i] + (reverberant ? reverberation_power : 0.0);
    const double power = (pulse_[i] * gain_[i] + band[i]) * speckle_[i] + background * noise_[i] + clutter_[i];
    const bool blanked = (static_cast<double>(i) + 0.5) * bin_m < echo_.blanking_m;
    intensities[i] = blanked ? 0 : countsOfPower(scale_, power);
  }
}

}  // namespace sonarmap::sim
