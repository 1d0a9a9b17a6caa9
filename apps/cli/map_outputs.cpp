#include "map_outputs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <vector>

#include "progress.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/io/octomap_binary.hpp"
#include "sonarmap/io/octomap_full.hpp"
#include "sonarmap/mapping/map_slice.hpp"
#include "sonarmap/render/map_figures.hpp"
#include "sonarmap/render/sonar_figures.hpp"
#include "sonarmap/sonar/map_views.hpp"
#include "sonarmap/sonar/polar.hpp"
#include "sonarmap/sonar/png_writer.hpp"
#include "sonarmap/sonar/range_scales.hpp"
#include "sonarmap/sonar/sweeps.hpp"

namespace sonarmap::cli {
namespace {

/// The sweep drawn in the PNGs: the largest (last, on ties) sweep of the range scale most beams
/// use (the one the automatic resolution follows), and its caption. One pass over `source`, holding
/// the largest sweep so far and the one being read.
std::pair<PolarImage, std::string> pictureSweep(BeamSource& source, const LogSurvey& survey) {
  const RangeScale* scale = mostUsedRangeScale(survey.scales);
  if (scale == nullptr) throw ValueError("the log holds no beams to draw");
  std::vector<Beam> best, current;
  auto close = [&] {
    if (!current.empty() && current.front().bin_length_m == scale->bin_length_m && current.size() >= best.size()) {
      best = std::move(current);
    }
    current.clear();
  };
  SweepSplitter splitter;
  passOver(source)([&](const Beam& beam) {
    if (splitter.startsSweep(beam)) close();
    current.push_back(beam);
  });
  close();
  PolarImage polar = makePolarImage(best, 0, best.size());
  char caption[192];
  if (survey.scales.size() > 1) {
    std::snprintf(caption, sizeof caption, "%.3g m scale (%zu of %zu beams): last largest sweep, %d x %d bins of %.2g m",
                  scale->reach_m, scale->beams, survey.beams, polar.rows(), polar.cols(), polar.bin_length_m);
  } else {
    std::snprintf(caption, sizeof caption, "largest sweep: %d beams x %d bins of %.3f m", polar.rows(), polar.cols(),
                  polar.bin_length_m);
  }
  return {std::move(polar), caption};
}

/// The input's file name, for the figures' titles.
std::string inputName(const MapArgs& args) {
  return args.input.empty() ? "simulated log" : std::filesystem::path(args.input).filename().string();
}

/// "beams.csv | 0.05 m voxels | detector background | " then `what`: the map figures' title line.
std::string figureTitle(const MapArgs& args, double resolution_m, const std::string& what) {
  const std::string input = inputName(args);
  char text[256];
  std::snprintf(text, sizeof text, "%s  |  %g m voxels  |  detector %s  |  %s", input.c_str(), resolution_m,
                args.detector.c_str(), what.c_str());
  return text;
}

}  // namespace

MappedLog mapWithProgress(const MapCall& map, bool quiet) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  SonarMapper mapper = [&] {
    ProgressBar bar("mapping");
    return map([&](std::size_t done, std::size_t total) {
      if (!quiet) bar.update(done, total);
    });
  }();
  return {std::move(mapper), std::chrono::duration<double>(Clock::now() - start).count()};
}

std::vector<Eigen::Vector3d> sonarTrack(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body, const LogSurvey& survey) {
  std::vector<Eigen::Vector3d> track;
  if (survey.beams == 0) return track;
  for (const NavSample& fix : nav) {
    if (fix.time_s >= survey.earliest_s && fix.time_s <= survey.latest_s) {
      track.push_back(sonarToMap(fix, sonar_to_body).translation());
    }
  }
  return track;
}

std::vector<Eigen::Vector3d> sonarTrack(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body, const SonarLog& log) {
  return sonarTrack(nav, sonar_to_body, surveyLog(passOver(log)));
}

void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, const SonarLog& log, const OcTree16& map,
                     double pixel_m, const std::string& side_png, const std::vector<Eigen::Vector3d>& track_m) {
  LogBeamSource source(log);
  stageMapOutputs(outputs, args, source, surveyLog(passOver(log)), map, pixel_m, side_png, track_m);
}

void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, BeamSource& source, const LogSurvey& survey,
                     const OcTree16& map, double pixel_m, const std::string& side_png,
                     const std::vector<Eigen::Vector3d>& track_m) {
  outputs.stage(args.output_bt, [&](std::ostream& out) {
    if (mapFormatOf(args.output_bt) == MapFormat::kFull) {
      writeFull(map, out);
    } else {
      writeBinary(map, out);
    }
  });
  const double res = map.resolution_m();
  if (!args.map_png.empty()) {
    const cv::Mat top = args.volume ? topViewFigure(map, figureTitle(args, res, "3D map, top view"), track_m)
                                    : sliceFigure(map, 0.0, figureTitle(args, res, "2D map, slice z = 0"), track_m);
    outputs.stageBytes(args.map_png, encodePng(top));
  }
  if (!side_png.empty()) {
    outputs.stageBytes(side_png, encodePng(sideViewFigure(map, figureTitle(args, res, "3D map, side view"), track_m)));
  }
  if (args.polar_png.empty() && args.cartesian_png.empty()) return;
  const auto [polar, sweep] = pictureSweep(source, survey);
  const std::string input = inputName(args);
  if (!args.polar_png.empty()) {
    outputs.stageBytes(args.polar_png, encodePng(polarFigure(polar, input + "  |  polar image, " + sweep)));
  }
  if (!args.cartesian_png.empty()) {
    // With single rays (width 0) the image still spreads each beam over the Micron's 3°.
    const double width_deg = args.beam_width_deg > 0.0 ? args.beam_width_deg : 3.0;
    char what[64];
    std::snprintf(what, sizeof what, "  |  %g m pixels, beams %g deg wide  |  ", pixel_m, width_deg);
    const cv::Mat cartesian = cartesianFigure(polar, pixel_m, width_deg * std::numbers::pi / 180.0,
                                              input + what + sweep);
    outputs.stageBytes(args.cartesian_png, encodePng(cartesian));
  }
}

void printWarnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) std::fprintf(stderr, "sonarmap: warning: %s\n", warning.c_str());
}

void printMapSummary(const MappedLog& run, const std::string& output_bt, bool with_nav, std::size_t warnings) {
  const MappingStats& stats = run.mapper.stats();
  const MappingStats::Calibration& calibration = stats.calibration;
  const OcTree16& map = run.mapper.map();
  const NodeCounts counts = map.counts();
  std::printf("%zu beams used, %zu skipped, ", stats.beams_used, stats.beams_skipped + stats.out_of_map);
  if (with_nav) std::printf("%zu without navigation, ", stats.beams_without_nav);
  if (stats.beams_uncalibrated > 0) std::printf("%zu uncalibrated, ", stats.beams_uncalibrated);
  if (stats.beams_without_evidence > 0) std::printf("%zu without obstacle (clearing nothing), ", stats.beams_without_evidence);
  if (stats.extended_returns > 0) std::printf("%zu weak extended returns, ", stats.extended_returns);
  std::printf("%zu sweeps, %zu obstacles%s, ", stats.sweeps, stats.obstacles,
              stats.obstacles == 0 ? " (EMPTY MAP)" : "");
  if (const std::optional<HeightExtent> extent = occupiedHeightExtent(map)) {
    std::printf("occupied z %.2f .. %.2f m, ", extent->min_m, extent->max_m);
  }
  // Each sweep calibrates its own minimum range: the summary gives the span over the log.
  std::printf("%g m voxels%s, min range %.2f", map.resolution_m(), run.resolution_note.c_str(), calibration.min_range_lowest_m);
  if (std::lround(calibration.min_range_highest_m * 100.0) != std::lround(calibration.min_range_lowest_m * 100.0)) {
    std::printf(" .. %.2f", calibration.min_range_highest_m);
  }
  std::printf(" m, threshold %.1f dB on %.0f dB, %zu map nodes (%zu leaves), %.1f KiB, %.3f s", calibration.threshold_db, calibration.span_db, counts.nodes,
              counts.leaves, static_cast<double>(map.memoryBytes()) / 1024.0, run.seconds);
  if (!run.skip_note.empty()) std::printf(", %s", run.skip_note.c_str());
  if (warnings > 0) std::printf(", %zu warning%s (see stderr)", warnings, warnings == 1 ? "" : "s");
  std::printf(" -> %s\n", output_bt.c_str());
}

void printTankReport(const OcTree16& map) {
  const std::size_t occupied = cellsInSlice(map, 0.0, Occupancy::kOccupied).size();
  if (occupied < 8) {
    std::printf("tank: %zu occupied cells at z = 0, too few to fit walls\n", occupied);
    return;
  }
  const TankMapQuality quality = evaluateTankMap(map, 0.0);
  const WallFitReport& walls = quality.walls;
  std::printf("tank: %.2f x %.2f m at %.1f deg, %zu occupied cells, %.3f on walls, %.3f of walls covered, "
              "rms %.3f m, inside %.3f free %.4f occupied\n",
              walls.rect.width_m, walls.rect.height_m, walls.rect.angle_rad * 180.0 / std::numbers::pi,
              quality.occupied_cells, walls.share_on_walls, walls.wall_coverage, walls.rms_wall_distance_m,
              quality.interior_free_share, quality.interior_occupied_share);
}

}  // namespace sonarmap::cli
