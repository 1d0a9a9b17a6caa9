#pragma once
/// @file scan_matcher.hpp
/// Registration of two scans' points (scan_forming.hpp) in the plane: a probabilistic ICP, point-to-line
/// where the target is locally straight (a wall) and along the target's view elsewhere (a pile: the
/// side facing its sonar), each pair weighted by both points' covariances (Montesano et al. 2005,
/// "Probabilistic scan matching for motion estimation in unstructured environments", IROS; its MSIS
/// form MSISpIC, Mallios et al. 2014), leaving out source points beyond the end of the target's
/// surface as its sonar saw it (Rusinkiewicz & Levoy 2001, "Efficient variants of the ICP
/// algorithm", 3DIM: pairs on boundaries rejected); and a correlative search (Olson 2009, "Real-time correlative scan matching", ICRA) over
/// the prior's window as the fallback when ICP's basin is too small or the features few or
/// repetitive. Ambiguous matches (one long wall: free along it; a row of equal piles: several equal
/// peaks) are reported with the reason, so a caller can refuse them.
///
/// Frames: the target's points and the result are in one frame (e.g. NED's plane, pose2.hpp); the
/// source's points are in their own frame; the match is the pose of the source frame in the target
/// frame.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sonarmap/slam/pose2.hpp"
#include "sonarmap/slam/pose2_covariance.hpp"
#include "sonarmap/slam/scan_forming.hpp"

namespace sonarmap {

/// Options of matchScans.
struct ScanMatchOptions {
  int max_iterations = 40;          ///< Gauss–Newton iterations of the ICP, ≥ 1
  /// Correspondence gate: a pair is used while its squared Mahalanobis distance (point-to-point, 2
  /// degrees of freedom) stays below this; 9.21 is χ²₂'s 99 % quantile.
  double gate_chi2 = 9.21;
  std::size_t min_pairs = 12;       ///< fewest pairs of an accepted match, ≥ 3
  double min_overlap = 0.25;        ///< least share of the source's points paired, (0, 1]
  /// Translation information of an accepted match may be at most this many times weaker in its
  /// weakest direction than in its strongest (eigenvalues): beyond, the match slides along one
  /// direction (a long straight wall) and is reported ambiguous. ≥ 1; 25: a σ ratio of 5.
  double max_information_ratio = 25.0;
  /// Correlative search: the best pose must score at least this much higher (ratio, ≥ 1) than the
  /// best second peak (CorrelativeResult::distinct_score), else the match is ambiguous
  /// (repetitive or too few features).
  double min_peak_ratio = 1.15;
  int max_search_steps = 41;        ///< cells across the search window per axis, ≥ 3 (coarser cells beyond)

  /// @throws ValueError naming the field when out of range.
  void validate() const;
};

/// The outcome of a match.
struct ScanMatch {
  bool accepted = false;
  /// Why not accepted ("too few pairs: 5 of 80 points", "ambiguous: constrained along one
  /// direction only (a long straight wall)", …); empty when accepted.
  std::string reason;
  Pose2 pose;  ///< the source frame in the target frame
  /// Information of `pose` (x, y, yaw; 1/m², 1/rad²): the ICP's Gauss–Newton Hessian of the pairs'
  /// weighted residuals, scaled down when the residuals are larger than their covariances say. A
  /// match along one wall has no information along it.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  std::size_t pairs = 0;       ///< pairs of the last ICP iteration
  double overlap = 0.0;        ///< pairs / source points
  double mean_chi2 = 0.0;      ///< mean squared Mahalanobis residual per degree of freedom
  bool searched = false;       ///< the correlative search ran
  double peak_ratio = 0.0;     ///< its best score over the best distinct one (0: not run)
  /// The search's score surface's information (CorrelativeResult::information; zero: not run).
  Eigen::Matrix3d surface_information = Eigen::Matrix3d::Zero();
  /// The translation's least measured direction (unit, the target's frame): the weakest of the
  /// pairs' information, or of the surface's where that decided the match ambiguous.
  Eigen::Vector2d along_m = Eigen::Vector2d::UnitX();
};

/// What the correlative search scores a source point by: the distance to the nearest target point
/// (kSamples), or to the nearest target point or stretch of wall between them (kSurfaces: each target
/// point on a line drawn as far as its neighbours reach either side of it, SurfaceSegment). Two
/// turns of a head moving along a straight wall sample it at the same offsets from the vehicle, so
/// to its samples the likelihood peaks at no motion; to the wall it does not.
enum class SearchField { kSamples, kSurfaces };

/// A disc a target scan's beams heard (its sonar's position, the target's frame, and its reach,
/// metres): a source point outside every disc falls where the target has no observation, and
/// says nothing about the pose (a scan sees farther ahead than the scans before it did).
struct CoverageDisc {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
};

/// Matches `source` (points in its own frame) against `target` (points in the target frame),
/// starting from `initial` (the source frame in the target frame) whose uncertainty is
/// `prior_covariance` (x, y, yaw; m², rad²). With `search`, a correlative search over
/// ±3σ of the prior (at most ±20° and max_search_steps cells per axis) finds the start of the ICP;
/// without, the ICP starts at `initial` and the search runs only when the ICP does not converge
/// to enough pairs. `coverage` (the target scans' reach, the target's frame; empty: everywhere)
/// leaves the source's points no target scan heard out of the search's score (correlativeSearch).
/// With `bound_by_surface`, a searched match's information is no more, in any direction, than the
/// search's score surface gives (CorrelativeResult::information; the generalised eigenbasis of the
/// two, each eigenvalue above the pairs' cut to it), so a direction the surface leaves flat (two
/// parallel walls) is reported "constrained along one direction only". Deterministic.
/// @throws ValueError for invalid options or a prior covariance that is not finite.
ScanMatch matchScans(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                     const Pose2& initial, const Eigen::Matrix3d& prior_covariance, bool search,
                     const ScanMatchOptions& options = {}, SearchField field = SearchField::kSamples,
                     const std::vector<CoverageDisc>& coverage = {}, bool bound_by_surface = false);

/// ICP from `initial` (the source frame in the target frame) with no prior: the pose the pairs alone
/// give, judged as matchScans judges; no correlative search. What a match measures independently of
/// the dead reckoning that started it (navigation_calibration.hpp). Deterministic.
/// @throws ValueError for invalid options.
ScanMatch matchScansFrom(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source, const Pose2& initial,
                         const ScanMatchOptions& options = {});

/// The best pose of a correlative search (Olson 2009), how distinct its peak is, and what the whole
/// score surface says of the pose.
struct CorrelativeResult {
  Pose2 pose;
  double score = 0.0;          ///< mean likelihood of the source's points a target scan heard, [0, 1]
  /// Score of the best second peak: a local maximum of the translations (best heading each) farther
  /// than max(3 cells, 2σ) from `pose`'s, with a valley below 90 % of it between the two; 0: none.
  double distinct_score = 0.0;
  /// The posterior's mean over the grid (the scans' likelihood times the prior's density).
  Pose2 posterior_pose;
  /// The information (x, y, yaw; 1/m², 1/rad², the target's frame) the score surface adds to the
  /// prior's: Σ_post⁻¹ − Σ_prior⁻¹ of the posterior over the grid, its negative directions 0 (Olson
  /// 2009, §IV-C, the covariance from the score distribution). Along a direction the surface is
  /// flat (one straight wall, two parallel walls) it is about 0, whatever the pairs' Hessian says;
  /// across several equal peaks it is as weak as their spread. Within the grid's cell it says
  /// nothing finer (a peak one cell wide gives a very large value).
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
};

/// A stretch of surface the target's points lie on (the target's frame, metres), drawn into the
/// correlative search's likelihood field between them: a wall's likelihood is then the distance to
/// the wall, not to its samples, whose pattern repeats at no motion (each turn of a head samples a
/// straight wall at the same offsets from itself).
struct SurfaceSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

/// Exhaustive search of poses initial ⊕ (dx, dy, dyaw) over ±3σ of `prior_covariance` (x, y, yaw;
/// m², rad²; the translation's window square, at most 10 km, the heading's at most ±20°), on a grid
/// of at most `max_steps` cells per axis (cells no finer than sigma_m / 2), scoring each by the
/// mean over the source's points of exp(−d²/2σ²), d the distance to the nearest target point or
/// `surfaces` segment (a likelihood field from OpenCV's distance transform). With `coverage`, a
/// source point outside every disc is left out of a pose's score (and of its posterior's
/// likelihood, where it stands in at the mean of the heard ones); a pose that leaves most of the
/// source unheard scores 0. Without, every point is heard.
CorrelativeResult correlativeSearch(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                    const Pose2& initial, const Eigen::Matrix3d& prior_covariance, double sigma_m,
                                    int max_steps, const std::vector<SurfaceSegment>& surfaces = {},
                                    const std::vector<CoverageDisc>& coverage = {});

/// The points' typical σ, metres: the median of √trace of their covariances (at least 1 mm); what
/// the correlative search's likelihood field is smoothed by. 1 mm for no points.
double typicalPointSigma(const std::vector<ScanPoint>& points);

/// How well each of `source`'s points fits `target` with the source placed at each of `poses` (the
/// source frame in the target frame): exp(−d²/2σ²), d the distance to the nearest target point, σ =
/// typicalPointSigma(source), as the correlative search scores a pose (Olson 2009), in [0, 1]; shape
/// poses.size() × source.size(), zeros when either side is empty. What two hypotheses of one match
/// are compared by.
std::vector<std::vector<double>> pointLikelihoods(const std::vector<ScanPoint>& target, const std::vector<ScanPoint>& source,
                                                  const std::vector<Pose2>& poses);

}  // namespace sonarmap
