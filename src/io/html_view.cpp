#include "sonarmap/io/html_view.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <limits>
#include <optional>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/io/web_text.hpp"

namespace sonarmap {
namespace embedded {
extern const std::string_view kHtmlViewTemplate;  // src/io/html_view_template.html, embedded by CMake
}  // namespace embedded

namespace {

/// Box [min, max] in metres grown by the boxes it is given; empty until the first.
struct Bounds {
  Eigen::Vector3d min_m = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max_m = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  bool empty = true;

  void grow(const Eigen::Vector3d& corner_m, double edge_m) {
    min_m = min_m.cwiseMin(corner_m);
    max_m = max_m.cwiseMax(corner_m + Eigen::Vector3d::Constant(edge_m));
    empty = false;
  }
};

/// The boxes as 8 little-endian bytes each: key x, y, z, depth (uint16).
std::vector<std::uint8_t> boxBytes(const std::vector<ViewBox>& boxes) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(boxes.size() * 8);
  for (const ViewBox& box : boxes) {
    const std::array<std::uint16_t, 4> words{box.key[0], box.key[1], box.key[2], static_cast<std::uint16_t>(box.depth)};
    for (const std::uint16_t word : words) {
      bytes.push_back(static_cast<std::uint8_t>(word & 0xFFU));
      bytes.push_back(static_cast<std::uint8_t>(word >> 8));
    }
  }
  return bytes;
}

std::string vectorJson(const Eigen::Vector3d& v) {
  std::string out = "[";
  out.append(jsonNumber(v.x())).append(",").append(jsonNumber(v.y())).append(",").append(jsonNumber(v.z()));
  return out + "]";
}

std::string boundsJson(const Bounds& bounds) {
  if (bounds.empty) return "null";
  return "{\"min\":" + vectorJson(bounds.min_m) + ",\"max\":" + vectorJson(bounds.max_m) + "}";
}

std::string boxesJson(const ViewBoxes& set) {
  return "{\"boxes\":" + std::to_string(set.boxes.size()) + ",\"leaves\":" + std::to_string(set.leaves) +
         ",\"level\":" + std::to_string(set.level) + ",\"data\":\"" + base64(boxBytes(set.boxes)) + "\"}";
}

void checkScript(std::string_view script, const char* name) {
  if (script.empty()) throw ValueError(std::string("the viewer needs ") + name + ", which is empty");
  constexpr std::string_view kEnd = "</script";
  const auto it = std::search(script.begin(), script.end(), kEnd.begin(), kEnd.end(),
                              [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
  if (it != script.end()) throw ValueError(std::string(name) + " contains \"</script\" and cannot be inlined");
}

/// The template with each @NAME@ of `values` replaced; only the template is scanned, never a value.
std::string fillTemplate(std::string_view page, const std::vector<std::pair<std::string, std::string_view>>& values) {
  std::string out;
  std::size_t size = page.size();
  for (const auto& [name, value] : values) size += value.size();
  out.reserve(size);
  std::size_t at = 0;
  while (at < page.size()) {
    const std::size_t mark = page.find('@', at);
    if (mark == std::string_view::npos) break;
    out.append(page.substr(at, mark - at));
    bool replaced = false;
    for (const auto& [name, value] : values) {
      if (page.compare(mark, name.size(), name) == 0) {
        out.append(value);
        at = mark + name.size();
        replaced = true;
        break;
      }
    }
    if (!replaced) {
      out += '@';
      at = mark + 1;
    }
  }
  if (at < page.size()) out.append(page.substr(at));
  return out;
}

}  // namespace

HtmlView renderHtmlView(const OcTree16& tree, const HtmlViewOptions& options, const ViewerScripts& scripts) {
  checkScript(scripts.three_js, "three.js");
  checkScript(scripts.orbit_controls_js, "OrbitControls.js");
  std::string trajectory = "[";
  for (const Eigen::Vector3d& point_m : options.trajectory_m) {
    if (!point_m.allFinite()) throw ValueError("a trajectory point of the viewer is not finite");
    for (int axis = 0; axis < 3; ++axis) {
      if (trajectory.size() > 1) trajectory += ',';
      trajectory += jsonNumber(point_m[axis]);
    }
  }
  trajectory += "]";

  HtmlView view;
  view.occupied = collectViewBoxes(tree, Occupancy::kOccupied, options.max_boxes);
  view.free = collectViewBoxes(tree, Occupancy::kFree, options.max_free_boxes);

  Bounds all, occupied;
  std::size_t unknown_leaves = 0;
  tree.forEachLeaf([&](const LeafView<16>& leaf) {
    const ViewBox box{leaf.key, leaf.depth};
    const Eigen::Vector3d corner_m = boxCorner_m(tree, box);
    const double edge_m = boxEdge_m(tree, box);
    all.grow(corner_m, edge_m);
    const Occupancy occupancy = tree.model().classify(leaf.log_odds);
    if (occupancy == Occupancy::kOccupied) occupied.grow(corner_m, edge_m);
    if (occupancy == Occupancy::kUnknown) ++unknown_leaves;
  });
  const NodeCounts counts = tree.counts();

  std::string payload = "{\"title\":" + jsonString(options.title) + ",\"resolution_m\":" + jsonNumber(tree.resolution_m());
  payload += ",\"counts\":{\"nodes\":" + std::to_string(counts.nodes) + ",\"inner\":" + std::to_string(counts.inner) +
             ",\"leaves\":" + std::to_string(counts.leaves) + ",\"occupied_leaves\":" +
             std::to_string(view.occupied.leaves) + ",\"free_leaves\":" + std::to_string(view.free.leaves) +
             ",\"unknown_leaves\":" + std::to_string(unknown_leaves) + "}";
  payload += ",\"memory_bytes\":" + std::to_string(tree.memoryBytes());
  payload += ",\"map_bounds_m\":" + boundsJson(all) + ",\"occupied_bounds_m\":" + boundsJson(occupied);
  payload += ",\"max_boxes\":" + std::to_string(options.max_boxes) +
             ",\"max_free_boxes\":" + std::to_string(options.max_free_boxes);
  payload += ",\"frame\":" + jsonString(options.frame);
  payload += ",\"trajectory_m\":" + trajectory + ",\"trajectory_source\":" + jsonString(options.trajectory_source);
  payload += ",\"occupied\":" + boxesJson(view.occupied) + ",\"free\":" + boxesJson(view.free) + "}";

  const std::string title = htmlText(options.title.empty() ? std::string("map") : options.title);
  view.html = fillTemplate(embedded::kHtmlViewTemplate, {{"@TITLE@", title},
                                                         {"@PAYLOAD@", payload},
                                                         {"@THREE_JS@", scripts.three_js},
                                                         {"@ORBIT_CONTROLS_JS@", scripts.orbit_controls_js}});
  return view;
}

}  // namespace sonarmap
