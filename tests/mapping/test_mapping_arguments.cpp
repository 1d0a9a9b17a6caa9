// MappingArguments (mapping/mapping_arguments.hpp): the user's options in their units, turned into
// MapperOptions by the translation `sonarmap map` and the Python module share.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

TEST(MappingArguments, DefaultsAreTheLibrarysOptions) {
  const MapperOptions options = toMapperOptions(MappingArguments{});
  const MapperOptions library;
  EXPECT_FALSE(options.resolution_m.has_value());
  EXPECT_EQ(options.detector.kind, library.detector.kind);
  EXPECT_DOUBLE_EQ(options.beam_width_rad, library.beam_width_rad);
  EXPECT_DOUBLE_EQ(options.vertical_aperture_rad, library.vertical_aperture_rad);
  EXPECT_DOUBLE_EQ(options.max_range_m, library.max_range_m);
  EXPECT_DOUBLE_EQ(options.octree.occupancy.prob_hit, library.octree.occupancy.prob_hit);
  EXPECT_EQ(options.beam_model, BeamModel::kPlanar);
}

TEST(MappingArguments, UserUnitsBecomeLibraryUnits) {
  MappingArguments args;
  args.resolution = "0.05";
  args.beam_width_deg = 2.0;
  args.vertical_aperture_deg = 25.0;
  args.volume = true;
  args.detector = "cfar-os";
  args.min_range = "0.3";
  const MapperOptions options = toMapperOptions(args);
  EXPECT_DOUBLE_EQ(*options.resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(options.beam_width_rad, 2.0 * kRadPerDeg);
  EXPECT_DOUBLE_EQ(options.vertical_aperture_rad, 25.0 * kRadPerDeg);
  EXPECT_EQ(options.beam_model, BeamModel::kVolume);
  EXPECT_EQ(options.detector.kind, Detector::kCfar);
  EXPECT_DOUBLE_EQ(*options.detector.min_range_m, 0.3);
}

TEST(MappingArguments, BadValuesNameTheOption) {
  auto message = [](MappingArguments args) {
    try {
      toMapperOptions(args);
    } catch (const ValueError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  MappingArguments args;
  args.resolution = "-1";
  EXPECT_NE(message(args).find("--resolution"), std::string::npos);
  args = {};
  args.false_alarm = 0.7;
  EXPECT_NE(message(args).find("--false-alarm"), std::string::npos);
  args = {};
  args.detector = "magic";
  EXPECT_NE(message(args).find("magic"), std::string::npos);
  args = {};
  args.ray = "straight";
  EXPECT_NE(message(args).find("--ray"), std::string::npos);
  EXPECT_THROW(parseOptionNumber("1e999", "--x", "metres"), ValueError);
  EXPECT_THROW(parseOptionNumber("0", "--x", "metres"), ValueError);
  EXPECT_DOUBLE_EQ(parseOptionNumber("0", "--x", "metres", true), 0.0);
}

TEST(MappingArguments, TheSonarsBeamUnlessGiven) {
  MappingArguments args;
  const MapperOptions ping360 = withSonarBeam(toMapperOptions(args), args, LogFormat::kPing360);
  EXPECT_NEAR(ping360.beam_width_rad, nominalBeam(LogFormat::kPing360).width_rad, 1e-12);
  EXPECT_NEAR(ping360.vertical_aperture_rad, nominalBeam(LogFormat::kPing360).vertical_aperture_rad, 1e-12);
  args.beam_width_deg = 5.0;
  args.beam_width_given = true;
  const MapperOptions given = withSonarBeam(toMapperOptions(args), args, NominalBeam{0.01, 0.2});
  EXPECT_DOUBLE_EQ(given.beam_width_rad, 5.0 * kRadPerDeg);
  EXPECT_DOUBLE_EQ(given.vertical_aperture_rad, 0.2);
}

TEST(MappingArguments, InputFormatByNameOrExtension) {
  EXPECT_EQ(inputFormat("log.V4LOG", "auto"), LogFormat::kV4Log);
  EXPECT_EQ(inputFormat("capture.raw", "seanet"), LogFormat::kSeaNet);
  EXPECT_THROW(inputFormat("capture.raw", "auto"), FileError);
  EXPECT_THROW(inputFormat("log.csv", "nonsense"), ValueError);
}

TEST(MappingArguments, MountingInDegrees) {
  EXPECT_TRUE(sonarToBodyOfMounting({}).isApprox(defaultSonarToBody()));
  EXPECT_TRUE(sonarToBodyOfMounting({0, 0, 0, 0, 0, 0}).isApprox(defaultSonarToBody(), 1e-12));  // zeros: aligned
  // Pitch −25°: bearing 0 tilted 25° down (body z is down), as a navigation fix's pitch.
  const Eigen::Vector3d tilted = sonarToBodyOfMounting({0, 0, 0, 0, -25, 0}).linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(tilted.z(), std::sin(25.0 * std::numbers::pi / 180.0), 1e-12);
  const Eigen::Isometry3d shifted = sonarToBodyOfMounting({1, 2, 3, 0, 0, 90});
  EXPECT_TRUE(shifted.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((shifted.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_THROW(sonarToBodyOfMounting({1, 2, 3}), ValueError);
  EXPECT_THROW(sonarToBodyOfMounting({0, 0, NAN, 0, 0, 0}), ValueError);
}

}  // namespace
}  // namespace sonarmap
