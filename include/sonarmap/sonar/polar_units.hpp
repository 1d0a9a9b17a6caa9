#pragma once
/// @file polar_units.hpp
/// Physical units on a polar image: lengths along the beam in bins, angles across beams in rows,
/// echo levels in intensity counts. Every option of the filters and detectors is given in metres,
/// radians or dB and converted here with each log's own bin length, beam spacing and intensity
/// scale, so that a default means the same on a 5 m Micron log (1.25 cm bins) and on a 50 m
/// Ping360 log (4 cm samples).

#include "sonarmap/sonar/polar_image.hpp"

namespace sonarmap {

/// dB span of the intensity scale 0…255 assumed when the log does not record it: MSIS heads
/// log-compress the echo into 8 bits over the span their AD converter is set to (Tritech's
/// ADspan). The SeaNet log of ../shared/data records 46.7 dB; the simulator's Micron uses 45 dB.
inline constexpr double kDefaultIntensitySpan_db = 45.0;

/// Whole bins in `length_m` along a beam of `bin_length_m` bins, rounded to nearest, clamped to
/// [min_bins, max_bins]. Never overflows: a length of 10⁹ m gives max_bins.
/// @throws ValueError when length_m is negative or NaN, bin_length_m is not finite and > 0, or
///         min_bins > max_bins.
int binsForLength(double length_m, double bin_length_m, int min_bins, int max_bins);

/// Index of the first bin whose centre, (bin + 0.5) × bin_length_m, is at or beyond `range_m`,
/// clamped to [0, max_bin]. Never overflows.
/// @throws ValueError when range_m is negative or NaN or bin_length_m is not finite and > 0.
int firstBinAtOrBeyond(double range_m, double bin_length_m, int max_bin);

/// The bearing step between consecutive rows of `polar`, radians: the median of the absolute
/// wrapped differences that are not zero; 0 for an image of fewer than two distinct bearings.
double beamSpacing_rad(const PolarImage& polar);

/// Whole rows (beams) in `angle_rad` across beams spaced `spacing_rad`, rounded to nearest,
/// clamped to [min_rows, max_rows]; min_rows when the spacing is 0.
/// @throws ValueError when angle_rad is negative or NaN or min_rows > max_rows.
int rowsForAngle(double angle_rad, double spacing_rad, int min_rows, int max_rows);

/// dB span of the intensity scale of `polar`: its intensity_span_db when the log recorded it,
/// else kDefaultIntensitySpan_db.
double intensitySpan_db(const PolarImage& polar);

/// Intensity counts (of 0…255) that `level_db` spans on a scale of `span_db` per 255 counts.
/// @throws ValueError when level_db is negative or NaN or span_db is not finite and > 0.
double countsForDb(double level_db, double span_db);

}  // namespace sonarmap
