#pragma once
/// @file water_evidence.hpp
/// What water looks like to the receiver at one range band, measured on the bins that are water,
/// and the evidence each bin's intensity gives that a return (a surface) is there instead.
///
/// The water of a sweep at a range band is described by the distribution of its excess
/// e = I − B over the band's level B (intensity counts; B: the background percentile of the beams
/// still in water at that range, calibration.hpp). It is measured on water samples only: the bins
/// of the beams not yet past their first return, less the beams inside a return (censored, as a
/// censored mean-level detector censors its largest samples: Rickard & Dillard 1977, IEEE Trans.
/// AES 13; ordered-statistic CFAR: Rohling 1983, IEEE Trans. AES 19). Real water is not one-look
/// speckle: its tail holds fish, bubbles and interference (the CRAS tank's water: 79 % of bins 0,
/// its 99.99th percentile 114 counts; docs/accuracy.md), and it is often clipped at 0 by the
/// receiver's floor. So the distribution is the measured one:
///  - up to the band's 90th percentile q, the histogram of the samples (the body);
///  - beyond q, an exponential tail in counts, P(E > q + x) = P_t · exp(−x / m), with P_t the share
///    of samples beyond q and m their mean excess over q, at least the least tail m₀ the caller
///    gives (fully developed speckle's mean excess over its 90th percentile, 1.41 dB:
///    speckleTailMeanExcess_db, acoustics/speckle.hpp; at least one count): water seen clipped at
///    the receiver's floor, or with a handful of samples beyond q, says little of its tail, and a
///    one-count scale would make the first noise rising out of the floor certain evidence of a
///    return within two bins. In dB an exponential
///    tail is heavier than speckle's (whose log-intensity tail falls as exp(−10^(x/10))), as
///    K-distributed reverberation's is (Abraham & Lyons 2002, IEEE J. Oceanic Eng. 27(4)), and it
///    extrapolates beyond the loudest sample instead of calling everything louder impossible.
/// The alternative, a return, has an unknown level anywhere on the receiver's scale: its intensity
/// is uniform over the 256 counts. A bin's evidence is the log-likelihood ratio
/// λ(e) = ln(1/256) − ln p_water(e), in nats, made non-decreasing in e (a louder bin is never less
/// evidence of a return than a quieter one: where the histogram has a gap, the next louder value's
/// λ applies) and at most −ln(256 p_min) (no value is impossible in water: p_min = 10⁻⁹ per count).
/// Summed over bins (weighted for their correlation, evidence_detector.cpp) it is the evidence of a
/// return against water in log-odds: ln(10)/10 nats per dB of likelihood ratio.

#include <array>
#include <cstdint>
#include <span>

namespace sonarmap {

/// The water of one range band and the evidence of a return it gives (see the file's comment).
class WaterEvidence {
 public:
  /// Excess values represented: e in [−255, 255], index e + 255.
  static constexpr int kExcessValues = 511;
  /// Least probability of any one count in water.
  static constexpr double kMinProbability = 1e-9;

  /// The evidence of a band whose water samples' excess counts are `histogram` (index e + 255,
  /// kExcessValues entries), its tail's mean excess at least `min_tail_scale_counts` (m₀ above,
  /// counts; below 1: 1). An empty histogram gives no evidence either way (λ = 0 everywhere).
  /// @throws ValueError when the histogram does not hold kExcessValues entries or the least tail
  ///         scale is NaN.
  explicit WaterEvidence(std::span<const std::uint32_t> histogram, double min_tail_scale_counts = 1.0);

  /// λ(e) of an excess `excess_counts` (clamped to [−255, 255]), nats.
  float logLikelihoodRatio(int excess_counts) const {
    const int i = (excess_counts < -255 ? -255 : (excess_counts > 255 ? 255 : excess_counts)) + 255;
    if (i > body_index_) {  // the tail: linear in the excess up to the least probability's bound
      const double llr = tail_first_llr_ + (i - body_index_ - 1) / tail_scale_;
      return static_cast<float>(llr < max_llr_ ? llr : max_llr_);
    }
    return llr_[static_cast<std::size_t>(i > lowest_index_ ? i : lowest_index_)];
  }
  /// The band's 90th percentile of the excess, counts (the end of the measured body).
  int bodyEnd() const { return body_end_; }
  /// The tail's mean excess over bodyEnd(), counts (≥ 1).
  double tailScale() const { return tail_scale_; }
  /// Water samples the band held.
  std::uint64_t samples() const { return samples_; }

 private:
  std::array<float, kExcessValues> llr_{};  ///< λ over the body's indices [lowest_index_, body_index_]
  int lowest_index_ = 0;                     ///< the lowest excess seen; below it λ is its λ
  int body_index_ = kExcessValues - 1;       ///< the body's end (all of it for an empty band)
  double tail_first_llr_ = 0.0;              ///< λ one count beyond the body's end
  double max_llr_ = 0.0;                     ///< λ at the least probability
  int body_end_ = 0;
  double tail_scale_ = 1.0;
  std::uint64_t samples_ = 0;
};

}  // namespace sonarmap
