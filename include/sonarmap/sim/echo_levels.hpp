#pragma once
/// @file echo_levels.hpp
/// What a simulated head hears of each surface: the mean level of every scene primitive's direct
/// echo in each range bin of one beam, over the receiver's floor, in dB.
///
/// The echo follows steps 1, 2, 4 and 5 of msis_simulator.hpp (rays across the aperture with the
/// two-way beam pattern, Lambert backscatter, two-way spreading and absorption, the pulse, the
/// time-varying gain) without multipath, speckle, noise or quantisation. The floor of bin i is the
/// receiver's floor (acoustics/receiver_model.hpp, receiverFloorPower): the larger of the additive
/// noise's mean power after the gain (EchoModelOptions::noise_level_db) and the A/D converter's
/// lowest level (EchoModelOptions::ad_low_db: a weaker bin logs 0 however often it is looked at);
/// the scene's reverberation (Scene::reverberation_db) is not counted. A surface
/// whose echo stays below that floor in every bin it lies in leaves nothing in the log for a
/// detector to find: eval/heard_surface.hpp maps what lies above it, the oracle of what a mission
/// can map.

#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Per-primitive echo levels of one head in one scene (see the file's comment). Copies the scene
/// and the options.
class EchoLevels {
 public:
  /// @throws ValueError for invalid head or echo options (their validate()) or an invalid scene
  ///         (validateScene).
  EchoLevels(const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo);
  ~EchoLevels();
  EchoLevels(EchoLevels&&) noexcept;
  EchoLevels& operator=(EchoLevels&&) noexcept;

  /// Sets `levels_db` to one vector per scene primitive, in scene order, of head.bins values: that
  /// primitive's mean direct echo in bin i (range [i, i + 1) bin lengths) over the floor, dB;
  /// −infinity where it returns nothing. `sonar_to_map`: the head's pose (sonar frame, beam.hpp, to
  /// the map frame); `bearing_rad`: the beam's bearing in the sonar frame. Nothing is thrown.
  void levels(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
              std::vector<std::vector<double>>& levels_db) const;

  /// The floor of each bin after the gain, in the echo model's power units (head.bins values).
  const std::vector<double>& floorPower() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sonarmap
