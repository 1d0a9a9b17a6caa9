/// @file beam_cells.cpp
/// A sweep's beams as the volume inversion takes them (see beam_cells.hpp).

#include "beam_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {

namespace {
/// Where beam `row` heard water up to, metres.
double waterRange_m(const BeamDetection& detection, double valid_m, double tolerance_m) {
  double first_echo_m = std::min(detection.echo_onset_m, valid_m);
  if (detection.hasObstacle()) first_echo_m = std::min(first_echo_m, detection.range_m);
  return std::max(0.0, first_echo_m - tolerance_m);
}
}  // namespace

std::vector<CellBeam> cellBeams(const PolarImage& polar, const std::vector<BeamDetection>& detections,
                                          double cell_m, double tolerance_m) {
  const int rows = polar.rows(), cols = polar.cols();
  const double bin_m = polar.bin_length_m;
  const double db_per_count = intensitySpan_db(polar) / 255.0;
  std::vector<double> power_of_count(256);
  for (int count = 0; count < 256; ++count) power_of_count[count] = std::pow(10.0, count * db_per_count / 10.0);
  std::vector<CellBeam> beams(static_cast<std::size_t>(rows));
  // The water's level per column, from the bins before each beam's first echo.
  std::vector<double> sum(static_cast<std::size_t>(cols), 0.0);
  std::vector<std::size_t> samples(static_cast<std::size_t>(cols), 0);
  for (int row = 0; row < rows; ++row) {
    const int valid = polar.valid_bins[static_cast<std::size_t>(row)];
    beams[row].water_range_m = waterRange_m(detections[row], valid * bin_m, tolerance_m);
    const int water_bins = std::min(valid, static_cast<int>(beams[row].water_range_m / bin_m));
    const std::uint8_t* intensity = polar.intensities.ptr<std::uint8_t>(row);
    for (int col = 0; col < water_bins; ++col) {
      sum[col] += power_of_count[intensity[col]];
      ++samples[col];
    }
  }
  std::vector<double> level(static_cast<std::size_t>(cols), std::numeric_limits<double>::quiet_NaN());
  for (int col = 0; col < cols; ++col) {
    if (samples[col] >= kMinWaterSamples) level[col] = sum[col] / static_cast<double>(samples[col]);
  }
  // Columns without enough water: the nearest column's level (earlier first, then later).
  double carried = std::numeric_limits<double>::quiet_NaN();
  for (int col = 0; col < cols; ++col) {
    if (std::isnan(level[col])) level[col] = carried; else carried = level[col];
  }
  carried = std::numeric_limits<double>::quiet_NaN();
  for (int col = cols - 1; col >= 0; --col) {
    if (std::isnan(level[col])) level[col] = carried; else carried = level[col];
  }
  if (cols > 0 && std::isnan(level[0])) {  // no water anywhere: the quietest quarter of the sweep
    std::vector<double> powers;
    for (int row = 0; row < rows; ++row) {
      const std::uint8_t* intensity = polar.intensities.ptr<std::uint8_t>(row);
      for (int col = 0; col < polar.valid_bins[row]; ++col) powers.push_back(power_of_count[intensity[col]]);
    }
    if (powers.empty()) return beams;
    std::sort(powers.begin(), powers.end());
    double quiet = 0.0;
    const std::size_t quarter = std::max<std::size_t>(1, powers.size() / 4);
    for (std::size_t i = 0; i < quarter; ++i) quiet += powers[i];
    std::fill(level.begin(), level.end(), quiet / static_cast<double>(quarter));
  }
  // Each beam's cells: the mean power over the water of the bins whose centre lies in the cell.
  for (int row = 0; row < rows; ++row) {
    const int valid = polar.valid_bins[static_cast<std::size_t>(row)];
    const auto cells = static_cast<std::size_t>(std::ceil(valid * bin_m / cell_m));
    std::vector<float>& cell_power = beams[row].cell_power;
    cell_power.assign(cells, std::numeric_limits<float>::quiet_NaN());
    std::vector<double> cell_sum(cells, 0.0);
    std::vector<int> cell_bins(cells, 0);
    const std::uint8_t* intensity = polar.intensities.ptr<std::uint8_t>(row);
    for (int col = 0; col < valid; ++col) {
      const auto cell = static_cast<std::size_t>((col + 0.5) * bin_m / cell_m);
      if (cell >= cells) continue;
      cell_sum[cell] += power_of_count[intensity[col]] / level[col];
      ++cell_bins[cell];
    }
    for (std::size_t cell = 0; cell < cells; ++cell) {
      if (cell_bins[cell] > 0) {
        cell_power[cell] = static_cast<float>(cell_sum[cell] / cell_bins[cell]);
      } else {  // a bin longer than the cell: the bin that holds the cell's centre
        const auto col = static_cast<int>((cell + 0.5) * cell_m / bin_m);
        if (col < valid) cell_power[cell] = static_cast<float>(power_of_count[intensity[col]] / level[col]);
      }
    }
  }
  return beams;
}

}  // namespace sonarmap
