// The head options of `live` (see head_options.hpp).

#include "head_options.hpp"

#include <cmath>
#include <numbers>

#include "help_groups.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::cli {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

}  // namespace

void addHeadOptions(CLI::App& cmd, HeadArgs& args) {
  cmd.add_option("--range", args.range_m, "METRES: the range scale the head is set to")->group(help_group::kHead);
  cmd.add_option("--gain", args.gain, "Ping360: low|normal|high (0|1|2); SeaNet: PERCENT")->group(help_group::kHead);
  cmd.add_option("--sector", args.sector_deg, "DEGREES scanned, (0, 360]; 360: continuous turns")
      ->capture_default_str()
      ->group(help_group::kHead);
  cmd.add_option("--sector-center", args.sector_center_deg, "DEGREES: the sector's centre, clockwise from ahead")
      ->capture_default_str()
      ->group(help_group::kHead);
  cmd.add_option("--step", args.step_deg, "DEGREES between beams (Ping360: 0.9 x N; SeaNet: 0.45 x N)")
      ->group(help_group::kHead);
  cmd.add_option("--frequency", args.frequency_khz, "KHZ: the transmit frequency, where the head has a choice")
      ->group(help_group::kHead);
  cmd.add_option("--sound-speed", args.sound_speed_m_s, "M/S: the speed of sound for ranges and times")
      ->capture_default_str()
      ->group(help_group::kHead);
  cmd.add_flag("--listen-only", args.listen_only, "Send the head nothing: another program drives it")
      ->group(help_group::kHead);
}

HeadSettings toHeadSettings(const HeadArgs& args) {
  HeadSettings settings;
  if (args.range_m && !(std::isfinite(*args.range_m) && *args.range_m > 0.0)) {
    throw ValueError("--range must be > 0 metres");
  }
  if (!(std::isfinite(args.sector_deg) && args.sector_deg > 0.0 && args.sector_deg <= 360.0)) {
    throw ValueError("--sector must be in (0, 360] degrees");
  }
  if (!std::isfinite(args.sector_center_deg)) throw ValueError("--sector-center must be finite");
  if (args.step_deg && !(std::isfinite(*args.step_deg) && *args.step_deg > 0.0 && *args.step_deg <= 180.0)) {
    throw ValueError("--step must be in (0, 180] degrees");
  }
  if (args.frequency_khz && !(std::isfinite(*args.frequency_khz) && *args.frequency_khz > 0.0)) {
    throw ValueError("--frequency must be > 0 kHz");
  }
  if (!(std::isfinite(args.sound_speed_m_s) && args.sound_speed_m_s >= 1300.0 && args.sound_speed_m_s <= 1700.0)) {
    throw ValueError("--sound-speed must be within 1300 .. 1700 m/s (water)");
  }
  settings.range_m = args.range_m;
  if (!args.gain.empty()) settings.gain = args.gain;
  settings.sector_width_rad = args.sector_deg >= 360.0 ? 2.0 * std::numbers::pi : args.sector_deg * kRadPerDeg;
  settings.sector_center_rad = args.sector_center_deg * kRadPerDeg;
  if (args.step_deg) settings.step_rad = *args.step_deg * kRadPerDeg;
  settings.frequency_khz = args.frequency_khz;
  settings.sound_speed_m_s = args.sound_speed_m_s;
  return settings;
}

bool anyHeadSetting(const HeadArgs& args) {
  return args.range_m || !args.gain.empty() || args.sector_deg != 360.0 || args.sector_center_deg != 0.0 ||
         args.step_deg || args.frequency_khz;
}

}  // namespace sonarmap::cli
