#pragma once
/// @file figure.hpp
/// Figures a person can read at a glance: a raw raster (one pixel per voxel, bin or
/// beam) magnified with nearest-neighbour to at least kMinFigureLongSide_px on its long side, framed
/// by axes whose ticks are labelled in the raster's units (metres, degrees), under a title line,
/// beside a legend (colour swatches, a colour bar), with polylines such as the vehicle's track drawn
/// over it in the raster's coordinates. Everything is drawn with OpenCV (cv::putText, cv::line,
/// cv::rectangle, cv::applyColorMap); the figure is BGR, CV_8UC3, on a white background.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "sonarmap/sonar/colour_scale.hpp"  // colourOnScale, for the colour bars

namespace sonarmap {

/// The long side of a figure's plot area is at least this many pixels (the raster is magnified by
/// whole pixels until it is; a larger raster is never shrunk).
inline constexpr int kMinFigureLongSide_px = 800;
/// Without equal aspect (FigureSpec::equal_aspect false) each axis is magnified on its own: the
/// short side reaches at least this many pixels.
inline constexpr int kMinFigureShortSide_px = 480;

/// Colours of the occupancy maps' figures (BGR): occupied near-black, free light grey, unknown
/// white, and the vehicle's track in saturated red.
inline const cv::Vec3b kOccupiedBgr{25, 25, 25};
inline const cv::Vec3b kFreeBgr{200, 200, 200};
inline const cv::Vec3b kUnknownBgr{255, 255, 255};
inline const cv::Vec3b kTrackBgr{0, 0, 230};

/// Axis values at the raster's edges: `left` at the left edge of column 0, `right` at the right
/// edge of the last column, `bottom` at the lower edge of the last row, `top` at the upper edge of
/// row 0 (units of the axis labels, e.g. metres). left < right and bottom < top.
struct PlotExtent {
  double left = 0.0;
  double right = 1.0;
  double bottom = 0.0;
  double top = 1.0;
};

/// One entry of the legend: a filled square of `colour` and its label.
struct LegendSwatch {
  cv::Vec3b colour;
  std::string label;
};

/// A colour bar: values from `min` to `max` drawn through the OpenCV colour map `colormap`
/// (colourOnScale). With `clipped_high` the top label reads "≥ max" (">= max"): larger values
/// were drawn in the top colour.
struct ColourBar {
  cv::ColormapTypes colormap = cv::COLORMAP_VIRIDIS;
  double min = 0.0;
  double max = 1.0;
  std::string label;  ///< what the colours mean, with its unit, e.g. "z (m)"
  bool clipped_high = false;
};

/// A polyline in axis units (the PlotExtent's), drawn 2 px wide over the raster with a circle on
/// its first point; a single point is drawn as a filled dot. Parts outside the plot are clipped.
struct FigureLine {
  std::vector<Eigen::Vector2d> points;
  cv::Vec3b colour = kTrackBgr;
  std::string label;  ///< the legend's entry; empty: none
};

/// Everything a figure shows.
struct FigureSpec {
  cv::Mat raster;               ///< CV_8UC3 (BGR) or CV_8UC1 (grey), row 0 at the top; not empty
  PlotExtent extent;            ///< axis values at the raster's edges
  std::string title;            ///< the line above the plot (input, resolution, detector...)
  std::string x_label;          ///< e.g. "x (m)"
  std::string y_label;          ///< e.g. "y (m)"
  /// true: both axes magnified by the same whole factor (maps: a metre is as long in x as in y);
  /// false: each by its own (the polar image: range against bearing).
  bool equal_aspect = true;
  std::vector<LegendSwatch> swatches;
  std::optional<ColourBar> colour_bar;
  std::vector<FigureLine> lines;
};

/// Where the plot area of a composed figure lies, and how the raster was magnified.
struct FigureLayout {
  cv::Rect plot;        ///< plot area in the figure's pixels
  int scale_x = 1;      ///< figure pixels per raster column
  int scale_y = 1;      ///< figure pixels per raster row
};

/// The layout composeFigure() uses for a raster of `rows` × `cols` (both > 0).
FigureLayout figureLayout(int rows, int cols, bool equal_aspect);

/// Composes the figure: the title band on top, the plot (the raster magnified by whole pixels,
/// nearest-neighbour, to ≥ kMinFigureLongSide_px on its long side, see figureLayout) framed by
/// axes with "nice" ticks (1, 2 or 5 × 10ⁿ) labelled in the axes' units, the legend panel on the
/// right, the lines on top of the raster. CV_8UC3 (BGR).
/// @throws ValueError when the raster is empty or not CV_8UC1/CV_8UC3, or the extent is not finite
///         with left < right and bottom < top.
cv::Mat composeFigure(const FigureSpec& spec);


/// Tick values of "nice" steps (1, 2 or 5 × 10ⁿ) inside [lo, hi], about `wanted` of them (≥ 2
/// for any hi > lo).
std::vector<double> niceTicks(double lo, double hi, int wanted);

}  // namespace sonarmap
