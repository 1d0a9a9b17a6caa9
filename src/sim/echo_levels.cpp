/// @file echo_levels.cpp
/// Per-primitive echo levels over the receiver's floor (see echo_levels.hpp).

#include "sonarmap/sim/echo_levels.hpp"

#include <limits>

#include "beam_echo.hpp"
#include "sonarmap/acoustics/decibels.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/sim/acoustic_parameters.hpp"

namespace sonarmap {

struct EchoLevels::Impl {
  Impl(const Scene& scene_in, const MsisHeadOptions& head_in, const EchoModelOptions& echo_in)
      : scene(scene_in),
        head(head_in),
        echo(echo_in),
        tracer(scene, head, echo),
        pulse_bins(pulseBins(echo.pulse_length_m, head.binLength_m())) {
    const ReceiverNoise noise = receiverNoiseOf(echo);
    const ReceiverScale scale = receiverScaleOf(echo);
    gain.resize(static_cast<std::size_t>(head.bins));
    floor.resize(gain.size());
    for (std::size_t i = 0; i < gain.size(); ++i) {
      const double range_m = (static_cast<double>(i) + 0.5) * head.binLength_m();  // as the receiver's gain
      gain[i] = tvgGain(range_m, echo.tvg_absorption_db_per_m);
      floor[i] = receiverFloorPower(noise, scale, range_m);
    }
  }
  Scene scene;  // the tracer keeps references to these three
  MsisHeadOptions head;
  EchoModelOptions echo;
  sim::BeamEchoTracer tracer;
  int pulse_bins = 1;
  std::vector<double> gain;   // TVG per bin (power factor)
  std::vector<double> floor;  // per bin, after the gain
};

namespace {

const Scene& validated(const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo) {
  head.validate();
  echo.validate();
  validateScene(scene);
  return scene;
}

}  // namespace

EchoLevels::EchoLevels(const Scene& scene, const MsisHeadOptions& head, const EchoModelOptions& echo)
    : impl_(std::make_unique<Impl>(validated(scene, head, echo), head, echo)) {}

EchoLevels::~EchoLevels() = default;
EchoLevels::EchoLevels(EchoLevels&&) noexcept = default;
EchoLevels& EchoLevels::operator=(EchoLevels&&) noexcept = default;

const std::vector<double>& EchoLevels::floorPower() const { return impl_->floor; }

void EchoLevels::levels(const Eigen::Isometry3d& sonar_to_map, double bearing_rad,
                        std::vector<std::vector<double>>& levels_db) const {
  impl_->tracer.traceDirect(sonar_to_map, bearing_rad, levels_db);
  std::vector<double> summed;
  for (std::vector<double>& bins : levels_db) {
    pulseSum(bins, impl_->pulse_bins, summed);
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const double power = summed[i] * impl_->gain[i];
      bins[i] = power > 0.0 ? levelOfPower(power / impl_->floor[i]) : -std::numeric_limits<double>::infinity();
    }
  }
}

}  // namespace sonarmap
