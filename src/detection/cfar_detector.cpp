/// @file cfar_detector.cpp
/// CFAR detection along a beam: CA, SO, GO (Richards ch. 6) and OS (Rohling 1983); see cfar.hpp.

#include "sonarmap/detection/cfar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "sonarmap/core/errors.hpp"
#include "sonarmap/sonar/polar_units.hpp"

namespace sonarmap {
namespace {

constexpr int kMaxWindowBins = 65535;  // keeps the window arithmetic far from int overflow

[[noreturn]] void throwOption(const std::string& what) { throw ValueError("CFAR options: " + what); }

void requireLength(double value_m, bool positive, const char* name) {
  if (!(std::isfinite(value_m) && (positive ? value_m > 0.0 : value_m >= 0.0))) {
    throwOption(std::string(name) + (positive ? " must be > 0 m" : " must be >= 0 m"));
  }
}

/// Half-open range of training bins [begin, end).
struct Window {
  int begin = 0;
  int end = 0;
  int size() const { return end - begin; }
};

/// Noise estimate Z of each cell of one beam. CA/SO/GO read window sums from prefix sums (O(1) per
/// cell); OS copies the training cells into a scratch buffer and selects the k-th (O(T) per cell).
class NoiseEstimator {
 public:
  NoiseEstimator(std::span<const std::uint8_t> beam, const CfarCells& options)
      : beam_(beam), options_(options), prefix_(beam.size() + 1, 0) {
    for (std::size_t i = 0; i < beam.size(); ++i) prefix_[i + 1] = prefix_[i] + beam[i];
  }

  /// Z of cell c, or nullopt when neither training window lies inside the beam.
  std::optional<double> at(int c) {
    const int gap = options_.guard_bins + 1;
    const int length = static_cast<int>(beam_.size());
    const Window lag{c - gap - options_.training_bins + 1, c - gap + 1};
    const Window lead{c + gap, c + gap + options_.training_bins};
    const bool has_lag = lag.begin >= 0, has_lead = lead.end <= length;
    if (!has_lag && !has_lead) return std::nullopt;
    if (options_.variant == CfarVariant::kOrderedStatistic) {
      return orderedStatistic(has_lag ? lag : Window{}, has_lead ? lead : Window{});
    }
    if (!has_lag || !has_lead) return mean(has_lag ? lag : lead);
    if (options_.variant == CfarVariant::kSmallestOf) return std::min(mean(lag), mean(lead));
    if (options_.variant == CfarVariant::kGreatestOf) return std::max(mean(lag), mean(lead));
    return static_cast<double>(sum(lag) + sum(lead)) / (lag.size() + lead.size());  // CA
  }

 private:
  std::int64_t sum(Window w) const {
    return prefix_[static_cast<std::size_t>(w.end)] - prefix_[static_cast<std::size_t>(w.begin)];
  }
  double mean(Window w) const { return static_cast<double>(sum(w)) / w.size(); }

  /// The k-th smallest of the cells of both windows (an empty window adds none).
  double orderedStatistic(Window lag, Window lead) {
    scratch_.assign(beam_.begin() + lag.begin, beam_.begin() + lag.end);
    scratch_.insert(scratch_.end(), beam_.begin() + lead.begin, beam_.begin() + lead.end);
    const auto n = static_cast<double>(scratch_.size());
    const auto k = static_cast<std::ptrdiff_t>(std::clamp(std::lround(options_.os_rank * n), 1L, std::lround(n)));
    std::nth_element(scratch_.begin(), scratch_.begin() + (k - 1), scratch_.end());
    return scratch_[static_cast<std::size_t>(k - 1)];
  }

  std::span<const std::uint8_t> beam_;
  const CfarCells& options_;
  std::vector<std::int64_t> prefix_;  ///< prefix_[i] = sum of bins [0, i)
  std::vector<std::uint8_t> scratch_;
};

/// Does cell c pass both the CFAR threshold and the intensity floor?
bool passes(NoiseEstimator& noise, std::span<const std::uint8_t> beam, int c, const CfarCells& options,
            std::span<const float> floor) {
  const auto i = static_cast<std::size_t>(c);
  if (floor.empty() ? beam[i] < options.min_intensity : static_cast<float>(beam[i]) < floor[i]) return false;
  const std::optional<double> z = noise.at(c);
  return z.has_value() && beam[static_cast<std::size_t>(c)] > options.scale * *z;
}

void checkProbability(double pfa, int training_cells) {
  if (!(pfa > 0.0 && pfa < 1.0)) throw ValueError("CFAR scale: false-alarm probability must be in (0, 1)");
  if (training_cells < 1) throw ValueError("CFAR scale: training cells must be >= 1");
}

}  // namespace

void CfarCells::validate() const {
  if (training_bins < 1 || training_bins > kMaxWindowBins) {
    throwOption("training_bins must be in [1, 65535], got " + std::to_string(training_bins));
  }
  if (guard_bins < 0 || guard_bins > kMaxWindowBins) {
    throwOption("guard_bins must be in [0, 65535], got " + std::to_string(guard_bins));
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) throwOption("scale must be finite and > 0");
  if (!(os_rank > 0.0 && os_rank <= 1.0)) throwOption("os_rank must be in (0, 1]");
  if (min_intensity < 0 || min_intensity > 255) throwOption("min_intensity must be in [0, 255]");
  if (min_run_bins < 1) throwOption("min_run_bins must be >= 1, got " + std::to_string(min_run_bins));
}

std::vector<float> cfarThresholds(std::span<const std::uint8_t> beam, const CfarCells& options) {
  options.validate();
  NoiseEstimator noise(beam, options);
  std::vector<float> thresholds(beam.size(), std::numeric_limits<float>::infinity());
  for (int c = 0; c < static_cast<int>(beam.size()); ++c) {
    if (const std::optional<double> z = noise.at(c)) thresholds[static_cast<std::size_t>(c)] = static_cast<float>(options.scale * *z);
  }
  return thresholds;
}

int firstCfarBin(std::span<const std::uint8_t> beam, int min_bin, const CfarCells& options,
                 std::span<const float> floor) {
  options.validate();
  if (min_bin < 0) throw ValueError("CFAR detection: min_bin must be >= 0, got " + std::to_string(min_bin));
  if (!floor.empty() && floor.size() < beam.size()) throw ValueError("CFAR detection: the floor is shorter than the beam");
  NoiseEstimator noise(beam, options);
  int run = 0;
  for (int c = min_bin; c < static_cast<int>(beam.size()); ++c) {
    run = passes(noise, beam, c, options, floor) ? run + 1 : 0;
    if (run == options.min_run_bins) return c - run + 1;
  }
  return -1;
}

void CfarOptions::validate() const {
  requireLength(training_m, true, "the training window");
  requireLength(guard_m, false, "the guard window");
  requireLength(min_echo_length_m, false, "the minimum echo length");
  if (!(scale > 0.0) || !std::isfinite(scale)) throwOption("scale must be finite and > 0");
  if (!(os_rank > 0.0 && os_rank <= 1.0)) throwOption("os_rank must be in (0, 1]");
  if (!(std::isfinite(min_contrast_db) && min_contrast_db >= 0.0)) throwOption("the minimum contrast must be >= 0 dB");
}

CfarCells CfarOptions::cells(double bin_length_m) const {
  validate();
  CfarCells cells;
  cells.variant = variant;
  cells.training_bins = binsForLength(training_m, bin_length_m, 1, kMaxWindowBins);
  cells.guard_bins = binsForLength(guard_m, bin_length_m, 0, kMaxWindowBins);
  cells.scale = scale;
  cells.os_rank = os_rank;
  cells.min_intensity = 0;
  cells.min_run_bins = binsForLength(min_echo_length_m, bin_length_m, 1, kMaxWindowBins);
  return cells;
}

double caCfarScale(double false_alarm_probability, int training_cells) {
  checkProbability(false_alarm_probability, training_cells);
  const double n = training_cells;
  return n * (std::pow(false_alarm_probability, -1.0 / n) - 1.0);
}

double osCfarScale(double false_alarm_probability, int training_cells, int rank) {
  checkProbability(false_alarm_probability, training_cells);
  if (rank < 1 || rank > training_cells) throw ValueError("OS-CFAR scale: rank must be in [1, training cells]");
  const auto pfa = [&](double alpha) {
    double p = 1.0;
    for (int i = 0; i < rank; ++i) p *= (training_cells - i) / (training_cells - i + alpha);
    return p;
  };
  double lo = 0.0, hi = 1.0;
  while (pfa(hi) > false_alarm_probability) hi *= 2.0;  // pfa(0) = 1 > target, pfa → 0 as α → ∞
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (pfa(mid) > false_alarm_probability ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace sonarmap
