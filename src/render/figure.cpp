/// @file figure.cpp
/// composeFigure (figure.hpp): the raster magnified, the axes, the title, the legend, the lines.

#include "sonarmap/render/figure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

// The bands around the plot, pixels.
constexpr int kTitleBand = 46;
constexpr int kLeftBand = 84;
constexpr int kBottomBand = 62;
constexpr int kMinLegendBand = 200;  // wider when a legend text needs it
constexpr int kMinCanvasRows = 360;  // room for the legend under a flat plot

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTickScale = 0.5;
constexpr double kLabelScale = 0.55;
constexpr double kTitleScale = 0.65;
const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kFrame(90, 90, 90);

cv::Scalar scalarOf(const cv::Vec3b& c) { return cv::Scalar(c[0], c[1], c[2]); }

cv::Size textSize(const std::string& text, double scale, int thickness = 1) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, thickness, &baseline);
}

void putText(cv::Mat& image, const std::string& text, cv::Point at, double scale, int thickness = 1) {
  cv::putText(image, text, at, kFont, scale, kInk, thickness, cv::LINE_AA);
}

/// "%.Nf" with as many decimals as the tick step needs.
std::string tickText(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return text;
}

/// Where an axis value falls along the plot: pixels from the plot's left (or top) edge.
double toPixel(double value, double lo, double hi, int length, bool flipped) {
  const double t = (value - lo) / (hi - lo);
  return (flipped ? 1.0 - t : t) * length;
}

void drawTitle(cv::Mat& canvas, const std::string& title) {
  const int room = canvas.cols - 2 * 12;
  double scale = kTitleScale;
  while (scale > 0.4 && textSize(title, scale).width > room) scale -= 0.05;
  std::string shown = title;
  while (shown.size() > 4 && textSize(shown, scale).width > room) shown = shown.substr(0, shown.size() - 4) + "...";
  putText(canvas, shown, cv::Point(12, 30), scale, 1);
}

void drawAxes(cv::Mat& canvas, const FigureSpec& spec, const cv::Rect& plot) {
  const PlotExtent& e = spec.extent;
  cv::rectangle(canvas, cv::Rect(plot.x - 1, plot.y - 1, plot.width + 2, plot.height + 2), kFrame, 1);
  const std::vector<double> x_ticks = niceTicks(e.left, e.right, std::max(3, plot.width / 110));
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  for (const double x : x_ticks) {
    const int px = plot.x + static_cast<int>(std::lround(toPixel(x, e.left, e.right, plot.width, false)));
    const int bottom = plot.y + plot.height;
    cv::line(canvas, cv::Point(px, bottom), cv::Point(px, bottom + 6), kFrame, 1);
    const std::string text = tickText(x, x_step);
    putText(canvas, text, cv::Point(px - textSize(text, kTickScale).width / 2, bottom + 24), kTickScale);
  }
  const std::vector<double> y_ticks = niceTicks(e.bottom, e.top, std::max(3, plot.height / 90));
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  for (const double y : y_ticks) {
    const int py = plot.y + static_cast<int>(std::lround(toPixel(y, e.bottom, e.top, plot.height, true)));
    cv::line(canvas, cv::Point(plot.x - 7, py), cv::Point(plot.x - 1, py), kFrame, 1);
    const std::string text = tickText(y, y_step);
    putText(canvas, text, cv::Point(plot.x - 10 - textSize(text, kTickScale).width, py + 5), kTickScale);
  }
  // The x label centred under the ticks; the y label turned a quarter left, centred beside them.
  const cv::Size x_size = textSize(spec.x_label, kLabelScale);
  putText(canvas, spec.x_label, cv::Point(plot.x + (plot.width - x_size.width) / 2, plot.y + plot.height + 52),
          kLabelScale);
  const cv::Size y_size = textSize(spec.y_label, kLabelScale);
  if (y_size.width > 0) {
    cv::Mat label(y_size.height + 8, y_size.width + 4, CV_8UC3, cv::Scalar::all(255));
    putText(label, spec.y_label, cv::Point(2, y_size.height + 2), kLabelScale);
    cv::Mat turned;
    cv::rotate(label, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int top = std::max(0, plot.y + (plot.height - turned.rows) / 2);
    const cv::Rect at(6, top, turned.cols, std::min(turned.rows, canvas.rows - top));
    turned(cv::Rect(0, 0, at.width, at.height)).copyTo(canvas(at));
  }
}

void drawLines(cv::Mat& canvas, const FigureSpec& spec, const cv::Rect& plot) {
  cv::Mat area = canvas(plot);  // drawing into the plot's view clips the lines to it
  constexpr int kShift = 4;     // sub-pixel bits of the points
  const PlotExtent& e = spec.extent;
  for (const FigureLine& line : spec.lines) {
    std::vector<cv::Point> points;
    for (const Eigen::Vector2d& p : line.points) {
      if (!p.allFinite()) continue;
      points.emplace_back(static_cast<int>(std::lround(toPixel(p.x(), e.left, e.right, plot.width, false) * 16.0)),
                          static_cast<int>(std::lround(toPixel(p.y(), e.bottom, e.top, plot.height, true) * 16.0)));
    }
    if (points.empty()) continue;
    const cv::Scalar colour = scalarOf(line.colour);
    if (points.size() == 1) {
      cv::circle(area, points[0], 5 << kShift, colour, cv::FILLED, cv::LINE_AA, kShift);
      continue;
    }
    cv::polylines(area, points, false, colour, 2, cv::LINE_AA, kShift);
    cv::circle(area, points[0], 6 << kShift, colour, 2, cv::LINE_AA, kShift);
  }
}

/// The legend panel from column x0: swatches, line entries, then the colour bar.
void drawLegend(cv::Mat& canvas, const FigureSpec& spec, const cv::Rect& plot) {
  const int x0 = plot.x + plot.width + 22;
  int y = plot.y + 4;
  for (const LegendSwatch& swatch : spec.swatches) {
    const cv::Rect box(x0, y, 18, 18);
    cv::rectangle(canvas, box, scalarOf(swatch.colour), cv::FILLED);
    cv::rectangle(canvas, box, kFrame, 1);
    putText(canvas, swatch.label, cv::Point(x0 + 28, y + 15), kLabelScale);
    y += 28;
  }
  for (const FigureLine& line : spec.lines) {
    if (line.label.empty()) continue;
    if (line.points.size() == 1) {  // drawn as a dot
      cv::circle(canvas, cv::Point(x0 + 9, y + 9), 5, scalarOf(line.colour), cv::FILLED, cv::LINE_AA);
    } else {
      cv::line(canvas, cv::Point(x0, y + 9), cv::Point(x0 + 18, y + 9), scalarOf(line.colour), 2, cv::LINE_AA);
    }
    putText(canvas, line.label, cv::Point(x0 + 28, y + 15), kLabelScale);
    y += 28;
  }
  if (!spec.colour_bar) return;
  const ColourBar& bar = *spec.colour_bar;
  y += 12;
  putText(canvas, bar.label, cv::Point(x0, y + 14), kLabelScale);
  const int top = y + 28;
  const int bottom = std::max(top + 60, std::min(top + 320, canvas.rows - 20));
  const int left = x0, right = x0 + 22;
  for (int row = top; row <= bottom; ++row) {
    const double value = bar.min + (bar.max - bar.min) * static_cast<double>(bottom - row) / (bottom - top);
    cv::line(canvas, cv::Point(left, row), cv::Point(right, row),
             scalarOf(colourOnScale(bar.colormap, value, bar.min, bar.max)));
  }
  cv::rectangle(canvas, cv::Point(left - 1, top - 1), cv::Point(right + 1, bottom + 1), kFrame, 1);
  if (bar.max <= bar.min) {
    putText(canvas, tickText(bar.min, 0.01), cv::Point(right + 8, (top + bottom) / 2 + 5), kTickScale);
    return;
  }
  const std::vector<double> ticks = niceTicks(bar.min, bar.max, 5);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : (bar.max - bar.min);
  for (const double value : ticks) {
    const int row = bottom - static_cast<int>(std::lround((value - bar.min) / (bar.max - bar.min) * (bottom - top)));
    cv::line(canvas, cv::Point(right + 1, row), cv::Point(right + 5, row), kFrame, 1);
    if (bar.clipped_high && row < top + 16) continue;  // the ">=" label below takes the top
    putText(canvas, tickText(value, step), cv::Point(right + 8, row + 5), kTickScale);
  }
  if (bar.clipped_high) {  // beside the bar's top row, above the highest tick
    putText(canvas, ">= " + tickText(bar.max, step / 10.0), cv::Point(right + 8, top + 5), kTickScale);
  }
}

/// Width of the legend panel: room for its widest text.
int legendBand(const FigureSpec& spec) {
  int widest = 0;  // from the panel's left edge (22 px right of the plot)
  for (const LegendSwatch& swatch : spec.swatches) widest = std::max(widest, 28 + textSize(swatch.label, kLabelScale).width);
  for (const FigureLine& line : spec.lines) widest = std::max(widest, 28 + textSize(line.label, kLabelScale).width);
  if (spec.colour_bar) widest = std::max(widest, textSize(spec.colour_bar->label, kLabelScale).width);
  return std::max(kMinLegendBand, 22 + widest + 16);
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int wanted) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(1, wanted);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  for (;;) {
    ticks.clear();
    const double first = std::ceil(lo / step - 1e-9);
    for (double k = first; k * step <= hi + step * 1e-9; k += 1.0) ticks.push_back(k * step);
    if (ticks.size() >= 2) return ticks;
    step /= 2.0;  // a narrow range between two steps: halve until two ticks fit
  }
}

FigureLayout figureLayout(int rows, int cols, bool equal_aspect) {
  if (rows <= 0 || cols <= 0) throw ValueError("figure: the raster is empty");
  auto factor = [](int size, int wanted) { return std::max(1, (wanted + size - 1) / size); };
  FigureLayout layout;
  if (equal_aspect) {
    layout.scale_x = layout.scale_y = factor(std::max(rows, cols), kMinFigureLongSide_px);
  } else {
    const bool wide = cols >= rows;
    layout.scale_x = factor(cols, wide ? kMinFigureLongSide_px : kMinFigureShortSide_px);
    layout.scale_y = factor(rows, wide ? kMinFigureShortSide_px : kMinFigureLongSide_px);
  }
  layout.plot = cv::Rect(kLeftBand, kTitleBand, cols * layout.scale_x, rows * layout.scale_y);
  return layout;
}

cv::Mat composeFigure(const FigureSpec& spec) {
  if (spec.raster.empty() || (spec.raster.type() != CV_8UC1 && spec.raster.type() != CV_8UC3)) {
    throw ValueError("figure: the raster must be a non-empty CV_8UC1 or CV_8UC3 image");
  }
  const PlotExtent& e = spec.extent;
  if (!(std::isfinite(e.left) && std::isfinite(e.right) && std::isfinite(e.bottom) && std::isfinite(e.top) &&
        e.left < e.right && e.bottom < e.top)) {
    throw ValueError("figure: the extent must be finite with left < right and bottom < top");
  }
  const FigureLayout layout = figureLayout(spec.raster.rows, spec.raster.cols, spec.equal_aspect);
  const cv::Rect& plot = layout.plot;
  cv::Mat canvas(std::max(kMinCanvasRows, plot.y + plot.height + kBottomBand), plot.x + plot.width + legendBand(spec),
                 CV_8UC3, cv::Scalar::all(255));
  cv::Mat colour;
  if (spec.raster.channels() == 1) {
    cv::cvtColor(spec.raster, colour, cv::COLOR_GRAY2BGR);
  } else {
    colour = spec.raster;
  }
  cv::resize(colour, canvas(plot), plot.size(), 0.0, 0.0, cv::INTER_NEAREST);
  drawLines(canvas, spec, plot);
  drawAxes(canvas, spec, plot);
  drawTitle(canvas, spec.title);
  drawLegend(canvas, spec, plot);
  return canvas;
}

}  // namespace sonarmap
