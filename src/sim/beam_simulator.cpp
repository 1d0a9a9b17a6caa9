/// @file beam_simulator.cpp
/// One simulated beam at a commanded time and bearing (see beam_simulator.hpp); the steps are
/// msis_simulator.hpp's.

#include "sonarmap/sim/beam_simulator.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "beam_echo.hpp"
#include "pose_checks.hpp"
#include "random.hpp"
#include "receiver.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {

/// The tracer keeps references to the scene, head and echo options: they live here, and the
/// tracer and receiver are rebuilt when the settings change.
struct MsisBeamSimulator::State {
  State(Scene scene_in, const MsisHeadOptions& head_in, const EchoModelOptions& echo_in, Trajectory trajectory_in,
        const Eigen::Isometry3d& mounting, std::uint64_t seed)
      : scene(std::move(scene_in)), head(head_in), echo(echo_in), trajectory(std::move(trajectory_in)),
        sonar_to_body(mounting), random(seed) {
    rebuild();
  }
  void rebuild() {
    tracer.emplace(scene, head, echo);
    receiver.emplace(head, echo);
  }

  Scene scene;
  MsisHeadOptions head;
  EchoModelOptions echo;
  Trajectory trajectory;
  Eigen::Isometry3d sonar_to_body;
  sim::Random random;
  std::optional<sim::BeamEchoTracer> tracer;
  std::optional<sim::Receiver> receiver;
  std::vector<double> energy;
};

MsisBeamSimulator::MsisBeamSimulator(Scene scene, const MsisHeadOptions& head, const EchoModelOptions& echo,
                                     Trajectory trajectory, const Eigen::Isometry3d& sonar_to_body, std::uint64_t seed) {
  head.validate();
  echo.validate();
  validateScene(scene);
  if (!trajectory) throw ValueError("MSIS beam simulator: the trajectory is empty");
  if (!sim::isRigid(sonar_to_body)) {
    throw ValueError("MSIS beam simulator: sonar_to_body must be a finite rigid transform (rotation + translation)");
  }
  state_ = std::make_unique<State>(std::move(scene), head, echo, std::move(trajectory), sonar_to_body, seed);
}

MsisBeamSimulator::~MsisBeamSimulator() = default;
MsisBeamSimulator::MsisBeamSimulator(MsisBeamSimulator&&) noexcept = default;
MsisBeamSimulator& MsisBeamSimulator::operator=(MsisBeamSimulator&&) noexcept = default;

Beam MsisBeamSimulator::simulate(double time_s, double bearing_rad) {
  if (!std::isfinite(time_s) || !std::isfinite(bearing_rad)) {
    throw ValueError("MSIS beam simulator: time " + std::to_string(time_s) + " s and bearing " +
                     std::to_string(bearing_rad) + " rad must be finite");
  }
  State& s = *state_;
  Beam beam;
  beam.time_s = time_s;
  beam.bearing_rad = sim::wrapBearing(bearing_rad);
  beam.bin_length_m = s.head.binLength_m();
  if (s.head.logs_pulse_length) beam.pulse_length_m = s.echo.pulse_length_m;
  const Eigen::Isometry3d sonar_to_map = sonarToMap(pose(time_s), s.sonar_to_body);
  s.tracer->trace(sonar_to_map, beam.bearing_rad, s.energy);
  double reverberation_from_m = s.head.range_m;  // from the first surface on the beam's axis
  if (s.scene.reverberation_db) {
    const Eigen::Vector3d axis =
        sonar_to_map.linear() * Eigen::Vector3d(std::cos(beam.bearing_rad), std::sin(beam.bearing_rad), 0.0);
    const std::optional<SceneHit> hit = firstHit(s.scene, sonar_to_map.translation(), axis, s.head.range_m);
    if (hit) reverberation_from_m = hit->surface.range_m;
  }
  s.receiver->receive(s.energy, s.random, beam.intensities, s.scene.reverberation_db, reverberation_from_m);
  return beam;
}

void MsisBeamSimulator::setHead(const MsisHeadOptions& head, const EchoModelOptions& echo) {
  head.validate();
  echo.validate();
  state_->head = head;
  state_->echo = echo;
  state_->rebuild();
}

const MsisHeadOptions& MsisBeamSimulator::head() const { return state_->head; }
const EchoModelOptions& MsisBeamSimulator::echo() const { return state_->echo; }
const Scene& MsisBeamSimulator::scene() const { return state_->scene; }

NavSample MsisBeamSimulator::pose(double time_s) const {
  NavSample fix = state_->trajectory(time_s);
  fix.time_s = time_s;
  return fix;
}

}  // namespace sonarmap
