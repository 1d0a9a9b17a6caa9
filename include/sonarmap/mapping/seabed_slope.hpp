#pragma once
/// @file seabed_slope.hpp
/// A seabed's local slope from where weak extended returns start, so that a beam's
/// seabed trace (appendLevelTrace, sweep_fan.hpp) follows the seabed instead of the level through
/// its onset.
///
/// A down-looking cone's seabed return starts on the aperture's lowest edge (appendLevelTrace): the
/// onset point, sonar + onset range × that edge's direction, lies on the seabed whatever its slope.
/// A sweep's onsets cover a narrow fan ahead of a tilted head, too little to fit a plane (on
/// quay3d, fitted slopes of 0–19° in varying directions on a 7° seabed); the onsets of
/// every sweep so far, around the vehicle's track, do. SeabedSlope keeps them and fits, around a
/// point, a plane z = a + g · (x, y) to those within a horizontal radius: least median of squares
/// over triples of onsets (Rousseeuw 1984, JASA 79(388) 871), since some onsets are no seabed (a
/// weak echo of a wall or a pile heard by a beam without an obstacle), then least squares over its
/// inliers (2.5 robust deviations; Rousseeuw & Leroy 1987). It keeps the plane only where the data
/// ask for a slope: the F test of the plane against a level fit over the same points (two more
/// parameters) at 1 % (F > 4.61, the large-sample critical value χ²₂(0.99) / 2; Draper & Smith,
/// "Applied Regression Analysis", 3rd ed. 1998, §6), a slope of at most 30° (steeper ground is no
/// seabed met at grazing incidence), and onsets seen from many directions. The last because an
/// onset's error depends on the way its beam looks: a weak return is heard late, the more so where
/// the ground falls away from the beam (a smaller grazing angle on the edge ray, a weaker echo), so
/// onsets seen down a slope lie too deep and onsets seen up it too high. Seen from one way only (a
/// static head: its forward fan), they show the slope exaggerated (a 10° seabed fitted at 39°);
/// seen from opposite ways (a vehicle that turns), the errors cancel (quay3d's 7.1° seabed fitted
/// at 6.7–7.1° on the tilted loop). The inliers' look directions must therefore spread: the length
/// of their mean unit horizontal vector (the mean resultant length of directional statistics;
/// Mardia & Jupp, "Directional Statistics", 2000, §2.3.1) at most 0.5, where a fan of ±60° gives
/// 0.83 and a full turn 0. Elsewhere the surface stays level (the flat-seabed hypothesis of
/// sidescan slant-range correction; Blondel 2009).

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace sonarmap {

class SeabedSlope {
 public:
  /// Fewest onsets (after trimming) a plane is fitted to; fewer give the level.
  static constexpr std::size_t kMinOnsets = 30;
  /// Most onsets kept: the newest, so that a long mission's cost per beam stays bounded.
  static constexpr std::size_t kCapacity = 4096;

  /// Keeps an onset point, map frame (z up), metres, and the horizontal direction its beam looked
  /// (map frame, any length; normalised here). Non-finite points and vertical looks are ignored.
  void add(const Eigen::Vector3d& onset_m, const Eigen::Vector2d& look);

  /// The seabed's unit normal (map frame, z component > 0) around `at_m`: fitted to the onsets
  /// within `radius_m` horizontally (see the file's comment), or +z (level) where they are too few
  /// or do not ask for a slope. Nothing is thrown.
  Eigen::Vector3d normalAt(const Eigen::Vector3d& at_m, double radius_m) const;

  /// Where the seabed fitted around `at_m` lies (see the file's comment): the least-median-of-squares
  /// plane of the onsets within `radius_m` horizontally, with the robust deviation of their
  /// heights about it (Rousseeuw & Leroy 1987). A point's height over the seabed is
  /// `heightAbove`; a point more than kInlierDeviations deviations above is no seabed.
  struct Fit {
    Eigen::Vector3d at_m;     ///< where the plane was fitted, map frame
    Eigen::Vector3d plane;    ///< z = plane(0) + plane(1) (x − at.x) + plane(2) (y − at.y)
    double deviation_m = 0;   ///< the robust deviation of the onsets' heights about the plane
    /// The inliers' look directions spread (their mean resultant length at most 0.5): seen from
    /// around, their errors cancel (see the file's comment), so the plane's height can be trusted.
    bool seen_around = false;
    /// Height of `point_m` over the plane, metres (vertical).
    double heightAbove(const Eigen::Vector3d& point_m) const;
  };
  /// The fit around `at_m`, nullopt where fewer than kMinOnsets onsets lie within `radius_m` or they
  /// span no plane. Nothing is thrown.
  std::optional<Fit> fitAround(const Eigen::Vector3d& at_m, double radius_m) const;
  /// Inliers lie within this many robust deviations of the plane (Rousseeuw & Leroy 1987).
  static constexpr double kInlierDeviations = 2.5;
  std::size_t size() const { return onsets_.size(); }

 private:
  struct Onset {
    Eigen::Vector3d point_m;
    Eigen::Vector2d look;  ///< unit
  };
  /// The robust fit to the onsets within `radius_m` of `at_m` horizontally (fitAround), and those
  /// onsets relative to `at_m` with their looks in `near` and `looks` (cleared first).
  std::optional<Fit> robustFit(const Eigen::Vector3d& at_m, double radius_m, std::vector<Eigen::Vector3d>& near,
                               std::vector<Eigen::Vector2d>& looks) const;

  std::vector<Onset> onsets_;
  std::size_t next_ = 0;  ///< where the next onset goes once full
};

}  // namespace sonarmap
