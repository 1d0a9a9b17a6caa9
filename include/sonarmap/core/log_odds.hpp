#pragma once
/// @file log_odds.hpp
/// Log-odds arithmetic and the occupancy parameters of the inverse sensor model (paper §4, §5.2).
///
/// The recursive Bayes update of eq. (1) with a uniform prior P(n) = 0.5 becomes an addition in
/// log-odds: L(n | z_1:t) = L(n | z_1:t-1) + L(n | z_t), clamped to [clamp_min, clamp_max]
/// (Hornung et al. 2013, eq. 2-3). Defaults are OctoMap's.

#include <cmath>
#include <string>

#include "sonarmap/core/errors.hpp"

namespace sonarmap {

/// log(p / (1 - p)). @param probability in (0, 1).
inline float logOdds(double probability) {
  return static_cast<float>(std::log(probability / (1.0 - probability)));
}

/// Inverse of logOdds: 1 / (1 + exp(-l)).
inline double probability(float log_odds) { return 1.0 / (1.0 + std::exp(-static_cast<double>(log_odds))); }

/// Three-way classification of a log-odds value against the two thresholds (paper §5.2).
enum class Occupancy { kFree, kUnknown, kOccupied };

/// How inner nodes summarise their children (paper §5.3.1).
enum class InnerAggregation {
  kMax,   ///< the largest child log-odds: conservative, OctoMap's choice, the default
  kMean,  ///< the mean log-odds of the existing children
};

/// Parameters of the occupancy update. All probabilities are in (0, 1).
struct OccupancyParams {
  double prob_hit = 0.7;        ///< P(occupied | hit), OctoMap's default
  double prob_miss = 0.4;       ///< P(occupied | miss)
  double clamp_min = 0.1192;    ///< lower clamping probability (log-odds −2)
  double clamp_max = 0.971;     ///< upper clamping probability (log-odds +3.511)
  double occupied_above = 0.5;  ///< a node is occupied when its probability is above this
  double free_below = 0.5;      ///< a node is free when its probability is at or below this
                                ///< (equal thresholds: nothing is unknown once observed)

  /// @throws ValueError when a probability is outside (0, 1) or the order
  /// clamp_min ≤ free_below ≤ occupied_above ≤ clamp_max, prob_miss < 0.5 < prob_hit is violated.
  void validate() const {
    auto check = [](double p, const char* name) {
      if (!(p > 0.0 && p < 1.0)) throw ValueError(std::string(name) + " must be a probability in (0, 1), got " + std::to_string(p));
    };
    check(prob_hit, "prob_hit");
    check(prob_miss, "prob_miss");
    check(clamp_min, "clamp_min");
    check(clamp_max, "clamp_max");
    check(occupied_above, "occupied_above");
    check(free_below, "free_below");
    if (!(prob_hit > 0.5 && prob_miss < 0.5)) throw ValueError("prob_hit must exceed 0.5 and prob_miss be below 0.5");
    if (!(clamp_min <= free_below && free_below <= occupied_above && occupied_above <= clamp_max)) {
      throw ValueError("thresholds must satisfy clamp_min <= free_below <= occupied_above <= clamp_max");
    }
  }
};

/// The parameters converted to log-odds once, for the update loop.
struct LogOddsModel {
  float hit;
  float miss;
  float clamp_min;
  float clamp_max;
  float occupied_above;
  float free_below;

  /// @throws ValueError if `params` is invalid (see OccupancyParams::validate).
  static LogOddsModel from(const OccupancyParams& params) {
    params.validate();
    return {logOdds(params.prob_hit),   logOdds(params.prob_miss),      logOdds(params.clamp_min),
            logOdds(params.clamp_max),  logOdds(params.occupied_above), logOdds(params.free_below)};
  }

  /// Adds `delta` to `value` and clamps to [clamp_min, clamp_max].
  float update(float value, float delta) const {
    const float sum = value + delta;
    return sum < clamp_min ? clamp_min : (sum > clamp_max ? clamp_max : sum);
  }

  /// True when adding `delta` cannot change `value` any more: clamped in the update's direction
  /// (the stability check of paper §5.3), or the update is zero.
  bool isStable(float value, float delta) const {
    return delta == 0.0F || (delta > 0.0F && value >= clamp_max) || (delta < 0.0F && value <= clamp_min);
  }

  Occupancy classify(float value) const {
    if (value > occupied_above) return Occupancy::kOccupied;
    if (value <= free_below) return Occupancy::kFree;
    return Occupancy::kUnknown;
  }

  bool isOccupied(float value) const { return value > occupied_above; }
};

}  // namespace sonarmap
