#pragma once
/// @file polar.hpp
/// Polar images of beams and their top-view Cartesian rendering (paper §2.1, Figs. 3 and 4).

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "sonarmap/sonar/beam.hpp"
#include "sonarmap/sonar/png_writer.hpp"  // writePng, used with these images
#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// Builds the polar image of beams [first, last_exclusive): row r is beam first + r, column c is
/// bin c. Columns = the largest bin count of the range; shorter beams are padded with 0 and
/// `valid_bins[r]` keeps their real count. Bearings and times are copied per row.
///
/// @param beams           the beam list (e.g. SonarLog::beams).
/// @param first           index of the first beam.
/// @param last_exclusive  one past the last beam; first < last_exclusive ≤ beams.size().
/// @return                a PolarImage, `intensities` CV_8U of (last_exclusive − first) × max bins.
/// @throws ValueError  when the range is empty or out of bounds, when a beam has no bins, or when
///   the beams do not all share one bin length (the message names the beam and both lengths).
PolarImage makePolarImage(const std::vector<Beam>& beams, std::size_t first, std::size_t last_exclusive);

/// Renders a polar image as a top view, seen from above: the sonar at the centre pixel, +x
/// (bearing 0, ahead) up, +y (bearing π/2, starboard: bearings turn clockwise, beam.hpp) right. The image is square, of side 2·ceil(R / pixel_size_m) + 1
/// pixels with R = cols × bin_length_m, CV_8U; pixels no beam covers are 0.
///
/// Angle interpolation (paper §2.1, Fig. 4), by our own polar lookup (not cv::warpPolar, which
/// assumes rows evenly spread over 360°; sweeps here may be sectors or have gaps):
/// for each pixel, range r selects bin floor(r / bin_length_m) (nearest-bin in range), and its
/// bearing θ falls between the two rows whose bearings bracket it (rows sorted by bearing, circularly).
///   - If those two neighbours are at most `beam_width_rad` apart, their footprints touch and the
///     value is interpolated linearly in angle between them.
///   - Otherwise each beam only fills ±beam_width_rad/2 around its own bearing with its own value.
/// A single beam at bearing 0 thus lights a wedge upwards of half-angle beam_width_rad/2.
///
/// @param polar           a polar image with bin_length_m > 0 and at least one row.
/// @param pixel_size_m    side of one pixel in metres, > 0.
/// @param beam_width_rad  horizontal beam width in radians, in (0, 2π]; the Micron's is about 3°.
/// @throws ValueError  on an empty image, non-positive pixel size or bin length, a beam width out of
///   range, or an output side above 20,000 pixels.
cv::Mat makeCartesianImage(const PolarImage& polar, double pixel_size_m, double beam_width_rad);

}  // namespace sonarmap
