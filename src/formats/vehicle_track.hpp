#pragma once
/// @file vehicle_track.hpp
/// Private to src/formats: a NavTrack joined from the separate attitude, position and depth
/// messages a vehicle's own log holds (vehicle_log_navigation.hpp), and depth from pressure.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/formats/vehicle_log_navigation.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::detail {

/// Attitude of body FRD in NED at one time: Z-Y-X Euler angles, radians.
struct AttitudeSample {
  double time_s = 0.0;
  double roll_rad = 0.0, pitch_rad = 0.0, yaw_rad = 0.0;
};

/// A position (NED, metres) or, in a depth series, a depth in z with x, y unused.
struct PositionSample {
  double time_s = 0.0;
  Eigen::Vector3d ned_m = Eigen::Vector3d::Zero();
};

/// Fixes at the attitude samples' times: position interpolated linearly in `positions` when it has
/// any, else x = y = 0 and z interpolated in `depths` when it has any, else 0. Samples with a
/// non-finite value are dropped; each series is sorted by time and keeps the first of equal times;
/// attitude samples outside the span of the series used give no fix.
NavTrack joinVehicleTrack(std::vector<AttitudeSample> attitude, std::vector<PositionSample> positions,
                          std::vector<PositionSample> depths);

/// Depth in metres below the surface of an absolute pressure in pascals: (p − surface) / (ρ g).
double depthOfPressure_m(double pressure_pa, const VehicleLogOptions& options);

/// @throws ValueError naming `function` unless the options are positive and finite.
void checkVehicleLogOptions(const VehicleLogOptions& options, const std::string& function);

/// "the navigation: attitude from A, position from P" words for a description.
std::string vehicleTrackWords(const std::string& attitude, const std::string& position, const std::string& depth);

}  // namespace sonarmap::detail
