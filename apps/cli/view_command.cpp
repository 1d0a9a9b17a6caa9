#include "view_command.hpp"

#include "help_groups.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/map_file.hpp"
#include "sonarmap/mapping/local_origin.hpp"
#include "sonarmap/mapping/map_frame.hpp"

namespace sonarmap::embedded {
// three.js and its OrbitControls as found at configure time (SONARMAP_THREE_JS,
// SONARMAP_ORBIT_CONTROLS_JS); empty when they were not found.
extern const std::string_view kThreeJs;
extern const std::string_view kOrbitControlsJs;
}  // namespace sonarmap::embedded

namespace sonarmap::cli {
namespace {

bool isHtml(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".html" || extension == ".htm";
}

void check(const ViewArgs& args) {
  mapFormatOf(args.input);  // throws FileError on an extension other than .bt/.ot
  if (!isHtml(args.output)) throw ValueError("-o must name an .html file, got '" + args.output + "'");
  if (std::filesystem::exists(args.input) && std::filesystem::exists(args.output) &&
      std::filesystem::equivalent(args.input, args.output)) {
    throw ValueError("-o must differ from the map file");
  }
}

void printNote(const ViewBoxes& set, const char* what, const char* option, std::size_t cap, double resolution_m) {
  if (!set.downsampled()) return;
  std::fprintf(stderr,
               "sonarmap: note: %zu %s leaves exceed %s %zu: drawn as %zu boxes, one per octree node of depth %d "
               "(%g m) holding such a leaf\n",
               set.leaves, what, option, cap, set.boxes.size(), set.level, std::ldexp(resolution_m, 16 - set.level));
}

void run(const ViewArgs& args) {
  HtmlViewOptions options;
  options.max_boxes = args.max_boxes;
  options.max_free_boxes = args.max_free_boxes;
  options.title = std::filesystem::path(args.input).filename().string();
  const FramedMap file = readMapFileToNwu(args.input);
  if (!args.trajectory_csv.empty()) {
    NavTrack track = readNavCsv(args.trajectory_csv);  // the navigation's own coordinates
    moveToOrigin(track, file.origin_ned_m);              // the map's local origin (its header's)
    options.trajectory_m = trajectoryInMap(track);
    options.trajectory_source = std::filesystem::path(args.trajectory_csv).filename().string();
  }
  const OcTree16 map = mapInFrame(file.map, MapFrame::kEnu);
  if (file.frame != MapFrame::kEnu) {
    options.frame += "; the file is " + mapFrameDescription(file.frame) +
                     (file.frame_named ? "" : " (its header names no frame)");
  }
  FileTransaction output;
  const HtmlView view = stageView(output, args.output, map, options);
  output.commit();
  printViewNotes(view, options, map.resolution_m());
  std::printf("%zu occupied boxes (%zu occupied leaves), %zu free boxes (%zu free leaves) -> %s\n",
              view.occupied.boxes.size(), view.occupied.leaves, view.free.boxes.size(), view.free.leaves,
              args.output.c_str());
}

}  // namespace

std::vector<Eigen::Vector3d> trajectoryInMap(const NavTrack& track) {
  std::vector<Eigen::Vector3d> points_m;
  points_m.reserve(track.size());
  for (const NavSample& fix : track) points_m.push_back(nedToMap() * fix.position_ned_m);
  return pointsInMapFrame(points_m, MapFrame::kEnu);
}

bool viewerAvailable() { return !embedded::kThreeJs.empty() && !embedded::kOrbitControlsJs.empty(); }

HtmlView stageView(FileTransaction& outputs, const std::string& path, const OcTree16& map, const HtmlViewOptions& options) {
  if (!viewerAvailable()) {
    throw FileError("this sonarmap was built without three.js, so it cannot write a viewer: install libjs-three "
                    "(or npm's three) and configure again with -DSONARMAP_THREE_JS=.../three.min.js "
                    "-DSONARMAP_ORBIT_CONTROLS_JS=.../OrbitControls.js");
  }
  HtmlView view = renderHtmlView(map, options, {embedded::kThreeJs, embedded::kOrbitControlsJs});
  outputs.stage(path, [&view](std::ostream& out) { out << view.html; });
  return view;
}

void printViewNotes(const HtmlView& view, const HtmlViewOptions& options, double resolution_m) {
  printNote(view.occupied, "occupied", "--max-boxes", options.max_boxes, resolution_m);
  printNote(view.free, "free", "--max-free-boxes", options.max_free_boxes, resolution_m);
}

Command addViewCommand(CLI::App& app, ViewArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "view", "Write a map as one self-contained HTML page showing it in 3D, offline");
  cmd->add_option("map", args.input, "Map file: .bt or .ot")->required();
  cmd->add_option("-o,--output", args.output, "The page to write (.html, three.js inlined)")
      ->required()
      ->group(help_group::kOutput);
  cmd->add_option("--trajectory", args.trajectory_csv, "Navigation CSV drawn as the vehicle's path")
      ->group(help_group::kInput);
  cmd->add_option("--max-boxes", args.max_boxes, "Most occupied boxes drawn (more: downsampled)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(help_group::kOutput);
  cmd->add_option("--max-free-boxes", args.max_free_boxes, "Most free boxes drawn (more: downsampled)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(help_group::kOutput);
  return {cmd, [&args] { check(args); }, [&args] { run(args); }};
}

}  // namespace sonarmap::cli
