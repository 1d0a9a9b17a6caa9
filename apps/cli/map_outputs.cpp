#include "map_outputs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "progress.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/eval/tank_quality.hpp"
#include "sonarmap/io/geotiff.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/geo_raster.hpp"
#include "sonarmap/mapping/map_frame.hpp"
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

/// The heights the 2D picture shows: the band of the occupied voxels, or z = 0 in an empty map.
struct PictureBand {
  double z_min_m = 0.0;  ///< height (z up: internal NWU and ENU alike), metres
  double z_max_m = 0.0;
  bool occupied = false;  ///< false: nothing is occupied, the band is the slice z = 0
};

PictureBand pictureBand(const OcTree16& map) {
  const std::optional<HeightExtent> extent = occupiedHeightExtent(map);
  if (!extent) return {};
  return {extent->min_m, extent->max_m, true};
}

/// What the 2D picture shows, said in its title and the summary.
std::string pictureBandText(const PictureBand& band) {
  char text[128];
  if (!band.occupied) {
    std::snprintf(text, sizeof text, "slice z = 0 m (nothing occupied)");
  } else if (band.z_min_m == band.z_max_m) {
    std::snprintf(text, sizeof text, "slice z = %.2f m up (the occupied layer)", band.z_min_m);
  } else {
    std::snprintf(text, sizeof text, "occupied band z %.2f .. %.2f m up, seen from above", band.z_min_m, band.z_max_m);
  }
  return text;
}

/// The height (z up, metres) of the layer of voxels holding the most occupied voxels; 0 when none is.
double busiestOccupiedHeight(const OcTree16& map) {
  std::vector<std::size_t> per_layer(std::size_t{1} << 16, 0);
  bool any = false;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    const auto edge = static_cast<std::size_t>(leaf.edgeVoxels());
    for (std::size_t z = 0; z < edge; ++z) per_layer[leaf.key[2] + z] += edge * edge;
    any = true;
  });
  if (!any) return 0.0;
  const auto busiest = std::max_element(per_layer.begin(), per_layer.end()) - per_layer.begin();
  return map.coder().centerOf(static_cast<Key16::Index>(busiest));
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

SonarPoseAt sonarPoseOn(const NavTrack& nav, const Eigen::Isometry3d& sonar_to_body) {
  if (nav.empty()) return [](double) { return std::optional<Eigen::Isometry3d>(staticSonarToMap()); };
  auto interpolator = std::make_shared<NavInterpolator>(nav);
  return [interpolator, sonar_to_body](double time_s) -> std::optional<Eigen::Isometry3d> {
    const std::optional<Eigen::Isometry3d> body = interpolator->bodyToNedAt(time_s);
    if (!body) return std::nullopt;
    return nedToMap() * *body * sonar_to_body;
  };
}

void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, const SonarLog& log, const OcTree16& map,
                     double pixel_m, const std::string& side_png, const std::vector<Eigen::Vector3d>& track_m,
                     const SonarPoseAt& pose_at) {
  LogBeamSource source(log);
  stageMapOutputs(outputs, args, source, surveyLog(passOver(log)), map, pixel_m, side_png, track_m, pose_at);
}

void stageMapOutputs(FileTransaction& outputs, const MapArgs& args, BeamSource& source, const LogSurvey& survey,
                     const OcTree16& map, double pixel_m, const std::string& side_png,
                     const std::vector<Eigen::Vector3d>& track_m, const SonarPoseAt& pose_at) {
  outputs.stage(args.output_bt, [&](std::ostream& out) {
    const OcTree16& framed = args.map_frame == MapFrame::kNwu ? map : mapInFrame(map, args.map_frame);
    writeMap(framed, out, mapFormatOf(args.output_bt),
             mapHeaderComments(args.map_frame, args.map_origin_ned_m, args.map_geodetic_zero));
  });
  const double res = map.resolution_m();
  if (!args.geotiff.empty() && args.map_geodetic_zero) {
    // The 2D map's heights: the --png picture's band (the occupied voxels'; the slice z = 0 when none is).
    const PictureBand band = pictureBand(map);
    const std::optional<MosaicGrid> mosaic =
        args.mosaic ? std::optional(echoMosaic(source, pose_at ? pose_at : sonarPoseOn({}, {}),
                                               {res, args.beam_width_deg * std::numbers::pi / 180.0, args.mosaic_min_range_m}))
                    : std::nullopt;
    outputs.stageBytes(args.geotiff,
                       encodeGeoTiff(utmRasterOfMap(map, band.z_min_m, band.z_max_m, *args.map_geodetic_zero,
                                                    mosaic ? &*mosaic : nullptr)));
  }
  if (!args.map_png.empty() || !side_png.empty()) {
    // The pictures are charts whatever the file's frame: east to the right, north up.
    const OcTree16 enu = mapInFrame(map, MapFrame::kEnu);
    const std::vector<Eigen::Vector3d> track_enu = pointsInMapFrame(track_m, MapFrame::kEnu);
    if (!args.map_png.empty()) {
      const PictureBand band = pictureBand(map);
      const cv::Mat top =
          args.volume ? topViewFigure(enu, figureTitle(args, res, "3D map, top view"), track_enu)
                      : bandFigure(enu, band.z_min_m, band.z_max_m,
                                   figureTitle(args, res, "2D map, " + pictureBandText(band)), track_enu);
      outputs.stageBytes(args.map_png, encodePng(top));
    }
    if (!side_png.empty()) {
      outputs.stageBytes(side_png,
                         encodePng(sideViewFigure(enu, figureTitle(args, res, "3D map, side view"), track_enu)));
    }
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

void printMapSummary(const MappedLog& run, const MapArgs& args, bool with_nav, std::size_t warnings) {
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
    if (args.map_frame == MapFrame::kNed) {
      std::printf("occupied z %.2f .. %.2f m (down), ", -extent->max_m, -extent->min_m);
    } else {
      std::printf("occupied z %.2f .. %.2f m (up), ", extent->min_m, extent->max_m);
    }
  }
  if (!args.map_png.empty() && !args.volume) std::printf("picture: %s, ", pictureBandText(pictureBand(map)).c_str());
  // Each sweep calibrates its own minimum range: the summary gives the span over the log.
  std::printf("%g m voxels%s, min range %.2f", map.resolution_m(), run.resolution_note.c_str(), calibration.min_range_lowest_m);
  if (std::lround(calibration.min_range_highest_m * 100.0) != std::lround(calibration.min_range_lowest_m * 100.0)) {
    std::printf(" .. %.2f", calibration.min_range_highest_m);
  }
  std::printf(" m, threshold %.1f dB on %.0f dB, %zu map nodes (%zu leaves), %.1f KiB, %.3f s", calibration.threshold_db, calibration.span_db, counts.nodes,
              counts.leaves, static_cast<double>(map.memoryBytes()) / 1024.0, run.seconds);
  if (!run.skip_note.empty()) std::printf(", %s", run.skip_note.c_str());
  if (warnings > 0) std::printf(", %zu warning%s (see stderr)", warnings, warnings == 1 ? "" : "s");
  std::printf(" -> %s in %s\n", args.output_bt.c_str(), mapFrameDescription(args.map_frame).c_str());
}

void printTankReport(const OcTree16& map) {
  const double z_m = busiestOccupiedHeight(map);
  const std::size_t occupied = cellsInSlice(map, z_m, Occupancy::kOccupied).size();
  if (occupied < 8) {
    std::printf("tank: %zu occupied cells in the slice z = %.2f m up, too few to fit walls\n", occupied, z_m);
    return;
  }
  const TankMapQuality quality = evaluateTankMap(map, z_m);
  const WallFitReport& walls = quality.walls;
  std::printf("tank: slice z = %.2f m up (the layer with the most occupied cells), %.2f x %.2f m at %.1f deg, "
              "%zu occupied cells, %.3f on walls, %.3f of walls covered, "
              "rms %.3f m, inside %.3f free %.4f occupied\n",
              z_m, walls.rect.width_m, walls.rect.height_m, walls.rect.angle_rad * 180.0 / std::numbers::pi,
              quality.occupied_cells, walls.share_on_walls, walls.wall_coverage, walls.rms_wall_distance_m,
              quality.interior_free_share, quality.interior_occupied_share);
}

}  // namespace sonarmap::cli
