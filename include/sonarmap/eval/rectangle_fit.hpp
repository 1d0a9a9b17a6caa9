#pragma once
/// @file rectangle_fit.hpp
/// A map-quality measure for a rectangular tank: fit a rectangle to the occupied cells of a 2D map
/// and report how well the cells trace its four walls.
///
/// The paper's data were recorded in a square water tank with a floater (paper §2.1). A good map's
/// occupied cells lie on the four walls; a bad one shows, for instance, a ring of false obstacles
/// at the constant range where the floor or surface enters the beam. evaluateWalls() turns that
/// into numbers: the share of cells on the walls, the share of the outline they cover and their
/// RMS distance to it.
///
/// Frame: every point and the fitted rectangle are 2D, in metres, in one planar frame of the
/// caller's choice (typically the sonar's horizontal plane with the sonar at the origin). Nothing
/// here depends on where the origin is.

#include <Eigen/Core>

#include <cstddef>
#include <numbers>
#include <vector>

namespace sonarmap {

/// A rectangle of any orientation in the plane.
///
/// Canonical form returned by fitRectangle(): angle_rad in [0, π/2); width_m is the side along the
/// unit vector (cos angle_rad, sin angle_rad), height_m the side along (−sin angle_rad, cos angle_rad).
/// Every rectangle has exactly one such form, so a rectangle whose long side points at 100° comes
/// back with angle_rad = 10° and its long side as height_m.
struct RectangleFit {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();  ///< centre, metres, in the points' frame
  double angle_rad = 0.0;                              ///< direction of the width side, radians
  double width_m = 0.0;                                ///< side length along angle_rad, metres
  double height_m = 0.0;                               ///< side length perpendicular to it, metres

  /// The four corners in counter-clockwise order, metres, in the points' frame.
  std::vector<Eigen::Vector2d> corners() const;
};

/// Parameters of fitRectangle() and evaluateWalls(). All lengths in metres.
struct WallFitOptions {
  /// A point is "on a wall" when its distance to the rectangle's outline is at most this.
  /// Also the half-width of the band whose points refine a wall's position. Must be > 0.
  double wall_tolerance_m = 0.15;
  /// Length of the outline bins that wall_coverage counts. Must be > 0.
  double coverage_bin_m = 0.10;
  /// Step of the orientation search over [0, π/2). Must be in (0, π/2].
  double angle_step_rad = 0.5 * std::numbers::pi / 180.0;
  /// Width of the sliding window of the wall histograms (evaluated every histogram_bin_m / 5).
  /// About the thickness of a wall in the map (cell size plus noise). Must be > 0.
  double histogram_bin_m = 0.05;
  /// A histogram window is a wall candidate when it holds at least this fraction of the axis's
  /// highest window. Lower finds faint walls, higher ignores stronger multipath. In (0, 1].
  double peak_fraction = 0.25;
  /// When the outermost candidates of one axis are closer than this, that axis shows one wall only
  /// and the other is placed at the end of the perpendicular walls (partial outlines). Must be ≥ 0.
  double min_side_m = 0.5;
  /// Rounds of refinement (inliers → joint line fit of orientation → wall positions). Must be ≥ 0.
  int refine_iterations = 5;
};

/// How well a set of occupied cells traces a rectangular tank.
struct WallFitReport {
  RectangleFit rect;               ///< the fitted rectangle (see fitRectangle())
  std::size_t points = 0;          ///< number of points evaluated
  double share_on_walls = 0.0;     ///< share of points within wall_tolerance_m of the outline, [0, 1]
  /// Share of the outline, cut into bins of about coverage_bin_m along each side, whose bin holds
  /// the nearest outline point of at least one on-wall point, [0, 1].
  double wall_coverage = 0.0;
  double rms_wall_distance_m = 0.0;  ///< RMS distance of on-wall points to the outline, metres (0 if none)
};

/// Fits a rectangle (centre, orientation, two side lengths) to points that trace its outline.
///
/// Method (deterministic, O(n · angles + angles · bins), Eigen only):
///  1. Orientation search: for each angle θ on a grid of angle_step_rad over [0, π/2), project the
///     points on the axes u = (cos θ, sin θ) and v = (−sin θ, cos θ) and histogram each projection
///     with a sliding window of histogram_bin_m. Walls are lines, so at the right θ each wall falls
///     into few windows; the score is the sum of squared window counts of both axes and the best
///     θ is kept (lowest θ on ties).
///  2. Walls: on each axis the walls are the outermost windows holding at least peak_fraction of
///     the axis's highest window (each moved to the local maximum next to it). Clutter inside
///     (a floater) is not outermost; multipath behind the walls is spread over tens of centimetres
///     and stays below the threshold. If the two candidates of an axis are closer than min_side_m
///     only one wall is visible and the other is placed at the far end of the perpendicular walls.
///  3. Refinement, refine_iterations times: assign every point within wall_tolerance_m of the
///     outline to its nearest side; a side holding fewer than peak_fraction of the best side's
///     points is no wall and is from then on placed like a missing one (two opposite walls give a
///     flat histogram on the other axis); re-estimate θ by a joint total-least-squares fit of the
///     four sides' point sets with a shared direction (sides two by two perpendicular); set each
///     seen side's position to the mean of its points' perpendicular coordinates.
///
/// Accuracy on synthetic outlines (σ 2 cm, with 25 % floater and 10 % multipath): sides within
/// 1 cm, angle within 0.1°. A missing wall lies at the last perpendicular wall point, a few
/// centimetres outside (noise at the wall's end). Limits: a ghost wall behind a real one that is
/// as dense and straight as a wall is taken for the wall; so is a straight line of clutter when it
/// is the outermost strong line on its axis.
///
/// @param points_m  occupied cells, metres, any planar frame; at least 8, all finite.
/// @param options   see WallFitOptions.
/// @return the rectangle in canonical form (see RectangleFit). On data without a rectangle (a ring
///         of false obstacles) it still returns the best rectangle; evaluateWalls() says how bad it is.
/// @throws ValueError if there are fewer than 8 points, a coordinate is not finite, an option is out
///         of range, or the points span more than 10 million histogram windows.
RectangleFit fitRectangle(const std::vector<Eigen::Vector2d>& points_m, const WallFitOptions& options = {});

/// Fits a rectangle with fitRectangle() and measures how well the points trace its outline:
/// share_on_walls, wall_coverage and rms_wall_distance_m (see WallFitReport).
///
/// Reading it for a square tank of about 4.4 × 4.6 m: a good map gives sides near those sizes,
/// wall_coverage near 1 and share_on_walls equal to the share of cells that are truly walls; a
/// ring of false obstacles gives a small rectangle (about the ring's diameter) with low coverage.
///
/// @param points_m  occupied cells, metres, any planar frame; at least 8, all finite.
/// @param options   see WallFitOptions.
/// @throws ValueError as fitRectangle().
WallFitReport evaluateWalls(const std::vector<Eigen::Vector2d>& points_m, const WallFitOptions& options = {});

}  // namespace sonarmap
