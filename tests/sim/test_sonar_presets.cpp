// The sonar presets: each head's stated layout, the Micron's defaults unchanged, and what each preset
// simulates in the built-in scenes built for its range: wall and pile echoes at the geometric
// ranges, hard targets well above the noise, noise floors that differ between heads (visible and
// growing with range, or clipped), and open water that holds nothing but noise and the near field.
// Runs scan narrow sectors around the bearings they look at, so that the big heads stay fast.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sim/builtin_scenes.hpp"
#include "sonarmap/sim/msis_simulator.hpp"
#include "sonarmap/sim/sonar_presets.hpp"

namespace sonarmap {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// What sonar_presets.hpp states for each head.
struct Stated {
  std::string name;
  int bins;
  double range_m;
  std::size_t beams_per_turn;
  double horizontal_deg;
  double vertical_deg;
  double pulse_length_m;
};
const std::vector<Stated> kStated{
    {"micron", 399, 5.0, 200, 3.0, 35.0, 0.05},       {"seaking-30", 300, 30.0, 400, 3.0, 40.0, 0.10},
    {"seaking-50", 800, 50.0, 400, 3.0, 40.0, 0.15},  {"ping360", 1200, 50.0, 400, 2.0, 25.0, 0.20},
    {"ping360-2m", 1200, 2.0, 400, 2.0, 25.0, 0.008}, {"ping360-5m", 1200, 5.0, 400, 2.0, 25.0, 0.02},
    {"imagenex-881a", 500, 20.0, 400, 1.8, 20.0, 0.06}};

/// The Ping360 at the short range scales of tank work, at its power-on low gain: the shared Ping
/// Viewer logs' water is 0 in most bins and their strongest returns reach 100–160 counts.
bool lowGainShortRange(const std::string& name) { return name == "ping360-2m" || name == "ping360-5m"; }

/// The built-in scene `name` as built for the preset's head.
Scene sceneFor(const std::string& name, const SonarPreset& preset) {
  return builtinScene(name, preset.head.range_m, preset.head.vertical_beam_width_rad);
}

/// Options of `preset` scanning `passes` passes across a sector of `width_deg` around `center_deg`.
MsisSimulationOptions sectorRun(const SonarPreset& preset, double center_deg, double width_deg, std::size_t passes = 1) {
  MsisSimulationOptions options;
  options.head = preset.head;
  options.echo = preset.echo;
  options.head.sector_center_rad = center_deg * kDegree;
  options.head.sector_width_rad = width_deg * kDegree;
  options.turns = passes;
  options.nav_rate_hz = 0.0;
  return options;
}

/// Without speckle and noise: what is left is the geometry of the echoes.
MsisSimulationOptions noiseless(MsisSimulationOptions options) {
  options.echo.speckle_looks = 0;
  options.echo.noise_level_db = -300.0;
  return options;
}

/// Intensities of `beams` over ranges [from_m, to_m), all beams together.
std::vector<double> intensities(const std::vector<Beam>& beams, double from_m, double to_m) {
  std::vector<double> values;
  for (const Beam& beam : beams) {
    for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
      const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
      if (range_m >= from_m && range_m < to_m) values.push_back(beam.intensities[i]);
    }
  }
  return values;
}

double percentile(std::vector<double> values, double share) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(share * static_cast<double>(values.size() - 1))];
}

/// Range of the leading edge of the echo expected at `expected_m`: the first bin from
/// expected_m − 0.05 R on within 6 dB of the strongest bin of [expected_m − 0.05 R, expected_m + 0.05 R].
double leadingEdge_m(const Beam& beam, double expected_m, const SonarPreset& preset) {
  const double window_m = 0.05 * preset.head.range_m;
  int peak = 0;
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (std::abs(range_m - expected_m) <= window_m) peak = std::max<int>(peak, beam.intensities[i]);
  }
  const double threshold = peak - 6.0 * 255.0 / preset.echo.ad_span_db;
  for (std::size_t i = 0; i < beam.intensities.size(); ++i) {
    const double range_m = (static_cast<double>(i) + 0.5) * beam.bin_length_m;
    if (range_m >= expected_m - window_m && beam.intensities[i] >= threshold) return range_m;
  }
  return -1.0;
}

TEST(simSonarPresets, NamesAndUnknownNamesListed) {
  EXPECT_EQ(sonarPresetNames(),
            (std::vector<std::string>{"micron", "seaking-30", "seaking-50", "ping360", "ping360-2m", "ping360-5m",
                                      "imagenex-881a"}));
  try {
    sonarPreset("seabat");
    FAIL() << "expected ValueError";
  } catch (const ValueError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("seabat"), std::string::npos);
    for (const std::string& name : sonarPresetNames()) EXPECT_NE(message.find(name), std::string::npos) << name;
  }
}

TEST(simSonarPresets, EachPresetHasItsStatedLayoutAndValidates) {
  ASSERT_EQ(kStated.size(), sonarPresetNames().size());
  for (const Stated& stated : kStated) {
    SCOPED_TRACE(stated.name);
    const SonarPreset preset = sonarPreset(stated.name);
    EXPECT_EQ(preset.name, stated.name);
    EXPECT_NE(preset.description.find(std::to_string(static_cast<int>(stated.range_m)) + " m"), std::string::npos)
        << preset.description;
    EXPECT_NO_THROW(preset.head.validate());
    EXPECT_NO_THROW(preset.echo.validate());
    EXPECT_EQ(preset.head.bins, stated.bins);
    EXPECT_DOUBLE_EQ(preset.head.range_m, stated.range_m);
    EXPECT_DOUBLE_EQ(preset.head.binLength_m(), stated.range_m / stated.bins);
    EXPECT_FALSE(preset.head.isSector());
    EXPECT_EQ(preset.head.beamsPerTurn(), stated.beams_per_turn);
    EXPECT_NEAR(preset.head.horizontal_beam_width_rad, stated.horizontal_deg * kDegree, 1e-12);
    EXPECT_NEAR(preset.head.vertical_beam_width_rad, stated.vertical_deg * kDegree, 1e-12);
    EXPECT_DOUBLE_EQ(preset.echo.pulse_length_m, stated.pulse_length_m);
    // A turn takes between 8 s (the Micron) and a minute, each beam at least its two-way travel.
    EXPECT_GE(preset.head.beam_period_s, 2.0 * preset.head.range_m / 1500.0);
    EXPECT_LE(preset.head.beam_period_s * static_cast<double>(preset.head.beamsPerTurn()), 60.0);
  }
}

TEST(simSonarPresets, MicronIsTheSimulatorsDefaults) {
  const SonarPreset micron = sonarPreset("micron");
  MsisSimulationOptions preset_run;
  preset_run.head = micron.head;
  preset_run.echo = micron.echo;
  preset_run.turns = 1;
  MsisSimulationOptions default_run;
  default_run.turns = 1;
  const Scene tank = builtinScene("tank");
  const MsisSimulation a = simulateMsis(tank, preset_run);
  const MsisSimulation b = simulateMsis(tank, default_run);
  ASSERT_EQ(a.log.beams.size(), b.log.beams.size());
  for (std::size_t i = 0; i < a.log.beams.size(); ++i) {
    ASSERT_EQ(a.log.beams[i].intensities, b.log.beams[i].intensities) << i;
    ASSERT_EQ(a.log.beams[i].bearing_rad, b.log.beams[i].bearing_rad) << i;
    ASSERT_EQ(a.log.beams[i].time_s, b.log.beams[i].time_s) << i;
  }
  // The tank built for the Micron's head is the tank as first built.
  const Scene for_head = sceneFor("tank", micron);
  ASSERT_EQ(for_head.primitives.size(), tank.primitives.size());
  EXPECT_EQ(std::get<Plane>(for_head.primitives[0]).point_m, std::get<Plane>(tank.primitives[0]).point_m);
  EXPECT_EQ(std::get<Box>(for_head.primitives[2]).size_m, std::get<Box>(tank.primitives[2]).size_m);
}

TEST(simSonarPresets, PresetsDoNotAllShareTheMicronsLevels) {
  std::vector<std::pair<double, double>> mappings;
  for (const std::string& name : sonarPresetNames()) {
    const EchoModelOptions echo = sonarPreset(name).echo;
    mappings.emplace_back(echo.ad_low_db, echo.ad_span_db);
  }
  std::sort(mappings.begin(), mappings.end());
  EXPECT_GE(std::unique(mappings.begin(), mappings.end()) - mappings.begin(), 4);
}

TEST(simSonarPresets, WallsPilesAndHullsEchoAtTheirGeometricRanges) {
  for (const std::string& name : sonarPresetNames()) {
    SCOPED_TRACE(name);
    const SonarPreset preset = sonarPreset(name);
    const double r = preset.head.range_m, s = r / 5.0, bin_m = preset.head.binLength_m();
    // (scene, bearing of the surface's normal, perpendicular distance): the tank's walls (not the
    // +y one: the floater is in front), the harbour's pile ahead, the hull's side.
    const double pile_m = 0.4 * r - std::clamp(0.2 * s, 0.2, 0.3);
    const std::vector<std::tuple<std::string, double, double>> targets{
        {"tank", 0.0, 2.1 * s}, {"tank", 180.0, 2.1 * s}, {"tank", 270.0, 1.8 * s}, {"harbour", 0.0, pile_m},
        {"hull", 90.0, 0.4 * r}};
    for (const auto& [scene_name, normal_deg, distance_m] : targets) {
      SCOPED_TRACE(scene_name + " at " + std::to_string(normal_deg) + "°");
      // Beams within half a beam width of the normal: the nearest point is in the main lobe.
      const double width_deg = preset.head.horizontal_beam_width_rad / kDegree;
      // The static head's bearing b looks along map angle −b (staticSonarToMap: bearings clockwise).
      const double bearing_deg = std::fmod(360.0 - normal_deg, 360.0);
      const MsisSimulation run =
          simulateMsis(sceneFor(scene_name, preset), noiseless(sectorRun(preset, bearing_deg, width_deg)));
      ASSERT_GE(run.log.beams.size(), 2U);
      for (const Beam& beam : run.log.beams) {
        const double edge_m = leadingEdge_m(beam, distance_m, preset);
        EXPECT_GE(edge_m, distance_m - bin_m) << "bearing " << beam.bearing_rad / kDegree;
        EXPECT_LE(edge_m, distance_m + 2.0 * bin_m) << "bearing " << beam.bearing_rad / kDegree;
      }
    }
  }
}

TEST(simSonarPresets, PingThreeSixtyLogsRecordThePulseAsDeviceDataDoesTritechLogsDoNot) {
  for (const std::string& name : sonarPresetNames()) {
    SCOPED_TRACE(name);
    const SonarPreset preset = sonarPreset(name);
    const MsisSimulation run = simulateMsis(sceneFor("tank", preset), sectorRun(preset, 0.0, 10.0));
    ASSERT_FALSE(run.log.beams.empty());
    if (name.rfind("ping360", 0) == 0) {
      EXPECT_EQ(run.log.beams.front().pulse_length_m, preset.echo.pulse_length_m);
    } else {
      EXPECT_FALSE(run.log.beams.front().pulse_length_m.has_value());
    }
  }
}

TEST(simSonarPresets, HardTargetsStandWellAboveTheNoise) {
  for (const std::string& name : sonarPresetNames()) {
    SCOPED_TRACE(name);
    const SonarPreset preset = sonarPreset(name);
    const double r = preset.head.range_m;
    // The harbour's quay face at 0.7 R, seen between the piles (10°–30°), with noise and speckle,
    // against the noise at the same ranges in open water.
    const MsisSimulation quay = simulateMsis(sceneFor("harbour", preset), sectorRun(preset, 20.0, 20.0));
    std::vector<double> peaks;
    for (const Beam& beam : quay.log.beams) {
      const double face_m = 0.7 * r / std::cos(beam.bearing_rad);
      const std::vector<double> echo = intensities({beam}, face_m - 0.05 * r, face_m + 0.02 * r);
      peaks.push_back(*std::max_element(echo.begin(), echo.end()));
    }
    const MsisSimulation water = simulateMsis(sceneFor("open-water", preset), sectorRun(preset, 20.0, 20.0));
    const double noise = percentile(intensities(water.log.beams, 0.65 * r, 0.8 * r), 0.9);
    const double above_db = (percentile(peaks, 0.5) - noise) * preset.echo.ad_span_db / 255.0;
    EXPECT_GE(above_db, 15.0) << "quay median peak " << percentile(peaks, 0.5) << ", noise " << noise;
    EXPECT_GE(percentile(peaks, 0.5), lowGainShortRange(name) ? 120.0 : 150.0);
  }
}

TEST(simSonarPresets, NoiseFloorsAreVisibleAndGrowWithRangeOrAreClipped) {
  // Median intensity in open water near the full range, and how much it grew from half the range.
  std::vector<double> far_medians;
  for (const std::string& name : sonarPresetNames()) {
    SCOPED_TRACE(name);
    const SonarPreset preset = sonarPreset(name);
    const double r = preset.head.range_m;
    const MsisSimulation water = simulateMsis(sceneFor("open-water", preset), sectorRun(preset, 0.0, 30.0));
    const double far = percentile(intensities(water.log.beams, 0.95 * r, r), 0.5);
    const double half = percentile(intensities(water.log.beams, 0.45 * r, 0.55 * r), 0.5);
    far_medians.push_back(far);
    if (name == "imagenex-881a" || lowGainShortRange(name)) {
      EXPECT_EQ(far, 0.0) << "the 881A, and the Ping360 at its low gain, clip their noise";
      EXPECT_LE(percentile(intensities(water.log.beams, 0.2 * r, r), 0.99), 5.0);  // beyond the near field
    } else {
      EXPECT_GE(far, 8.0) << "a visible noise floor at the full range";
      EXPECT_LE(far, 65.0);
      EXPECT_GE(far - half, 8.0) << "that grows with range";
    }
  }
  // Floors differ between heads: at least four different levels (±3 counts).
  std::sort(far_medians.begin(), far_medians.end());
  int distinct = 1;
  for (std::size_t i = 1; i < far_medians.size(); ++i) distinct += far_medians[i] - far_medians[i - 1] > 3.0 ? 1 : 0;
  EXPECT_GE(distinct, 4);
}

TEST(simSonarPresets, OpenWaterHoldsOnlyNoiseAndTheNearField) {
  // Nothing is within reach in any direction: the log is exactly that of a head in an empty sea
  // (the same noise draws), so the mean beyond the near-field band is the noise level.
  const Scene nothing{{Plane{{0.0, 0.0, -1e6}, Eigen::Vector3d::UnitZ(), 0.5}}};
  for (const std::string& name : sonarPresetNames()) {
    SCOPED_TRACE(name);
    const SonarPreset preset = sonarPreset(name);
    MsisSimulationOptions options = sectorRun(preset, 45.0, 90.0);
    options.seed = 5;
    const MsisSimulation water = simulateMsis(sceneFor("open-water", preset), options);
    const MsisSimulation empty = simulateMsis(nothing, options);
    ASSERT_EQ(water.log.beams.size(), empty.log.beams.size());
    for (std::size_t i = 0; i < water.log.beams.size(); ++i) {
      ASSERT_EQ(water.log.beams[i].intensities, empty.log.beams[i].intensities) << i;
    }
  }
}

}  // namespace
}  // namespace sonarmap
