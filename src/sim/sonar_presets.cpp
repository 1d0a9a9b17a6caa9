/// @file sonar_presets.cpp
/// The heads of sonar_presets.hpp (each value's source and reasoning are given there).

#include "sonarmap/sim/sonar_presets.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kGradian = std::numbers::pi / 200.0;

/// What every preset but the Micron shares: 400 beams a turn; a flat-topped vertical pattern
/// sampled every W / 60 over ±0.65 W and a Gaussian horizontal one over ±W; TVG compensating the
/// water's absorption.
SonarPreset newPreset(std::string name, std::string description, double horizontal_beam_width_deg,
                      double vertical_beam_width_deg, int horizontal_rays, double absorption_db_per_m) {
  SonarPreset preset;
  preset.name = std::move(name);
  preset.description = std::move(description);
  preset.head.step_rad = 0.9 * kDegree;
  preset.head.horizontal_beam_width_rad = horizontal_beam_width_deg * kDegree;
  preset.head.vertical_beam_width_rad = vertical_beam_width_deg * kDegree;
  preset.echo.horizontal = {horizontal_rays, 2.0, 2.0};
  preset.echo.vertical = {78, 1.3, 8.0};
  preset.echo.absorption_db_per_m = absorption_db_per_m;
  preset.echo.tvg_absorption_db_per_m = absorption_db_per_m;
  return preset;
}

SonarPreset micron() {
  return {"micron", "Tritech Micron (CRAS log), 700 kHz, 5 m, 399 bins, 3 x 35 deg", MsisHeadOptions{},
          EchoModelOptions{}};
}

/// The Tritech SeaKing at 325 kHz with the SeaNet log's AD mapping and near field; what changes
/// with the range scale is passed in.
SonarPreset seaKing(std::string name, double range_m, int bins, double beam_period_s, double pulse_length_m,
                    double noise_level_db, int horizontal_rays) {
  SonarPreset preset = newPreset(std::move(name),
                                 "Tritech SeaKing, 325 kHz, " + std::to_string(static_cast<int>(range_m)) + " m, " +
                                     std::to_string(bins) + " bins, 3 x 40 deg",
                                 3.0, 40.0, horizontal_rays, 0.08);
  preset.head.range_m = range_m;
  preset.head.bins = bins;
  preset.head.beam_period_s = beam_period_s;
  EchoModelOptions& echo = preset.echo;
  echo.pulse_length_m = pulse_length_m;
  echo.speckle_looks = 2;
  echo.noise_level_db = noise_level_db;
  echo.ad_low_db = -38.0;
  echo.ad_span_db = 47.0;
  echo.blanking_m = 0.1;
  echo.self_reflection_end_m = 0.3;
  echo.self_reflection_intensity = 120.0;
  echo.self_reflection_taper_m = 1.0;
  return preset;
}

/// The Blue Robotics Ping360 at 750 kHz, 1200 samples a ping, 1 gradian steps; what changes with
/// the range scale and the gain is passed in.
SonarPreset ping360(std::string name, double range_m, double beam_period_s, double pulse_length_m, double noise_level_db,
                    double ad_low_db, double ringing_end_m, double ringing_intensity, double ringing_taper_m,
                    bool ringing_taper_db) {
  const int range_cm = static_cast<int>(std::lround(range_m * 100.0));
  const std::string range_text = range_cm % 100 == 0 ? std::to_string(range_cm / 100) : std::to_string(range_m);
  SonarPreset preset = newPreset(std::move(name),
                                 "Blue Robotics Ping360, 750 kHz, " + range_text + " m, 1200 samples, 2 x 25 deg", 2.0,
                                 25.0, 7, 0.22);
  preset.head.step_rad = 1.0 * kGradian;
  preset.head.logs_pulse_length = true;  // device_data's transmit_duration
  preset.head.range_m = range_m;
  preset.head.bins = 1200;
  preset.head.beam_period_s = beam_period_s;
  EchoModelOptions& echo = preset.echo;
  echo.pulse_length_m = pulse_length_m;
  echo.speckle_looks = 5;
  echo.noise_level_db = noise_level_db;
  echo.ad_low_db = ad_low_db;
  echo.ad_span_db = 60.0;
  echo.blanking_m = 0.0;
  echo.self_reflection_end_m = ringing_end_m;
  echo.self_reflection_intensity = ringing_intensity;
  echo.self_reflection_taper_m = ringing_taper_m;
  echo.self_reflection_taper_db = ringing_taper_db;
  return preset;
}

SonarPreset imagenex881a() {
  SonarPreset preset = newPreset("imagenex-881a", "Imagenex 881A-like, 675 kHz, 20 m, 500 samples, 1.8 x 20 deg",
                                 1.8, 20.0, 5, 0.19);
  preset.head.range_m = 20.0;
  preset.head.bins = 500;
  preset.head.beam_period_s = 0.075;
  EchoModelOptions& echo = preset.echo;
  echo.pulse_length_m = 0.06;
  echo.speckle_looks = 2;
  echo.noise_level_db = -66.0;
  echo.ad_low_db = -30.0;
  echo.ad_span_db = 40.0;
  echo.blanking_m = 0.05;
  echo.self_reflection_end_m = 0.15;
  echo.self_reflection_intensity = 60.0;
  echo.self_reflection_taper_m = 0.05;
  return preset;
}

}  // namespace

std::vector<std::string> sonarPresetNames() {
  return {"micron", "seaking-30", "seaking-50", "ping360", "ping360-2m", "ping360-5m", "imagenex-881a"};
}

SonarPreset sonarPreset(std::string_view name) {
  if (name == "micron") return micron();
  if (name == "seaking-30") return seaKing("seaking-30", 30.0, 300, 0.070, 0.10, -69.5, 7);
  if (name == "seaking-50") return seaKing("seaking-50", 50.0, 800, 0.140, 0.15, -71.3, 9);
  if (name == "ping360") return ping360("ping360", 50.0, 0.083, 0.20, -99.0, -55.0, 0.5, 230.0, 0.5, false);
  if (name == "ping360-2m") return ping360("ping360-2m", 2.0, 0.040, 0.008, -50.0, -40.0, 0.07, 250.0, 0.28, true);
  if (name == "ping360-5m") return ping360("ping360-5m", 5.0, 0.043, 0.020, -60.0, -40.0, 0.10, 250.0, 0.30, true);
  if (name == "imagenex-881a") return imagenex881a();
  std::string known;
  for (const std::string& candidate : sonarPresetNames()) known += (known.empty() ? "" : ", ") + candidate;
  throw ValueError("unknown sonar preset '" + std::string(name) + "', expected one of: " + known);
}

}  // namespace sonarmap
