#pragma once
/// @file sweep_fan.hpp
/// Planning the rays that clear a sweep's free space (the mapper's inverse sensor model).
///
/// A beam of horizontal width w clears the wedge from the sonar to its free range (its obstacle,
/// or its full range). The free space of a sweep is the union of its beams' wedges: at each angle,
/// the longest free range among the beams that cover that angle. The planner samples that union
/// on one hierarchical grid of 2^L angles per turn, fine enough for rays to be at most one voxel
/// apart at the longest range: a grid ray of level k starts only where its two coarser neighbours
/// drift a voxel apart, or where the shorter of them ends — before that they cover its cells.
/// Overlapping beams (3° wide every 1.8°) are thus cast once, not twice, and neighbouring rays are
/// neighbours in memory. With w = 0 every beam is one ray from the sonar (paper §6).
///
/// The beam volume: a beam of vertical aperture a is the cone bearing ± w/2 × elevation
/// ± a/2 in its sonar frame (elevation above the sonar's x–y plane). Its free space is the cone's
/// loud core up to the free range; its obstacle a vertical face (or, for planArcs's callers that
/// ask, the shell) at the hit range across both angles (docs/mapping.md). The fan is then a
/// 2D hierarchical grid (grid angle × elevation, the same angular step on both axes): a ray's level
/// is the finer of its two indices' levels, and it starts where its coarser neighbours on that axis
/// drift a voxel apart. The rays are at most one voxel apart at the longest range in both
/// directions, and the cost grows with the volume swept, not with the number of beams. An aperture
/// of 0 is the planar model (the sonar's plane, z = 0 of its frame), ray for ray.

#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace sonarmap {

/// One beam to integrate, in the sonar frame and with the sonar's pose at its time.
struct PlannedBeam {
  Eigen::Isometry3d sonar_to_map;
  double bearing_rad;   ///< sonar frame, [0, 2π)
  double free_range_m;  ///< the beam clears its wedge up to here: its obstacle's range minus the range
                        ///< tolerance, or the beam's full range without one
  double hit_range_m;   ///< range of the obstacle's arc (the echo's leading edge); unused without a hit
  bool hit;             ///< the beam ends in an obstacle
  /// How far the beam saw water, for carving other beams' arcs, metres; < 0: the hit range, or
  /// the free range without a hit (the beam-volume model sets its echo onset here).
  double water_range_m = -1.0;
  /// An extended return placed on the level surface its onset implies (appendLevelTrace), the
  /// beam without a hit: a weak one without an obstacle, or an obstacle's that isLevelReturn calls
  /// level (BeamDetection::extended_onset_m, extended_end_m). NaN: none.
  double trace_onset_m = std::numeric_limits<double>::quiet_NaN();
  double trace_end_m = std::numeric_limits<double>::quiet_NaN();
  /// The unit normal of the surface a trace lies on, map frame: level (+z) unless the mapper
  /// measured the seabed's slope around the onset (SeabedSlope, seabed_slope.hpp). The trace's
  /// surface is the plane through its onset point with this normal.
  Eigen::Vector3d trace_normal = Eigen::Vector3d::UnitZ();
  /// The water surface's height, map frame, metres (MapperOptions::water_surface_depth_m); NaN:
  /// unknown. A level head's weak trace is the seabed's when its onset is nearer than the surface
  /// can enter the cone (appendLevelTrace).
  double surface_z_m = std::numeric_limits<double>::quiet_NaN();
  /// The trace is an obstacle's loud return (isLevelReturn), not a weak one: heard before the
  /// aperture's nominal edge, its onset does not lie where that edge meets the surface, so it
  /// neither measures the seabed's slope nor follows it (SonarMapper).
  bool loud_trace = false;
  /// Where the obstacle's echo ends, metres: the mapper gives the nearer of where its loud echo falls
  /// back (BeamDetection::echo_end_m) and its lit run's end (BeamDetection::extended_end_m), or the
  /// beam's recorded range when neither is measured. A vertical face (ObstacleSurface::kVertical)
  /// reaches no farther: a weak return that goes on behind the loud one (the seabed at a quay's foot,
  /// met by the cone's lower rays) is not the face. NaN: no bound.
  double hit_end_m = std::numeric_limits<double>::quiet_NaN();
  /// Whether the beam is mapped as its trace: no hit, and a trace whose onset is at most its end.
  bool traced() const { return !hit && trace_onset_m <= trace_end_m; }
};

/// A segment to traverse, map frame. Every cell it crosses is free unless it is a hit cell.
struct FreeRay {
  Eigen::Vector3d start_m;
  Eigen::Vector3d end_m;
  /// The ray lies in the outer half of the cone being cleared (|elevation| > a_c/4 for the cleared
  /// aperture a_c; the volume model clears a_c = a/2, so a/8 < |e| ≤ a/4, where the two-way
  /// pattern falls from −0.4 to −1.5 dB), where a grazing surface is likelier to fail to echo: its
  /// cells do not clear what the map holds occupied (SonarMapper). False in the planar model.
  bool outer = false;
};

/// A point of an obstacle's arc, map frame.
struct HitPoint {
  Eigen::Vector3d point_m;
  /// Share of the obstacle's evidence this point gets, (0, 1]: its cell is updated with the
  /// probability 0.5 + (P(hit) − 0.5) · weight (ArcEvidence). 1 for the planar model.
  double weight = 1.0;
};

/// The shape of every beam of a sweep, sonar frame.
struct BeamShape {
  double width_rad = 0.0;              ///< horizontal −3 dB width, [0, π)
  double vertical_aperture_rad = 0.0;  ///< vertical −3 dB width, [0, π); 0: the planar model
};

/// How an obstacle's evidence is shared over the points of its shell that no other beam carved
/// away (the beam-volume model maps with kBeamPattern; the planar model always gives every point
/// the whole hit; the others are kept for tests and for OctoMap's comparison in bench/). A beam
/// says "the first surface in my cone is at range r"; where on the shell's vertical arc the echo
/// came from, it does not say.
enum class ArcEvidence {
  /// Every remaining point gets the whole hit (stonefish_slam's sonar-cone insertion). Assumes the
  /// whole arc is occupied; the arcs of other viewpoints carve the wrong parts away over the
  /// sweeps ("somewhere occupied, everywhere empty": Moravec & Elfes 1985).
  kWholeArc,
  /// The hit is one echo from one place on the arc, equally likely anywhere on the elevation rows
  /// that remain: each point gets 1 / (remaining rows) of it (Elfes 1987, the occupancy
  /// probability spread over the beam's arc). Assumes a single reflector per echo.
  kSpreadUniform,
  /// Each point gets the two-way vertical beam pattern at its elevation, g(e) = p(e)², with the
  /// one-way Gaussian p(e) = 2^−(2e/a)² (1 on the axis, 0.25 at the −3 dB edge ± a/2): an echo is
  /// likelier from where the beam is loud (Elfes 1987's angular profile). Assumes the pattern is
  /// Gaussian; nothing is spread.
  kBeamPattern,
};

/// Where in its cone an obstacle lies (planArcs; the volume model maps with kVertical). The echo's
/// leading edge is the range r of the nearest surface in the cone; which surface, the beam does not
/// say.
enum class ObstacleSurface {
  /// The shell: the sphere cap at r across the cone, every direction alike. Right for a surface
  /// that faces the sonar (a sphere about it); in front of a vertical face by r (1 − cos e) at
  /// elevation e off the face's normal (0.14 m at 3 m and 17.5°): the "banana" arcs of MSIS maps.
  kShell,
  /// A vertical face, the man-made structure of harbours (quay walls, piles, hulls, pontoons: the
  /// vertical-wall hypothesis of MSIS mapping in structured environments, Ribas et al. 2008, J.
  /// Field Robotics 25(11–12) 898). Its nearest point lies on the cone's most horizontal direction
  /// (map slope s₀), so the face stands at horizontal distance d = r cos s₀, and the direction of
  /// map slope s meets it at range d / cos s; each point of the cone's grid is placed there, up to
  /// where the loud echo ends (PlannedBeam::hit_end_m, plus the range tolerance) and along directions
  /// within 75° of the horizontal (a steeper ray meets the face at grazing incidence). The mirror of the
  /// level-surface hypothesis of extended returns (appendLevelTrace): a return from a surface met
  /// at grazing incidence is a level seabed, one loud enough to be an obstacle is a face.
  kVertical,
};

/// The two-way vertical pattern of a Gaussian beam of −3 dB width `aperture_rad` at `elevation_rad`
/// off its axis: p(e)² with p(e) = 2^−(2e/a)² (ArcEvidence::kBeamPattern), in (0, 1]. Nothing is thrown.
double twoWayPattern(double elevation_rad, double aperture_rad);

/// Plans the free rays of beams that share one pose (or nearly: each ray is placed with its own
/// beam's pose), in grid-angle order; `rays` is cleared first. With width 0 every beam is one ray.
/// Nothing is thrown.
/// @param beam_width_rad horizontal beam width, ≥ 0; @param voxel_m map resolution, > 0.
void planFreeRays(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m,
                  std::vector<FreeRay>& rays);

/// As above for beams of any shape: with a vertical aperture, the sweep's cones as one 2D fan
/// (bearing × elevation; see the file's comment). Nothing is thrown.
void planFreeRays(const std::vector<PlannedBeam>& beams, const BeamShape& shape, double voxel_m,
                  std::vector<FreeRay>& rays);

/// Plans the hit points of a sweep's obstacles, map frame; `hits` is cleared first. The beams may
/// each have their own pose (a moving vehicle). Nothing is thrown.
///
/// An obstacle is the arc at its range across the beam's width, points at most a voxel apart.
/// A point of the arc is dropped where another beam of the sweep, from its own pose, saw water
/// beyond it: the point lies inside that beam's wedge, nearer than the range up to which the beam
/// saw water (its echo's leading edge, or its free range without one) less `tolerance_m`
/// ("somewhere occupied, everywhere empty": Moravec & Elfes 1985, Elfes 1987). At oblique
/// incidence the leading edge comes from the beam's near side, and the neighbours, which see the
/// same wall farther away, carve the rest of the arc away. With width 0 each obstacle is one point.
/// @param beam_width_rad horizontal beam width, ≥ 0; @param voxel_m map resolution, > 0;
/// @param tolerance_m    how much farther than the arc another beam's water must reach, ≥ 0
///                       (the range uncertainty of a leading edge: a bin plus half a voxel).
void planArcs(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
              std::vector<HitPoint>& hits);

/// As above for beams of any shape. With a vertical aperture an obstacle is the shell at its range
/// across width × aperture, points at most a voxel apart on both axes; a point is carved where it
/// lies inside another beam's cone (bearing and elevation within its shape, sonar frame) nearer
/// than that beam's water range less `tolerance_m` (3D distance from its sonar); the points left
/// share the evidence as `evidence` says.
/// `surface` places each obstacle's points in its cone (the shell, or a vertical face); the
/// carving and the evidence are the same for both.
/// `face_slope` (a vertical face only): where the face distances of the beam's neighbours in
/// `beams` (those before and after it within half a beam width, and the nearest on each side within
/// a width) lie on a line through its own within `tolerance_m` (a plane, not a pile or a corner),
/// the face recedes across the beam along that line, from the near edge its leading edge came
/// from, instead of standing square to the beam at the leading edge's distance; only as far as the
/// echo lasted (PlannedBeam::hit_end_m), and not for a head rolled about the beam's axis by more
/// than asin(w / a). The volume model maps with face_slope on.
void planArcs(const std::vector<PlannedBeam>& beams, const BeamShape& shape, double voxel_m, double tolerance_m,
              ArcEvidence evidence, std::vector<HitPoint>& hits, ObstacleSurface surface = ObstacleSurface::kShell,
              bool face_slope = false);

/// Whether a beam's return from `onset_m` to `end_m` (metres; an obstacle's loud echo: the mapper
/// gives the start of the lit run that starts with it, BeamDetection::extended_onset_m, and the
/// nearer of the run's end and where the loud echo falls back, echo_end_m, since a face's loud echo
/// may go on into a weak seabed at its foot; without a run, the obstacle's range and echo_end_m)
/// is a level surface met at the cone's edge rather than a face: the cone points only down or only
/// up (as appendLevelTrace needs), and the return lasts longer than any vertical face inside the
/// cone could echo, from its nearest point to onset / cos e, e the slope of the cone's steepest ray,
/// plus `tolerance_m`. A sloping face lies between the two. A cone that points up under a known
/// water surface (at map height PlannedBeam::surface_z_m, h metres above the sonar) meets it first
/// on its top ray, at h / sin e: a return whose onset lies within `tolerance_m` of that range is the surface,
/// however soon the beam's recorded range cuts it short (a head tilted 25° looking back meets a
/// surface 3 m above at 4.4 m, and a face's bound 6 m lies past the Micron's 5 m). The beam-volume
/// model traces such a beam instead of marking its shell. Nothing is thrown.
bool isLevelReturn(const PlannedBeam& beam, const BeamShape& shape, double onset_m, double end_m, double tolerance_m);

/// Where a beam's seabed trace starts, map frame: its sonar plus the trace's onset range along the
/// aperture's lowest edge, when the beam has a trace (PlannedBeam::traced) and its cone points only
/// down (appendLevelTrace); nullopt otherwise. Nothing is thrown.
std::optional<Eigen::Vector3d> seabedOnsetPoint(const PlannedBeam& beam, const BeamShape& shape);

/// Appends the hit points of one beam's weak extended return (PlannedBeam::trace_onset_m,
/// trace_end_m) to `hits`, map frame; nothing else is touched, and a beam without one adds nothing.
/// planArcs of the volume model calls it for each such beam and carves the points as a shell's. Nothing is thrown.
///
/// A weak extended return is a surface met at grazing incidence: a surface facing the beam would
/// have echoed loud enough to be an obstacle. It starts where the surface enters the cone, at the
/// edge of the vertical aperture nearest to it, and goes on while the surface crosses the cone.
/// Under the flat-seabed hypothesis of sidescan slant-range correction (Blondel, "The Handbook of
/// Sidescan Sonar", 2009), the surface is the plane through the onset point on that edge (range
/// r₀) with normal n = PlannedBeam::trace_normal: level (+z), or the seabed's slope where the mapper
/// measured it (SeabedSlope). At every range r from the onset to the return's end (points half a
/// voxel apart in range, at most a voxel apart across the beam's width) the return comes from
/// where the shell meets that plane: the elevation e in the aperture with r · v(e) = r₀ · v(edge),
/// v the component of the direction along n. A slope drawn level puts the trace off the seabed by
/// the slope times the horizontal distance from the onset point (7° over 1 m: 0.12 m).
/// The edge is the aperture's most downward one when that points down (a seabed), its most upward
/// one when that points up (the water surface). An aperture that points both ways (a level head)
/// cannot tell the two from the onset alone: it is traced from its lower edge, as the seabed, only
/// when the surface's height is known (PlannedBeam::surface_z_m) and the onset is nearer, by more
/// than a voxel, than where the surface enters the aperture's upper edge (the surface's height
/// above the sonar over that edge's slope sine); otherwise it gets no trace. A point gets
/// `evidence`'s weight at its elevation (the two-way pattern, or 1). The planar model (aperture 0)
/// has no traces.
/// @param voxel_m map resolution, > 0.
void appendLevelTrace(const PlannedBeam& beam, const BeamShape& shape, double voxel_m, ArcEvidence evidence,
                      std::vector<HitPoint>& hits);

/// planFreeRays and planArcs of beams that share one pose.
void planSweep(const std::vector<PlannedBeam>& beams, double beam_width_rad, double voxel_m, double tolerance_m,
               std::vector<FreeRay>& rays, std::vector<HitPoint>& hits);

}  // namespace sonarmap
