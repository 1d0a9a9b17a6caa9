#pragma once
/// @file receiver.hpp
/// Private to the simulator: the head's receiver (steps 4–6 of msis_simulator.hpp): pulse,
/// time-varying gain, speckle, noise, self-reflection band and quantisation to 0…255.

#include <cstdint>
#include <optional>
#include <vector>

#include "random.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap::sim {

/// Bins the receiver sums per pulse: the pulse length in bins, rounded, at least 1.
int pulseBins(const MsisHeadOptions& head, const EchoModelOptions& echo);

/// Step 4 of msis_simulator.hpp: sets `pulse` (energy.size() values) to the energy of each bin
/// summed with the pulse_bins − 1 bins before it (never below 0).
void pulseSum(const std::vector<double>& energy, int pulse_bins, std::vector<double>& pulse);

/// The time-varying gain at `range_m` as a power factor: r² · 10^(2 α r / 10), α the absorption
/// the TVG compensates (20 log r + 2αr).
double tvgGain(const EchoModelOptions& echo, double range_m);

/// Turns received energy per range bin (BeamEchoTracer::trace) into one beam's intensities.
class Receiver {
 public:
  /// Precomputes the gain and the band for `head` and `echo`, which it copies.
  Receiver(const MsisHeadOptions& head, const EchoModelOptions& echo);

  /// @param energy       received energy per bin, head.bins values.
  /// @param random       the run's stream; takes 2 · (bins + speckle_looks − 1) draws (none
  ///                     without speckle), then the water scatterers' draws when there are any.
  /// @param intensities  set to head.bins values.
  /// @param reverberation_db  Scene::reverberation_db: the basin's diffuse reverberation after
  ///                     the gain, added from `reverberation_from_m` on under the noise's
  ///                     fluctuation (no extra draws); none when unset.
  void receive(const std::vector<double>& energy, Random& random, std::vector<std::uint8_t>& intensities,
               std::optional<double> reverberation_db = std::nullopt, double reverberation_from_m = 0.0);

  /// Echo level (dB) that quantises to `intensity` (the inverse of the AD mapping).
  double levelOf(double intensity) const;

 private:
  std::uint8_t quantise(double power) const;
  /// Sets `factors` (one per bin, mean 1) to the moving mean of speckle_looks exponential draws,
  /// or to 1 when speckle_looks is 0.
  void fluctuation(Random& random, std::vector<double>& factors);
  /// Sets `clutter` (one per bin) to the water scatterers' power after the gain
  /// (EchoModelOptions::water_scatterers_per_m); all 0 without scatterers, taking no draws.
  void waterScatterers(Random& random, std::vector<double>& clutter) const;

  MsisHeadOptions head_;
  EchoModelOptions echo_;
  int pulse_bins_ = 1;
  std::vector<double> gain_;                             // TVG per bin (power factor)
  std::vector<double> self_reflection_;                  // band power per bin, after the gain
  std::vector<double> pulse_, speckle_, noise_, clutter_, draws_;  // per-beam scratch
};

}  // namespace sonarmap::sim
