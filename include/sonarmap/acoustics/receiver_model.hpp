#pragma once
/// @file receiver_model.hpp
/// An MSIS head's receiver: the pulse it sums over, the noise it adds, its time-varying gain and
/// the log-compressed A/D converter that turns an echo's power into intensity counts 0…255.
///
/// A/D mapping (the Tritech heads' ADlow / ADspan, the Ping360's gain setting): the receiver's
/// amplifier is logarithmic, so the counts are linear in the echo's level L = 10 log10 P dB (after
/// the TVG, propagation.hpp):
///     intensity = 255 (L − ad_low_db) / ad_span_db, rounded, clipped to 0…255;
/// a level at or below ad_low_db gives 0, one at or above ad_low_db + ad_span_db gives 255.
/// Noise: additive, of mean power noise_level_db before the gain (so noise_level_db after it at
/// 1 m), growing with the TVG as r² · 10^(2 α r / 10) (Urick, "Principles of Underwater Sound",
/// 3rd ed. 1983, ch. 2: the noise-limited sonar equation, noise through the receiver's gain).
/// The receiver's floor: what a bin cannot go below in the log, the larger of the mean noise
/// after the gain and the A/D's lowest level (a weaker echo logs 0 however often it is looked at).

#include <cmath>
#include <cstdint>
#include <vector>

namespace sonarmap {

namespace detail {
/// Throws ValueError naming the field of `scale` that is out of range or not finite.
[[noreturn]] void throwInvalidReceiverScale(double ad_low_db, double ad_span_db);
}  // namespace detail

/// The log-compressed A/D mapping (see the file's comment). No default head: set both fields.
struct ReceiverScale {
  double ad_low_db = 0.0;   ///< level that maps to intensity 0, dB, finite
  double ad_span_db = 0.0;  ///< level span that maps to 0…255, dB, > 0

  /// Inline: the simulator quantises every bin through a checked scale.
  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const {
    if (!(std::isfinite(ad_low_db) && std::isfinite(ad_span_db) && ad_span_db > 0.0)) {
      detail::throwInvalidReceiverScale(ad_low_db, ad_span_db);
    }
  }
};

/// The unrounded, unclipped intensity of a level: 255 (level_db − ad_low_db) / ad_span_db, counts
/// (±infinity for an infinite level).
/// @throws ValueError for an invalid scale or a NaN level.
double intensityOfLevel(const ReceiverScale& scale, double level_db);

/// The level an intensity stands for, the inverse of intensityOfLevel:
/// ad_low_db + intensity / 255 · ad_span_db, dB.
/// @throws ValueError for an invalid scale or a non-finite intensity.
double levelOfIntensity(const ReceiverScale& scale, double intensity);

/// The counts the A/D writes for a level: intensityOfLevel clipped to [0, 255], then rounded
/// (halves away from zero).
/// @throws ValueError for an invalid scale or a NaN level.
std::uint8_t countsOfLevel(const ReceiverScale& scale, double level_db);

/// The counts the A/D writes for a power (after the gain, in the units the levels are re):
/// countsOfLevel(10 log10 power), and 0 for a power that is not > 0 (NaN included).
/// @throws ValueError for an invalid scale.
std::uint8_t countsOfPower(const ReceiverScale& scale, double power);

/// The receiver's additive noise and the gain it goes through.
struct ReceiverNoise {
  double noise_level_db = 0.0;           ///< mean noise power before the gain, dB (its level at 1 m after it), finite
  double tvg_absorption_db_per_m = 0.0;  ///< α of the TVG (propagation.hpp), dB/m, ≥ 0

  /// @throws ValueError naming the field that is out of range or not finite.
  void validate() const;
};

/// The noise's mean power after the TVG at `range_m` (> 0): 10^(noise_level_db / 10) · tvgGain(r, α).
/// @throws ValueError for invalid noise or a range that is not > 0 and finite.
double meanNoisePower(const ReceiverNoise& noise, double range_m);

/// The receiver's floor at `range_m`: max(meanNoisePower, 10^(ad_low_db / 10)), in the same units.
/// @throws ValueError for invalid noise or scale, or a range that is not > 0 and finite.
double receiverFloorPower(const ReceiverNoise& noise, const ReceiverScale& scale, double range_m);

/// Range bins the receiver sums per pulse: the pulse's range extent over the bin length, rounded,
/// at least 1. A bin's echo is what arrived over the last pulse length (an echo from range r fills
/// [r, r + L)).
/// @throws ValueError when either length is not > 0 and finite.
int pulseBins(double pulse_length_m, double bin_length_m);

/// Sets `pulse` (energy.size() values) to the energy of each bin summed with the pulse_bins − 1
/// bins before it (a running sum; never below 0, which rounding of the running sum could give).
/// `energy`: received energy per range bin, any length.
/// @throws ValueError when pulse_bins < 1.
void pulseSum(const std::vector<double>& energy, int pulse_bins, std::vector<double>& pulse);

}  // namespace sonarmap
