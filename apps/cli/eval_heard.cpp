#include "eval_heard.hpp"

#include "help_groups.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <system_error>

#include "map_options.hpp"
#include "progress.hpp"
#include "simulate_command.hpp"
#include "sonarmap/core/errors.hpp"
#include "sonarmap/formats/log_reader.hpp"
#include "sonarmap/mapping/mapping_arguments.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::cli {

void addHeardOptions(CLI::App& cmd, HeardArgs& args) {
  cmd.add_option("--heard-by", args.beams, "Also score against the surface this log's beams heard")
      ->group(help_group::kScoring);
  cmd.add_option("--nav", args.nav_csv, "With --heard-by: the log's TRUE navigation CSV (truth_nav.csv)")
      ->group(help_group::kNavigation);
  addMountingOption(cmd, args.mounting, "With --nav: ");
  cmd.add_option("--heard-level", args.level_db, "With --heard-by: heard at this many dB over the floor, or any")
      ->capture_default_str()
      ->group(help_group::kScoring);
  cmd.add_option("--sonar", args.sonar, sonarPresetHelp("With --heard-by: the log's head:"))
      ->capture_default_str()
      ->group(help_group::kScoring);
}

double parseHeardLevel(const std::string& text) {
  constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
  if (text == "any") return kMinusInfinity;
  double level_db = 0.0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, level_db);  // reads -inf too, not +inf or nan
  if (text.empty() || error != std::errc() || stop != end || !(std::isfinite(level_db) || level_db == kMinusInfinity)) {
    throw ValueError("--heard-level must be dB over the floor (a finite number), -inf or any, got '" + text + "'");
  }
  return level_db;
}

std::optional<HeardRequest> toHeardRequest(const CLI::App& cmd, const HeardArgs& args) {
  if (args.beams.empty()) {
    for (const char* option : {"--nav", "--mounting", "--heard-level", "--sonar"}) {
      if (cmd.count(option) > 0) throw ValueError(std::string(option) + " needs --heard-by");
    }
    return std::nullopt;
  }
  if (!args.mounting.empty() && args.nav_csv.empty()) throw ValueError("--mounting needs --nav");
  HeardRequest request;
  request.beams = args.beams;
  request.nav_csv = args.nav_csv;
  request.sonar_to_body = sonarToBodyOfMounting(args.mounting);
  request.min_level_db = parseHeardLevel(args.level_db);
  request.preset = sonarPreset(args.sonar);
  return request;
}

HeardSurfaceScore scoreHeardSurface(const HeardRequest& request, const Scene& scene, const OcTree16& map,
                                    const GroundTruthReport& truth, bool quiet, HeardSurfaceStats& stats) {
  const SonarLog log = readSonarLog(request.beams, inputFormat(request.beams, "auto"));
  const NavTrack nav = request.nav_csv.empty() ? NavTrack{} : readNavCsv(request.nav_csv);
  const OcTree16 heard = [&] {
    ProgressBar bar("heard surface");
    return heardSurfaceMap(log, nav, request.sonar_to_body, scene, request.preset.head, request.preset.echo,
                           HeardSurfaceOptions{map.resolution_m(), request.min_level_db}, &stats,
                           [&](std::size_t done, std::size_t total) {
                             if (!quiet) bar.update(done, total);
                           });
  }();
  return scoreAgainstHeardSurface(map, truth, heard);
}

void printHeardScore(const HeardRequest& request, const HeardSurfaceScore& score, const HeardSurfaceStats& stats) {
  std::printf("heard_recall %.4f (%zu of %zu heard surface voxels mapped)\n", score.recall, score.heard_voxels_found,
              score.heard_voxels);
  std::printf("heard_f1 %.4f (precision %.4f, heard recall %.4f)\n", score.f1, score.precision, score.recall);
  char level[64] = "every surface a ray meets";
  if (!std::isinf(request.min_level_db)) {
    std::snprintf(level, sizeof level, "echoes >= %g dB over the floor", request.min_level_db);
  }
  std::printf("heard_surface %zu voxels: %s by the %s head, %zu beams traced (%zu without navigation)\n",
              score.heard_voxels, level, request.preset.name.c_str(), stats.beams, stats.beams_without_nav);
}

}  // namespace sonarmap::cli
