/// @file map_views.cpp
/// Top and side views of a 3D map (see map_views.hpp): each leaf's footprint projected along one
/// axis, the nearest (or highest) occupied voxel kept per pixel, coloured through a colour map.

#include "sonarmap/sonar/map_views.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "sonarmap/sonar/colour_scale.hpp"

namespace sonarmap {
namespace {

/// How a view projects the map: the voxel-key axes drawn to the right (u) and up (v), the axis
/// looked along (depth), and which occupied voxel of a pixel's line of sight is shown.
struct Projection {
  int u = 0;
  int v = 1;
  int depth = 2;
  bool highest = true;  ///< true: the largest depth key (top view); false: the smallest (side view)
  const char* title = "";
};

/// Per pixel of a projection: the depth key of the occupied voxel shown, and whether any free
/// voxel lies on its line of sight. Pixel (i, j): i along u, j along v, both from the lower border.
struct ProjectedMap {
  long min_u = 0, min_v = 0;
  int cols = 3, rows = 3;  ///< with the one-voxel border
  std::vector<long> shown; ///< kNone when no occupied voxel
  std::vector<unsigned char> free;
  static constexpr long kNone = std::numeric_limits<long>::min();
  std::size_t index(long u, long v) const {
    return static_cast<std::size_t>(v - min_v + 1) * static_cast<std::size_t>(cols) +
           static_cast<std::size_t>(u - min_u + 1);
  }
};

ProjectedMap project(const OcTree16& map, const Projection& p) {
  long min_u = std::numeric_limits<long>::max(), min_v = min_u;
  long max_u = std::numeric_limits<long>::min(), max_v = max_u;
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const long edge = static_cast<long>(leaf.edgeVoxels());
    min_u = std::min(min_u, static_cast<long>(leaf.key[p.u]));
    min_v = std::min(min_v, static_cast<long>(leaf.key[p.v]));
    max_u = std::max(max_u, static_cast<long>(leaf.key[p.u]) + edge - 1);
    max_v = std::max(max_v, static_cast<long>(leaf.key[p.v]) + edge - 1);
  });
  ProjectedMap projected;
  if (min_u > max_u) {  // an empty map: one unknown pixel inside the border
    projected.shown.assign(9, ProjectedMap::kNone);
    projected.free.assign(9, 0);
    return projected;
  }
  projected.min_u = min_u;
  projected.min_v = min_v;
  projected.cols = static_cast<int>(max_u - min_u + 3);
  projected.rows = static_cast<int>(max_v - min_v + 3);
  const std::size_t pixels = static_cast<std::size_t>(projected.cols) * static_cast<std::size_t>(projected.rows);
  projected.shown.assign(pixels, ProjectedMap::kNone);
  projected.free.assign(pixels, 0);
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    const Occupancy occupancy = map.model().classify(leaf.log_odds);
    if (occupancy == Occupancy::kUnknown) return;
    const long edge = static_cast<long>(leaf.edgeVoxels());
    const long u0 = leaf.key[p.u], v0 = leaf.key[p.v], d0 = leaf.key[p.depth];
    const long depth = p.highest ? d0 + edge - 1 : d0;
    for (long v = v0; v < v0 + edge; ++v) {
      for (long u = u0; u < u0 + edge; ++u) {
        const std::size_t i = projected.index(u, v);
        if (occupancy == Occupancy::kFree) {
          projected.free[i] = 1;
        } else if (long& shown = projected.shown[i]; shown == ProjectedMap::kNone ||
                                                      (p.highest ? depth > shown : depth < shown)) {
          shown = depth;
        }
      }
    }
  });
  return projected;
}

void putLabel(cv::Mat& image, const char* text, int x, int y) {
  cv::putText(image, text, cv::Point(x, y), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

/// The legend panel from column `x0`: the title, then the colour bar with the scale's ends, or
/// "none" when nothing is occupied.
void drawLegend(cv::Mat& image, int x0, const MapView& view, const char* title) {
  putLabel(image, title, x0 + 6, 14);
  if (view.occupied_pixels == 0) {
    putLabel(image, "none", x0 + 6, 34);
    return;
  }
  const int top = 24, bottom = image.rows - 10, left = x0 + 6, right = x0 + 18;
  for (int y = top; y <= bottom; ++y) {
    const double t = static_cast<double>(bottom - y) / static_cast<double>(bottom - top);
    const double value = view.scale_min_m + t * (view.scale_max_m - view.scale_min_m);
    const cv::Vec3b colour = scaleColour(value, view.scale_min_m, view.scale_max_m);
    cv::line(image, cv::Point(left, y), cv::Point(right, y), cv::Scalar(colour[0], colour[1], colour[2]));
  }
  cv::rectangle(image, cv::Point(left - 1, top - 1), cv::Point(right + 1, bottom + 1), cv::Scalar::all(kFrameGrey));
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", view.scale_max_m);
  putLabel(image, text, right + 5, top + 8);
  if (view.scale_max_m != view.scale_min_m) {
    std::snprintf(text, sizeof text, "%.2f", view.scale_min_m);
    putLabel(image, text, right + 5, bottom);
  }
}

MapView render(const OcTree16& map, const Projection& p, int max_side_px) {
  const ProjectedMap projected = project(map, p);
  const auto& coder = map.coder();
  MapView view;
  if (max_side_px > 0) {
    view.pixels_per_voxel = std::clamp(max_side_px / std::max(projected.cols, projected.rows), 1, kMaxPixelsPerVoxel);
  }
  const int f = view.pixels_per_voxel;
  view.voxel_m = map.resolution_m();
  view.left_m = coder.centerOf(static_cast<Key16::Index>(projected.min_u)) - 1.5 * view.voxel_m;
  view.bottom_m = coder.centerOf(static_cast<Key16::Index>(projected.min_v)) - 1.5 * view.voxel_m;
  view.view_cols = projected.cols * f;
  view.view_rows = projected.rows * f;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const long shown : projected.shown) {
    if (shown == ProjectedMap::kNone) continue;
    ++view.occupied_pixels;
    const double value = coder.centerOf(static_cast<Key16::Index>(shown));
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  if (view.occupied_pixels > 0) {
    view.scale_min_m = lo;
    view.scale_max_m = hi;
  }
  cv::Mat pixels(projected.rows, projected.cols, CV_8UC3, cv::Scalar::all(255));
  for (int j = 0; j < projected.rows; ++j) {
    for (int i = 0; i < projected.cols; ++i) {
      const std::size_t k =
          static_cast<std::size_t>(j) * static_cast<std::size_t>(projected.cols) + static_cast<std::size_t>(i);
      cv::Vec3b& pixel = pixels.at<cv::Vec3b>(projected.rows - 1 - j, i);  // +v up
      if (projected.shown[k] != ProjectedMap::kNone) {
        pixel = scaleColour(coder.centerOf(static_cast<Key16::Index>(projected.shown[k])), view.scale_min_m,
                            view.scale_max_m);
      } else if (projected.free[k] != 0) {
        pixel = cv::Vec3b(kFreeGrey, kFreeGrey, kFreeGrey);
      }
    }
  }
  view.image = cv::Mat(std::max(view.view_rows, kLegendMinRows), view.view_cols + kLegendCols, CV_8UC3,
                       cv::Scalar::all(255));
  cv::Mat target = view.image(cv::Rect(0, 0, view.view_cols, view.view_rows));
  if (f == 1) {
    pixels.copyTo(target);
  } else {
    cv::resize(pixels, target, target.size(), 0.0, 0.0, cv::INTER_NEAREST);
  }
  cv::rectangle(view.image, cv::Rect(0, 0, view.view_cols, view.view_rows), cv::Scalar::all(kFrameGrey));
  drawLegend(view.image, view.view_cols, view, p.title);
  return view;
}

}  // namespace

cv::Vec3b scaleColour(double value_m, double min_m, double max_m) {
  return colourOnScale(cv::COLORMAP_VIRIDIS, value_m, min_m, max_m);
}

std::optional<HeightExtent> occupiedHeightExtent(const OcTree16& map) {
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  map.forEachLeaf([&](const LeafView<16>& leaf) {
    if (map.model().classify(leaf.log_odds) != Occupancy::kOccupied) return;
    lo = std::min(lo, static_cast<long>(leaf.key[2]));
    hi = std::max(hi, static_cast<long>(leaf.key[2]) + static_cast<long>(leaf.edgeVoxels()) - 1);
  });
  if (lo > hi) return std::nullopt;
  const auto& coder = map.coder();
  return HeightExtent{coder.centerOf(static_cast<Key16::Index>(lo)), coder.centerOf(static_cast<Key16::Index>(hi))};
}

MapView renderTopView(const OcTree16& map, int max_side_px) {
  return render(map, {0, 1, 2, true, "z (m)"}, max_side_px);
}

MapView renderSideView(const OcTree16& map, int max_side_px) {
  return render(map, {0, 2, 1, false, "y (m)"}, max_side_px);
}

}  // namespace sonarmap
