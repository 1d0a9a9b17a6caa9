#pragma once
// `sonarmap view`: a map file (.bt/.ot) → one self-contained HTML page that shows it in 3D in a
// browser (io/html_view.hpp), with three.js compiled into the tool (apps/cli/CMakeLists.txt).

#include <cstddef>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "sonarmap/io/atomic_file.hpp"
#include "sonarmap/io/html_view.hpp"
#include "sonarmap/nav/navigation.hpp"

namespace sonarmap::cli {

/// Arguments of `sonarmap view` as typed by the user.
struct ViewArgs {
  std::string input;            ///< .bt or .ot map file
  std::string output;           ///< .html page
  std::string trajectory_csv;   ///< navigation CSV (nav/navigation.hpp), optional
  std::size_t max_boxes = HtmlViewOptions{}.max_boxes;
  std::size_t max_free_boxes = HtmlViewOptions{}.max_free_boxes;
};

/// Adds the `view` subcommand to `app`; its options fill `args`.
Command addViewCommand(CLI::App& app, ViewArgs& args);

/// True when three.js was compiled into the tool, so stageView can write a page.
bool viewerAvailable();

/// The vehicle positions of `track` (NED) in ENU, the viewer's frame (map_frame.hpp), metres.
std::vector<Eigen::Vector3d> trajectoryInMap(const NavTrack& track);

/// Renders the page of `map` with the three.js compiled into the tool, stages it for `path` in
/// `outputs`, and returns it (for printViewNotes).
/// @throws FileError when the tool was built without three.js; ValueError as renderHtmlView.
HtmlView stageView(FileTransaction& outputs, const std::string& path, const OcTree16& map, const HtmlViewOptions& options);

/// Says on stderr, one line each ("sonarmap: note: ..."), when the occupied or free boxes of `view`
/// were downsampled; `resolution_m` is the map's.
void printViewNotes(const HtmlView& view, const HtmlViewOptions& options, double resolution_m);

}  // namespace sonarmap::cli
