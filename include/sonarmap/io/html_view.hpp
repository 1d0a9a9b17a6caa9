#pragma once
/// @file html_view.hpp
/// A map as one self-contained HTML page that shows it in 3D in a browser, offline: the page
/// inlines three.js (given by the caller, e.g. Debian's libjs-three r111 or an npm copy), the
/// octree's boxes (view_boxes.hpp) and its statistics. Occupied leaves are boxes of their real size
/// coloured by the height of their centre (10 bands, legend in metres); free leaves are shown on a
/// toggle; a grid at the map's floor with cells of a round number of metres, axes from the map's
/// origin, the sonar's trajectory as a line. The tree is drawn in ENU (x east, y north, z up,
/// metres: map_frame.hpp's mapInFrame(map, MapFrame::kEnu)); the page states HtmlViewOptions::frame.
///
/// Opened as `MAP.html#selfcheck`, the page checks itself once its first frame is drawn (it draws
/// the map thirteen times, so a plain opening skips it and reads `boxes=B stated=S leaves=L (open
/// as #selfcheck ...)`): the element `<pre id="check">` then reads
/// `boxes=B stated=S leaves=L level=D bands=N unseen=U missing_px=M box_px=X painted=P webgl=yes ok`:
/// B boxes drawn (instances of the occupied meshes), S boxes the page was given
/// (HtmlView::occupied.boxes), L occupied leaves of the map, D the octree depth drawn (16: one box
/// per leaf), N height bands holding boxes, U of them that paint no pixel when drawn alone, M pixels
/// painted by some band drawn alone but not by all bands drawn together, X pixels that differ from
/// the background in the frame of all boxes, P in the full first frame (boxes, grid, axes,
/// trajectory); `ok` when B == S, U == 0 and M ≤ 1 % of the pixels the bands paint alone, else
/// `MISMATCH`; `webgl=no` without WebGL.
///
/// The page is a function of its inputs only (no time stamp, no random number): the same map and
/// options give the same bytes.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/io/view_boxes.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"

namespace sonarmap {

/// The JavaScript the page inlines. Neither may contain "</script" (it would end the element).
struct ViewerScripts {
  std::string_view three_js;           ///< three.js r111 or later, non-module build (defines THREE)
  std::string_view orbit_controls_js;  ///< examples/js/controls/OrbitControls.js (THREE.OrbitControls)
};

/// What the page shows besides the map.
struct HtmlViewOptions {
  std::size_t max_boxes = 200000;       ///< cap on the occupied boxes; beyond it the map is downsampled
  std::size_t max_free_boxes = 100000;  ///< the same cap for the free boxes
  std::string title;                    ///< shown as the page's title and heading (e.g. the file name)
  std::vector<Eigen::Vector3d> trajectory_m;  ///< sonar or vehicle positions, ENU, metres
  /// The frame, as the page's statistics state it (e.g. where the map file's own frame differs).
  std::string frame = "ENU (x east, y north, z up), metres";
  std::string trajectory_source;        ///< where the trajectory came from (a file name), shown beside it
};

/// A rendered page and the boxes it draws.
struct HtmlView {
  std::string html;
  ViewBoxes occupied;  ///< the occupied boxes drawn (downsampled when above max_boxes)
  ViewBoxes free;      ///< the free boxes drawn on the toggle (downsampled when above max_free_boxes)
};

/// Renders `tree` as an HTML page. The tree is not modified. Payload: each box as 8 bytes (uint16
/// little-endian key x, y, z of its lowest corner in OctoMap's depth-16 key layout, and its depth),
/// base64 in a JSON element, with the counts (octree nodes, leaves by class), memoryBytes(), the
/// bounds in metres of all leaves and of the occupied ones, and the trajectory.
/// @throws ValueError when a cap is 0, a script is empty or contains "</script", or a trajectory
///         point is not finite.
HtmlView renderHtmlView(const OcTree16& tree, const HtmlViewOptions& options, const ViewerScripts& scripts);

}  // namespace sonarmap
