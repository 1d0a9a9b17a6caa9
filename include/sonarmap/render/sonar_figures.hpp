#pragma once
/// @file sonar_figures.hpp
/// Readable figures of a sweep's echoes (figure.hpp): the polar image with range and bearing axes,
/// and its Cartesian top view with axes in metres. Intensities (0–255) are drawn through
/// COLORMAP_INFERNO (black at 0, yellow at 255) with its colour bar. Each figure is
/// composeFigure()'s BGR image, CV_8UC3, at least kMinFigureLongSide_px on its long side.

#include <string>

#include <opencv2/core.hpp>

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// The polar image (polar_image.hpp) with range to the right (x axis, "range (m)", from 0 to
/// cols × bin_length_m) and bearing up (y axis, "bearing (deg)", sonar frame, clockwise
/// from bearing 0). The rows are ordered by bearing, unwrapped along the sweep so that a turn
/// through 360° or a sector across 0° stays continuous (the lowest bearing in [−180°, 180°)), and
/// drawn as evenly spaced: each row spans (highest − lowest) / (rows − 1) degrees (1° for a single
/// beam). The two axes are magnified independently (a 28-beam sector becomes ≥ 480 pixels tall).
/// @throws ValueError when the image is empty or its bin length is not > 0, or when
///         polar.bearing_rad does not hold one bearing per row.
cv::Mat polarFigure(const PolarImage& polar, const std::string& title);

/// makeCartesianImage(polar, pixel_size_m, beam_width_rad) with the sonar at (0, 0), seen from
/// above: "ahead" (m, bearing 0) up, "starboard" (m, bearing 90°) right; pixels no beam covers are black
/// (intensity 0).
/// @throws ValueError as makeCartesianImage.
cv::Mat cartesianFigure(const PolarImage& polar, double pixel_size_m, double beam_width_rad, const std::string& title);

}  // namespace sonarmap
