// sonarmap_seabed_levels: where a flat seabed's echo sits against each head's noise, by the sonar
// equation the simulator follows (acoustics/sonar_equation.hpp, asked through sim/sonar_equation.hpp),
// for the quay3d missions' geometry (sim/missions.hpp). Not a test.
//
//   sonarmap_seabed_levels
//
// For each preset: the seabed 2 m below the head at the Micron's 5 m scale (scaled with the range),
// level (lawnmower) and tilted 25° down (tilted loop, the beam looking the way it tilts); the echo
// power of a bin at 40, 60, 80 and 100 % of the range against the mean noise power after the TVG
// (meanNoisePower: noise_level_db + 20 log r + 2 α r), in dB, for the quay3d seabed (reflectivity 0.5, Lambert
// μ = ρ / π = −8.0 dB) and for Mackenzie's (1961) deep-sea Lambert constant μ = −27 dB. Ranges
// where the seabed lies outside the echo model's rays are left out.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "sonarmap/sim/sonar_equation.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

int main() {
  using namespace sonarmap;
  const double mackenzie = std::numbers::pi * std::pow(10.0, -27.0 / 10.0);  // ρ = π μ
  std::printf("| head | geometry | range (m) | noise (dB) | seabed ρ 0.5: echo − noise (dB) | μ −27 dB: echo − noise (dB) |\n");
  std::printf("|---|---|---:|---:|---:|---:|\n");
  for (const std::string& name : sonarPresetNames()) {
    const SonarPreset preset = sonarPreset(name);
    const double reach_m = preset.head.range_m;
    const double altitude_m = 2.0 * reach_m / 5.0;
    for (const double tilt_deg : {0.0, 25.0}) {
      for (const double share : {0.4, 0.6, 0.8, 1.0}) {
        const double range_m = share * reach_m;
        const double noise_db = 10.0 * std::log10(meanNoisePower(preset.echo, range_m));
        const double tilt_rad = tilt_deg * std::numbers::pi / 180.0;
        auto relative = [&](double reflectivity) -> std::string {
          const double power = flatSeabedEchoPower(preset.head, preset.echo, altitude_m, reflectivity, range_m, tilt_rad);
          if (!(power > 0.0)) return "outside the beam";
          char text[32];
          std::snprintf(text, sizeof text, "%.1f", 10.0 * std::log10(power) - noise_db);
          return text;
        };
        const std::string strong = relative(0.5);
        if (strong == "outside the beam") continue;
        std::printf("| %s | %s, seabed %.1f m below | %.1f | %.1f | %s | %s |\n", name.c_str(),
                    tilt_deg == 0.0 ? "level" : "tilted 25°", altitude_m, range_m, noise_db, strong.c_str(),
                    relative(mackenzie).c_str());
      }
    }
  }
  return 0;
}
