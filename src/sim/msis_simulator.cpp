/// @file msis_simulator.cpp
/// The simulation run: options, the head's turn, poses, the navigation track (see msis_simulator.hpp).

#include "sonarmap/sim/msis_simulator.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "pose_checks.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/beam_simulator.hpp"

namespace sonarmap {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// A sector width within this of 2π is a full turn (degrees converted to radians may miss 2π by
/// an ulp or so).
constexpr double kSectorSlack_rad = 1e-9;

void require(bool valid, const std::string& what) {
  if (!valid) throw ValueError(what);
}

/// Fixes of the trajectory every 1 / rate_hz seconds from first_s until at least last_s.
NavTrack sampleTrajectory(const Trajectory& trajectory, double first_s, double last_s, double rate_hz) {
  NavTrack track;
  if (rate_hz <= 0.0) return track;
  const auto intervals = static_cast<std::size_t>(std::ceil((last_s - first_s) * rate_hz - 1e-9));
  for (std::size_t k = 0; k <= intervals; ++k) {
    const double time_s = first_s + static_cast<double>(k) / rate_hz;
    NavSample fix = trajectory(time_s);
    fix.time_s = time_s;
    track.push_back(fix);
  }
  return track;
}

}  // namespace

bool MsisHeadOptions::isSector() const { return sector_width_rad < kTwoPi - kSectorSlack_rad; }

std::size_t MsisHeadOptions::sectorSteps() const {
  return static_cast<std::size_t>(std::floor(sector_width_rad / step_rad + 1e-9));
}

std::size_t MsisHeadOptions::beamsPerTurn() const {
  return isSector() ? sectorSteps() + 1 : static_cast<std::size_t>(std::lround(kTwoPi / step_rad));
}

double MsisHeadOptions::bearingOf(std::size_t index) const {
  const double signed_step_rad = counter_clockwise ? -step_rad : step_rad;  // bearings count clockwise (beam.hpp)
  if (!isSector()) return sim::wrapBearing(start_bearing_rad + static_cast<double>(index) * signed_step_rad);
  const std::size_t steps = sectorSteps();
  const std::size_t pass = index / (steps + 1);
  const std::size_t along = index % (steps + 1);
  const std::size_t from_first_limit = pass % 2 == 0 ? along : steps - along;
  const double first_limit_rad = sector_center_rad - 0.5 * static_cast<double>(steps) * signed_step_rad;
  return sim::wrapBearing(first_limit_rad + static_cast<double>(from_first_limit) * signed_step_rad);
}

void MsisHeadOptions::validate() const {
  require(std::isfinite(step_rad) && step_rad > 0.0 && step_rad <= std::numbers::pi,
          "MSIS head: step_rad must be in (0, π], got " + std::to_string(step_rad));
  require(std::isfinite(horizontal_beam_width_rad) && horizontal_beam_width_rad > 0.0 &&
              horizontal_beam_width_rad < std::numbers::pi,
          "MSIS head: horizontal_beam_width_rad must be in (0, π), got " + std::to_string(horizontal_beam_width_rad));
  require(std::isfinite(vertical_beam_width_rad) && vertical_beam_width_rad > 0.0 &&
              vertical_beam_width_rad < std::numbers::pi,
          "MSIS head: vertical_beam_width_rad must be in (0, π), got " + std::to_string(vertical_beam_width_rad));
  require(std::isfinite(range_m) && range_m > 0.0, "MSIS head: range_m must be > 0, got " + std::to_string(range_m));
  require(bins >= 1, "MSIS head: bins must be ≥ 1, got " + std::to_string(bins));
  require(std::isfinite(beam_period_s) && beam_period_s > 0.0,
          "MSIS head: beam_period_s must be > 0, got " + std::to_string(beam_period_s));
  require(std::isfinite(start_bearing_rad), "MSIS head: start_bearing_rad must be finite");
  require(std::isfinite(sector_width_rad) && sector_width_rad > 0.0 && sector_width_rad <= kTwoPi + kSectorSlack_rad,
          "MSIS head: sector_width_rad must be in (0, 2π], got " + std::to_string(sector_width_rad));
  require(!isSector() || sector_width_rad >= step_rad * (1.0 - 1e-9),
          "MSIS head: a sector must hold at least one step: sector_width_rad " + std::to_string(sector_width_rad) +
              " < step_rad " + std::to_string(step_rad));
  require(std::isfinite(sector_center_rad), "MSIS head: sector_center_rad must be finite");
}

void ApertureAxis::validate(const char* axis) const {
  const std::string prefix = std::string("echo model, ") + axis + " aperture: ";
  require(rays >= 1, prefix + "rays must be ≥ 1, got " + std::to_string(rays));
  require(std::isfinite(extent) && extent > 0.0, prefix + "extent must be > 0");
  require(std::isfinite(exponent) && exponent > 0.0, prefix + "exponent must be > 0");
}

void EchoModelOptions::validate() const {
  auto finite = [](double value) { return std::isfinite(value); };
  horizontal.validate("horizontal");
  vertical.validate("vertical");
  require(finite(lambert_exponent) && lambert_exponent >= 1.0, "echo model: lambert_exponent must be ≥ 1");
  require(finite(absorption_db_per_m) && absorption_db_per_m >= 0.0, "echo model: absorption_db_per_m must be ≥ 0");
  require(finite(tvg_absorption_db_per_m) && tvg_absorption_db_per_m >= 0.0,
          "echo model: tvg_absorption_db_per_m must be ≥ 0");
  require(finite(pulse_length_m) && pulse_length_m > 0.0, "echo model: pulse_length_m must be > 0");
  require(speckle_looks >= 0, "echo model: speckle_looks must be ≥ 0");
  require(finite(water_scatterers_per_m) && water_scatterers_per_m >= 0.0,
          "echo model: water_scatterers_per_m must be ≥ 0");
  require(finite(water_scatterer_level_db) && water_scatterer_level_db > 0.0,
          "echo model: water_scatterer_level_db must be > 0");
  require(finite(noise_level_db) && finite(ad_low_db), "echo model: noise_level_db and ad_low_db must be finite");
  require(finite(ad_span_db) && ad_span_db > 0.0, "echo model: ad_span_db must be > 0");
  require(finite(blanking_m) && blanking_m >= 0.0, "echo model: blanking_m must be ≥ 0");
  require(finite(self_reflection_end_m) && self_reflection_end_m >= 0.0,
          "echo model: self_reflection_end_m must be ≥ 0");
  require(finite(self_reflection_intensity) && self_reflection_intensity >= 0.0 && self_reflection_intensity <= 255.0,
          "echo model: self_reflection_intensity must be in 0…255");
  require(finite(self_reflection_taper_m) && self_reflection_taper_m > 0.0,
          "echo model: self_reflection_taper_m must be > 0");
  require(finite(self_reflection_spread_db) && self_reflection_spread_db >= 0.0,
          "echo model: self_reflection_spread_db must be ≥ 0");
  require(finite(specular_share) && specular_share >= 0.0 && specular_share <= 1.0,
          "echo model: specular_share must be in [0, 1]");
  require(finite(glint_gain) && glint_gain >= 0.0, "echo model: glint_gain must be ≥ 0");
  require(finite(glint_width_rad) && glint_width_rad > 0.0, "echo model: glint_width_rad must be > 0");
  require(finite(sidelobe_level_db) && sidelobe_level_db <= 0.0, "echo model: sidelobe_level_db must be ≤ 0");
}

void MsisSimulationOptions::validate() const {
  head.validate();
  echo.validate();
  require(static_cast<bool>(trajectory), "MSIS simulation: the trajectory is empty");
  require(std::isfinite(start_time_s), "MSIS simulation: start_time_s must be finite");
  require(std::isfinite(nav_rate_hz) && nav_rate_hz >= 0.0, "MSIS simulation: nav_rate_hz must be ≥ 0");
  require(sim::isRigid(sonar_to_body),
          "MSIS simulation: sonar_to_body must be a finite rigid transform (rotation + translation)");
  dead_reckoning.validate();
}

MsisSimulation simulateMsis(const Scene& scene, const MsisSimulationOptions& options, const ProgressCallback& progress) {
  options.validate();
  MsisSimulation run;
  run.scene = scene;
  const MsisHeadOptions& head = options.head;
  MsisBeamSimulator simulator(scene, head, options.echo, options.trajectory, options.sonar_to_body, options.seed);
  const std::size_t beams = options.turns * head.beamsPerTurn();
  run.log.beams.reserve(beams);
  for (std::size_t i = 0; i < beams; ++i) {
    run.log.beams.push_back(
        simulator.simulate(options.start_time_s + static_cast<double>(i) * head.beam_period_s, head.bearingOf(i)));
    if (progress) progress(i + 1, beams);
  }
  if (beams > 0) {
    run.nav = sampleTrajectory(options.trajectory, run.log.beams.front().time_s, run.log.beams.back().time_s,
                               options.nav_rate_hz);
  }
  if (options.dead_reckoning.any() && !run.nav.empty()) run.dead_reckoning = deadReckon(run.nav, options.dead_reckoning);
  return run;
}

}  // namespace sonarmap
