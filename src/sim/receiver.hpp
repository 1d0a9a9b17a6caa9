#pragma once
/// @file receiver.hpp
/// Private to the simulator: the head's receiver (steps 4–6 of msis_simulator.hpp): pulse,
/// time-varying gain, speckle, noise, self-reflection band and quantisation to 0…255. The pulse
/// sum, the gain, the noise's mean and the A/D mapping are the acoustics layer's
/// (acoustics/receiver_model.hpp, propagation.hpp); the random draws, the self-reflection band,
/// the water scatterers and the blanking are the simulator's own.

#include <cstdint>
#include <optional>
#include <vector>

#include "random.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/sim/msis_simulator.hpp"

namespace sonarmap::sim {

/// Turns received energy per range bin (BeamEchoTracer::trace) into one beam's intensities.
class Receiver {
 public:
  /// Precomputes the gain and the band for `head` and `echo`, which it copies.
  Receiver(const MsisHeadOptions& head, const EchoModelOptions& echo);

  /// @param energy       received energy per bin, head.bins values.
  /// @param random       the run's stream; takes 2 · (bins + speckle_looks − 1) draws (none
  ///                     without speckle), then the water scatterers' draws when there are any,
  ///                     then one gaussian draw with a spread self-reflection band.
  /// @param intensities  set to head.bins values.
  /// @param reverberation_db  Scene::reverberation_db: the basin's diffuse reverberation after
  ///                     the gain, added from `reverberation_from_m` on under the noise's
  ///                     fluctuation (no extra draws); none when unset.
  void receive(const std::vector<double>& energy, Random& random, std::vector<std::uint8_t>& intensities,
               std::optional<double> reverberation_db = std::nullopt, double reverberation_from_m = 0.0);

 private:
  /// Sets `factors` (one per bin, mean 1) to the moving mean of speckle_looks exponential draws,
  /// or to 1 when speckle_looks is 0: marginally Gamma speckle of speckle_looks looks
  /// (acoustics/speckle.hpp), correlated over speckle_looks bins.
  void fluctuation(Random& random, std::vector<double>& factors);
  /// Sets `clutter` (one per bin) to the water scatterers' power after the gain
  /// (EchoModelOptions::water_scatterers_per_m); all 0 without scatterers, taking no draws.
  void waterScatterers(Random& random, std::vector<double>& clutter) const;
  /// This ping's self-reflection band's power per bin after the gain: self_reflection_, or with
  /// EchoModelOptions::self_reflection_spread_db its level shifted by one gaussian draw (its only draw).
  const std::vector<double>& selfReflection(Random& random);

  MsisHeadOptions head_;
  EchoModelOptions echo_;
  ReceiverScale scale_;
  int pulse_bins_ = 1;
  std::vector<double> gain_;                             // TVG per bin (power factor)
  std::vector<double> mean_noise_;                       // the noise's mean power per bin, after the gain
  std::vector<double> self_reflection_;                  // band power per bin, after the gain
  std::vector<double> self_reflection_db_;               // a dB taper's level per bin, its line past the end
  std::vector<double> band_;                             // this ping's band (a spread band)
  std::vector<double> pulse_, speckle_, noise_, clutter_, draws_;  // per-beam scratch
};

}  // namespace sonarmap::sim
