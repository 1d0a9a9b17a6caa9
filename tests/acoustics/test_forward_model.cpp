// The forward model of one beam (acoustics/forward_model.hpp) against closed forms: one beam over
// one plane gives, bin by bin, the pulse-limited bottom reverberation of the flat-seabed sonar
// equation (sonar_equation.hpp; Urick 1983 ch. 8) for a level and a tilted beam; a plane facing the
// beam at normal incidence returns its reflectivity at the bin of its range; absorption takes
// 2αr dB; a plane behind the head or parallel to the rays returns nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sonarmap/acoustics/forward_model.hpp"
#include "sonarmap/acoustics/propagation.hpp"
#include "sonarmap/acoustics/receiver_model.hpp"
#include "sonarmap/acoustics/sonar_equation.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A Micron-like head: 3° × 35°, a Gaussian horizontal and flat-topped vertical pattern, vertical
/// cells dense enough (W / 60) for neighbouring footprints to overlap smoothly, no absorption.
ForwardModelHead micronLike() {
  ForwardModelHead head;
  head.horizontal_width_rad = 3.0 * kDeg;
  head.vertical_width_rad = 35.0 * kDeg;
  head.pattern = {{head.horizontal_width_rad, 2.0}, {head.vertical_width_rad, 8.0}};
  head.horizontal = {5, 2.0};
  head.vertical = {90, 1.5};
  head.bins = 400;
  head.range_m = 5.0;
  head.absorption_db_per_m = 0.0;
  return head;
}

/// The expected energy per bin of the beam at bearing 0 of a head at the origin, pitched down by
/// `tilt_rad` about the sonar's y axis (x ahead, z down), over a level seabed `altitude_m` below.
std::vector<double> seabedEcho(const BeamForwardModel& model, double altitude_m, double tilt_rad, double reflectivity) {
  const Eigen::Isometry3d sonar_to_map(Eigen::AngleAxisd(-tilt_rad, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d seabed_point(0.0, 0.0, altitude_m);  // z down: the seabed below the head
  const Eigen::Vector3d seabed_normal(0.0, 0.0, -1.0);       // facing the head
  std::vector<double> energy;
  model.directEchoes(
      sonar_to_map, 0.0,
      [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_range_m) {
        return planeHit(seabed_point, seabed_normal, reflectivity, origin, direction, max_range_m);
      },
      energy);
  return energy;
}

FlatSeabedHead closedFormHead(const ForwardModelHead& head, double pulse_length_m) {
  return FlatSeabedHead{head.pattern.vertical, head.vertical, pulse_length_m, head.binLength_m()};
}

TEST(acousticsForwardModel, OneBeamOverOnePlaneFollowsTheFlatSeabedClosedForm) {
  const ForwardModelHead head = micronLike();
  const BeamForwardModel model(head);
  const double pulse_length_m = 0.05;
  const int pulse_bins = pulseBins(pulse_length_m, head.binLength_m());
  for (const double tilt_deg : {0.0, 25.0}) {
    const double altitude_m = tilt_deg > 0.0 ? 1.5 : 0.6;
    std::vector<double> pulse;
    pulseSum(seabedEcho(model, altitude_m, tilt_deg * kDeg, 0.5), pulse_bins, pulse);
    const FlatSeabedHead closed = closedFormHead(head, pulse_length_m);
    int checked = 0;
    // From just inside the aperture's lower edge (the flat top of the pattern) to the range's end.
    const double lower_edge_rad = tilt_deg * kDeg + 0.45 * head.vertical_width_rad;
    for (double range_m = altitude_m / std::sin(lower_edge_rad) + 0.1; range_m < 4.8; range_m += 0.25) {
      const auto bin = static_cast<std::size_t>(range_m / head.binLength_m());
      const double bin_range_m = (static_cast<double>(bin) + 0.5) * head.binLength_m();
      const double expected = flatSeabedEchoPower(closed, FlatSeabed{altitude_m, 0.5, 2.0}, bin_range_m, tilt_deg * kDeg);
      ASSERT_GT(expected, 0.0) << tilt_deg << "° " << range_m;
      // The closed form is after the TVG, which gives back the r² of the loss per solid angle.
      const double modelled = pulse[bin] * tvgGain(bin_range_m, 0.0);
      EXPECT_NEAR(10.0 * std::log10(modelled / expected), 0.0, 1.0)
          << "tilt " << tilt_deg << "°, range " << bin_range_m << " m: forward model " << 10.0 * std::log10(modelled)
          << " dB, closed form " << 10.0 * std::log10(expected) << " dB";
      ++checked;
    }
    EXPECT_GE(checked, 3) << tilt_deg;
    // Nearer than the seabed's first return, on the steepest ray of the aperture's cells, there is
    // nothing to hear.
    const double steepest_rad = tilt_deg * kDeg + 0.5 * head.vertical.extent * head.vertical_width_rad;
    const auto first = static_cast<std::size_t>(0.99 * altitude_m / std::sin(steepest_rad) / head.binLength_m());
    for (std::size_t bin = 0; bin < first && bin < pulse.size(); ++bin) EXPECT_EQ(pulse[bin], 0.0) << bin;
  }
}

TEST(acousticsForwardModel, AFacingPlaneReturnsItsReflectivityAtItsRange) {
  // A plane square to the beam 2 m ahead fills the beam at normal incidence: the units' reference,
  // reflectivity × r⁻² of the two-way loss per solid angle, all of it within a bin or two of 2 m.
  ForwardModelHead head = micronLike();
  const BeamForwardModel model(head);
  std::vector<double> energy;
  const Eigen::Vector3d wall_point(2.0, 0.0, 0.0), wall_normal(-1.0, 0.0, 0.0);
  model.directEchoes(
      Eigen::Isometry3d::Identity(), 0.0,
      [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_range_m) {
        return planeHit(wall_point, wall_normal, 0.8, origin, direction, max_range_m);
      },
      energy);
  double total = 0.0, before = 0.0;
  for (std::size_t bin = 0; bin < energy.size(); ++bin) {
    total += energy[bin];
    if ((static_cast<double>(bin) + 1.0) * head.binLength_m() < 2.0) before += energy[bin];
  }
  // Off the axis a ray meets the plane a little farther (r / cos) and at incidence cos: the grid's
  // pattern-weighted mean of cos^(k−1) θ · cos² θ is within 4 % of 1 for this aperture.
  EXPECT_NEAR(total * 2.0 * 2.0 / 0.8, 1.0, 0.04);
  EXPECT_EQ(before, 0.0);
  // Absorption: 2 α r dB less over the same path.
  head.absorption_db_per_m = 0.5;
  const BeamForwardModel absorbing(head);
  std::vector<double> absorbed;
  absorbing.directEchoes(
      Eigen::Isometry3d::Identity(), 0.0,
      [&](const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double max_range_m) {
        return planeHit(wall_point, wall_normal, 0.8, origin, direction, max_range_m);
      },
      absorbed);
  double absorbed_total = 0.0;
  for (const double value : absorbed) absorbed_total += value;
  EXPECT_NEAR(10.0 * std::log10(total / absorbed_total), 2.0 * 0.5 * 2.0, 0.1);
}

TEST(acousticsForwardModel, PlanesBehindOrAlongTheRaysAreSilent) {
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  // Behind the head.
  EXPECT_FALSE(planeHit({-1.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, 0.5, origin, {1.0, 0.0, 0.0}, 10.0));
  // The ray runs along the plane's face.
  EXPECT_FALSE(planeHit({0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}, 0.5, origin, {1.0, 0.0, 0.0}, 10.0));
  // Beyond the range.
  EXPECT_FALSE(planeHit({3.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, 0.5, origin, {1.0, 0.0, 0.0}, 2.0));
  const auto hit = planeHit({3.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, 0.5, origin, {1.0, 0.0, 0.0}, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->range_m, 3.0);
}

TEST(acousticsForwardModel, AnInvalidHeadIsRefusedNamingTheField) {
  ForwardModelHead head = micronLike();
  head.vertical_width_rad = 0.0;
  EXPECT_THROW(BeamForwardModel{head}, ValueError);
  head = micronLike();
  head.bins = 0;
  try {
    BeamForwardModel model(head);
    FAIL() << "no throw";
  } catch (const ValueError& error) {
    EXPECT_NE(std::string(error.what()).find("bins"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace sonarmap
