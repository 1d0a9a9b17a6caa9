/// @file vehicle_track.cpp
/// joinVehicleTrack, depthOfPressure_m (see vehicle_track.hpp).

#include "vehicle_track.hpp"

#include <algorithm>
#include <cmath>

#include "sonarmap/core/errors.hpp"

namespace sonarmap::detail {
namespace {

constexpr double kStandardGravity_m_s2 = 9.80665;

template <typename Sample, typename Finite>
void tidy(std::vector<Sample>& samples, Finite finite) {
  std::erase_if(samples, [&](const Sample& s) { return !std::isfinite(s.time_s) || !finite(s); });
  std::stable_sort(samples.begin(), samples.end(), [](const Sample& a, const Sample& b) { return a.time_s < b.time_s; });
  samples.erase(std::unique(samples.begin(), samples.end(),
                            [](const Sample& a, const Sample& b) { return a.time_s == b.time_s; }),
                samples.end());
}

/// The series' value at `time_s`, linear between its samples; nullopt outside its span.
std::optional<Eigen::Vector3d> interpolate(const std::vector<PositionSample>& series, double time_s) {
  if (series.empty() || time_s < series.front().time_s || time_s > series.back().time_s) return std::nullopt;
  const auto after = std::lower_bound(series.begin(), series.end(), time_s,
                                      [](const PositionSample& s, double t) { return s.time_s < t; });
  if (after->time_s == time_s) return after->ned_m;
  const PositionSample& before = *(after - 1);
  const double w = (time_s - before.time_s) / (after->time_s - before.time_s);
  return ((1.0 - w) * before.ned_m + w * after->ned_m).eval();
}

}  // namespace

NavTrack joinVehicleTrack(std::vector<AttitudeSample> attitude, std::vector<PositionSample> positions,
                          std::vector<PositionSample> depths) {
  tidy(attitude, [](const AttitudeSample& s) {
    return std::isfinite(s.roll_rad) && std::isfinite(s.pitch_rad) && std::isfinite(s.yaw_rad);
  });
  tidy(positions, [](const PositionSample& s) { return s.ned_m.allFinite(); });
  tidy(depths, [](const PositionSample& s) { return std::isfinite(s.ned_m.z()); });
  NavTrack track;
  track.reserve(attitude.size());
  for (const AttitudeSample& a : attitude) {
    NavSample fix;
    fix.time_s = a.time_s;
    fix.roll_rad = a.roll_rad;
    fix.pitch_rad = a.pitch_rad;
    fix.yaw_rad = a.yaw_rad;
    if (!positions.empty()) {
      const std::optional<Eigen::Vector3d> p = interpolate(positions, a.time_s);
      if (!p) continue;
      fix.position_ned_m = *p;
    } else if (!depths.empty()) {
      const std::optional<Eigen::Vector3d> d = interpolate(depths, a.time_s);
      if (!d) continue;
      fix.position_ned_m = Eigen::Vector3d(0.0, 0.0, d->z());
    }
    track.push_back(fix);
  }
  return track;
}

double depthOfPressure_m(double pressure_pa, const VehicleLogOptions& options) {
  return (pressure_pa - options.surface_pressure_pa) / (options.water_density_kg_m3 * kStandardGravity_m_s2);
}

void checkVehicleLogOptions(const VehicleLogOptions& options, const std::string& function) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(options.water_density_kg_m3) || !positive(options.surface_pressure_pa)) {
    throw ValueError(function + ": water density " + std::to_string(options.water_density_kg_m3) +
                     " kg/m^3 and surface pressure " + std::to_string(options.surface_pressure_pa) +
                     " Pa must be positive and finite");
  }
}

std::string vehicleTrackWords(const std::string& attitude, const std::string& position, const std::string& depth) {
  if (!position.empty()) return "attitude " + attitude + ", position " + position;
  if (!depth.empty()) return "attitude " + attitude + ", depth " + depth + ", no horizontal position (north, east 0)";
  return "attitude " + attitude + ", no position or depth (0, 0, 0)";
}

}  // namespace sonarmap::detail
