#pragma once
/// @file beam_simulator.hpp
/// The MSIS simulator (msis_simulator.hpp) one beam at a time, at the time and bearing a caller
/// asks for, with head settings that may change between beams: what a head emulator needs to
/// answer a command (a Ping360 `transducer` message names the angle, range and gain of the one
/// beam it wants; a SeaNet head steps itself after each `mtSendData`). simulateMsis is a loop over
/// it, so a beam here is the beam simulateMsis writes for the same time, bearing, settings and
/// place in the random stream.

#include <cstdint>
#include <memory>

#include <Eigen/Geometry>

#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/scene.hpp"
#include "sonarmap/sim/trajectory.hpp"
#include "sonarmap/sonar/beam.hpp"

namespace sonarmap {

/// Simulates single beams of one head in one scene from a vehicle on a trajectory.
class MsisBeamSimulator {
 public:
  /// @param scene          the scene (map frame), copied.
  /// @param head           range_m, bins, beam widths; its step, period and sector are not used
  ///                       (the caller chooses each beam's bearing and time).
  /// @param echo           the echo model (levels in dB re a perfect reflector filling the beam).
  /// @param trajectory     the vehicle's pose (NED, body FRD) at a time, seconds.
  /// @param sonar_to_body  the sonar's mounting: sonar frame → body frame (FRD).
  /// @param seed           seed of the speckle and noise (msis_simulator.hpp, "Randomness").
  /// @throws ValueError for invalid head or echo options, an invalid scene, an empty trajectory or
  ///         a mounting that is not a finite rigid transform.
  MsisBeamSimulator(Scene scene, const MsisHeadOptions& head, const EchoModelOptions& echo, Trajectory trajectory,
                    const Eigen::Isometry3d& sonar_to_body, std::uint64_t seed);
  ~MsisBeamSimulator();
  MsisBeamSimulator(MsisBeamSimulator&&) noexcept;
  MsisBeamSimulator& operator=(MsisBeamSimulator&&) noexcept;

  /// The beam at `bearing_rad` (sonar frame, radians, wrapped to [0, 2π)) at `time_s`, from the
  /// trajectory's pose then: head().bins intensities of head().binLength_m(), its pulse length
  /// set when head().logs_pulse_length. Takes the random draws of one beam (msis_simulator.hpp).
  /// @throws ValueError when `time_s` or `bearing_rad` is not finite.
  Beam simulate(double time_s, double bearing_rad);

  /// New settings for the beams after this call (a head command changed the range, the bins or
  /// the gain): the random stream goes on where it was.
  /// @throws ValueError for invalid options (nothing changes then).
  void setHead(const MsisHeadOptions& head, const EchoModelOptions& echo);

  const MsisHeadOptions& head() const;
  const EchoModelOptions& echo() const;
  const Scene& scene() const;
  /// The vehicle's pose at `time_s` (the trajectory's, with its time set to `time_s`).
  NavSample pose(double time_s) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sonarmap
