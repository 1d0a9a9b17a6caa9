#include "odometry_options.hpp"

#include "help_groups.hpp"

#include <cmath>
#include <numbers>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {

bool OdometryArgs::stated() const {
  return nav_class != "auto" || scale_sigma_pct || heading_sigma_deg || velocity_noise_mps ||
         gyro_walk_deg_per_sqrt_s || max_speed_mps || max_turn_rate_deg_s;
}

void addOdometryOptions(CLI::App& cmd, OdometryArgs& args) {
  std::string classes;
  for (const std::string& name : navigationClasses()) classes += (classes.empty() ? "" : " | ") + name;
  cmd.add_option("--nav-class", args.nav_class, "How far --slam trusts the navigation: auto | " + classes)
      ->capture_default_str()
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--nav-scale-sigma", [&args](double value) { args.scale_sigma_pct = value; },
                                   "1-sigma distance travelled error, PERCENT >= 0")
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--nav-heading-sigma", [&args](double value) { args.heading_sigma_deg = value; },
                                   "1-sigma heading error, DEGREES >= 0")
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--nav-velocity-noise", [&args](double value) { args.velocity_noise_mps = value; },
                                   "1-sigma noise of each velocity reading, M/S >= 0")
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--nav-gyro-walk", [&args](double value) { args.gyro_walk_deg_per_sqrt_s = value; },
                                   "Heading random walk, DEGREES/sqrt(s) >= 0")
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--max-speed", [&args](double value) { args.max_speed_mps = value; },
                                   "Vehicle's top speed without a navigated position, M/S > 0 (2)")
      ->group(help_group::kLocalization);
  cmd.add_option_function<double>("--max-turn-rate", [&args](double value) { args.max_turn_rate_deg_s = value; },
                                   "Vehicle's top turn rate without --nav, DEGREES/s > 0 (30)")
      ->group(help_group::kLocalization);
}

OdometryNoise toOdometryNoise(const OdometryArgs& args, const NavTrack& track) {
  OdometryNoise noise = odometryNoiseOf(args.nav_class == "auto" ? navigationClassOf(track) : args.nav_class);
  // A noise may be 0 (a perfect sensor); a limit may not (a vehicle that cannot move).
  const auto set = [](const std::optional<double>& given, double unit, double& field, const char* flag,
                      const char* units, bool limit = false) {
    if (!given) return;
    if (!(std::isfinite(*given) && (limit ? *given > 0.0 : *given >= 0.0))) {
      throw ValueError(std::string(flag) + " expects " + units + (limit ? " > 0" : " >= 0"));
    }
    field = *given * unit;
  };
  constexpr double kDegree = std::numbers::pi / 180.0;
  set(args.scale_sigma_pct, 0.01, noise.scale_sigma, "--nav-scale-sigma", "PERCENT");
  set(args.heading_sigma_deg, kDegree, noise.heading_sigma_rad, "--nav-heading-sigma", "DEGREES");
  set(args.velocity_noise_mps, 1.0, noise.velocity_noise_mps, "--nav-velocity-noise", "M/S");
  set(args.gyro_walk_deg_per_sqrt_s, kDegree, noise.gyro_walk_rad_per_sqrt_s, "--nav-gyro-walk", "DEGREES/sqrt(s)");
  set(args.max_speed_mps, 1.0, noise.max_speed_mps, "--max-speed", "M/S", true);
  set(args.max_turn_rate_deg_s, kDegree, noise.max_turn_rate_radps, "--max-turn-rate", "DEGREES/s", true);
  noise.validate();
  return noise;
}

void checkOdometryArgs(const OdometryArgs& args, bool slam) {
  if (args.stated() && !slam) {
    throw ValueError("--nav-class, --nav-* and --max-* describe the navigation for --slam: give --slam");
  }
  toOdometryNoise(args);
}

SlamOptions toSlamOptions(const OdometryArgs& args, const NavTrack& track) {
  SlamOptions slam;
  slam.forming.odometry = toOdometryNoise(args, track);
  return slam;
}

}  // namespace sonarmap::cli
