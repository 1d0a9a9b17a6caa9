#pragma once
/// @file ground_truth.hpp
/// Scoring an occupancy map against the ground truth of a simulated run (sim/scene.hpp): how many
/// occupied voxels lie on a surface (precision), how much of the surface the sonar could see was
/// mapped (recall) or wrongly cleared (erosion), how many free voxels are really water (free
/// accuracy), and how far the mapped surfaces are from the true ones (surface error, wall-position
/// error). Works alike on a 2D map (one layer) and on a 3D map (the whole map, by default).
///
/// Definitions (map frame, metres; "voxel" is a finest voxel of the map, pruned leaves expanded;
/// a voxel's position is its centre; res is the map's resolution):
///  - Tolerance T = max(GroundTruthOptions::tolerance_m, √3 · res): never less than one voxel
///    diagonal.
///  - Evaluated region: the voxels whose centre z lies in [z_min, z_max]. Without z options this
///    is the slab of the map's known voxels (lowest to highest known voxel): a 2D sonar map is
///    scored on its own layer, a 3D map as a whole.
///  - Sensors: GroundTruthOptions::sensor_positions_m (default the map origin, where mapSonarLog
///    and `sonarmap map` place a static sonar). Range R: max_range_m, or when unset the largest
///    distance from a known voxel of the region to its nearest sensor plus T (the reach of the map;
///    a wall lies just beyond the last voxel the sonar cleared).
///  - Field of view (only when both GroundTruthOptions::sensor_orientations and
///    vertical_aperture_rad, A, are set): sensor i is a scanning head turning 360° about the z axis
///    of its own frame (sonar frame, beam.hpp: x along bearing 0, y starboard, z down), whose orientation
///    sensor_orientations[i] maps sonar-frame vectors to the map frame. It sees a point p when the
///    elevation of p in its frame, asin(z component of Rᵢᵀ · (p − sᵢ) / |p − sᵢ|), lies within
///    [−A/2, A/2]; no horizontal limit. Without them every direction is seen (a sphere).
///  - Precision = occupied voxels of the region within T of a scene surface (distanceToSurface)
///    / occupied voxels of the region. The others are split by where they lie: in the water (a
///    straight segment from some sensor reaches them through no surface, as for free accuracy
///    below: a shell in front of a face) or behind or inside a surface.
///  - Surface voxels: the voxels of the map's grid inside the region's box (the horizontal bounding
///    box of the region's known voxels, grown by T on each side, × the z extent of the region's
///    known voxels; or GroundTruthOptions::surface_box_m when set) whose centre is within res / 2 of a scene surface (the surface sampled at the
///    map's resolution), that are within R of a sensor and visible from it: within its field of
///    view (above) and the first surface along the ray from the sensor towards the centre is met
///    no earlier than one voxel (res) before the centre. Surfaces hidden behind others (the wall
///    behind a floater), out of reach, out of the aperture or outside the slab do not count. They
///    are found hierarchically (boxes of voxels far from every surface are skipped whole), with the
///    same result as testing every voxel of the box.
///  - Recall = surface voxels with an occupied voxel of the region whose centre is within T
///    / surface voxels.
///  - Erosion = surface voxels whose own voxel the map classifies free / surface voxels: the share
///    of the visible true surface that free space has carved away (a cone grazing a wall or the
///    seabed). The recall's denominator; a surface voxel that is unknown or occupied is not eroded.
///  - Surface error: for every occupied voxel of the region (clutter included, unlike the
///    wall-position error), the distance from its centre to the nearest scene surface; reported as
///    their median and 90th percentile, each by linear interpolation between order statistics (the
///    value at 0-based rank (n − 1) · p of the n sorted distances, p = 0.5 and 0.9: numpy's default;
///    for even n the median is the mean of the two middle values). 0 without occupied voxels.
///  - Free accuracy = free voxels of the region that are in the water / free voxels of the region.
///    A voxel is in the water when the straight segment from some sensor to its centre crosses no
///    scene surface (so it is neither inside a solid block or pile nor beyond a wall), or when it is
///    within T of a surface (the band where a wall's voxels are half water). No field of view.
///  - Wall-position error: over the occupied voxels of the region within match_distance_m of a
///    surface ("matched"; farther ones are clutter or ghosts, already counted by the precision), the
///    mean and the root mean square of the distance to the nearest surface. Per surface (scene
///    primitive), the median signed offset of the matched voxels whose nearest surface it is:
///    positive when the voxel is on the near side of the surface seen from the nearest sensor (the
///    segment from that sensor to the voxel does not cross the primitive: the map puts the wall too
///    near), negative behind it.
///
/// Cost: occupied voxels × primitives distance queries; surface voxels × primitives × about the
/// log of the box's size to find the surface voxels (not the box's volume: a 10 × 10 × 5 m map at
/// 5 cm holds 4·10⁶ voxel centres but about 10⁵ surface voxels); one ray–scene query per sensor
/// for each free voxel and each surface voxel: keep the sensor list short (a few positions of a
/// moving run) for large maps. The free voxels are expanded from pruned leaves one by one, so a
/// large 3D map's free space dominates time and memory.

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sonarmap/core/progress.hpp"
#include "sonarmap/octree/occupancy_octree.hpp"
#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Options of evaluateAgainstScene(); see the file's comment for each definition.
struct GroundTruthOptions {
  double tolerance_m = 0.1;             ///< match distance for precision and recall, > 0 (raised to √3 · res)
  std::optional<double> z_min_m;        ///< lower bound of the evaluated slab (map frame); unset: lowest known voxel
  std::optional<double> z_max_m;        ///< upper bound; unset: highest known voxel
  /// Positions of the sonar head, map frame, at least one. Default: the map origin.
  std::vector<Eigen::Vector3d> sensor_positions_m{Eigen::Vector3d::Zero()};
  std::optional<double> max_range_m;    ///< sonar reach, > 0; unset: the map's reach + T (see above)
  double match_distance_m = 0.5;        ///< occupied voxels within it enter the wall-position error, > 0
  /// Orientation of each sensor: the rotation from its sonar frame (x along bearing 0, y starboard, z
  /// up) to the map frame, parallel to sensor_positions_m. Empty: no field-of-view check (every
  /// direction seen). Set together with vertical_aperture_rad.
  std::vector<Eigen::Matrix3d> sensor_orientations;
  /// Vertical aperture of the sensors, radians, in (0, π): a surface voxel counts as seen only
  /// within ±half of it from the sonar's scan plane (see the file's comment). Unset: no check.
  std::optional<double> vertical_aperture_rad;
  /// Box (map frame, metres) in which the surface voxels of recall and erosion are sought instead
  /// of the known voxels' box grown by T (see the file's comment): with it, and max_range_m set,
  /// the recall's denominator no longer depends on how far the map reaches (a model that clears
  /// less must not shrink its own truth). Unset: the known box.
  std::optional<Eigen::AlignedBox3d> surface_box_m;

  /// @throws ValueError naming the field when a number is not finite, a distance is not > 0,
  ///         z_min_m > z_max_m, surface_box_m is empty or not finite, there is no sensor position, vertical_aperture_rad is not in
  ///         (0, π), only one of vertical_aperture_rad and sensor_orientations is set, their
  ///         counts differ from sensor_positions_m's, or an orientation is not a rotation
  ///         (RᵀR = I within 1e-6, det > 0).
  void validate() const;
};

/// The wall-position error of one scene primitive.
struct SurfaceOffset {
  std::size_t primitive = 0;           ///< index into Scene::primitives
  std::size_t voxels = 0;              ///< matched occupied voxels whose nearest surface it is
  double median_signed_offset_m = 0.0; ///< > 0: in front of the surface (sensor side), < 0: behind
};

/// Recall and erosion of one scene primitive: the visible surface voxels whose nearest surface it
/// is (the seabed, a quay wall, a pile: which surfaces the sonar finds and which it misses).
struct SurfaceRecall {
  std::size_t primitive = 0;       ///< index into Scene::primitives
  std::size_t visible_voxels = 0;  ///< visible surface voxels nearest this primitive
  std::size_t found_voxels = 0;    ///< of those, with an occupied voxel within T
  std::size_t free_voxels = 0;     ///< of those, held free by the map
};

/// One occupied voxel of the evaluated region and its distance to the nearest scene surface: the
/// values behind the surface error, for pictures of where the map is wrong (render/map_figures.hpp).
struct OccupiedVoxelError {
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();  ///< voxel centre, map frame, metres
  double distance_m = 0.0;                              ///< to the nearest surface (distanceToSurface), metres
};

/// What evaluateAgainstScene() measured. Shares are in [0, 1] and 0 when their denominator is 0.
struct GroundTruthReport {
  double tolerance_m = 0.0;  ///< T actually used
  double z_min_m = 0.0;      ///< evaluated slab, map frame
  double z_max_m = 0.0;
  double max_range_m = 0.0;  ///< R actually used

  std::size_t occupied_voxels = 0;
  std::size_t occupied_on_surface = 0;  ///< within T of a surface
  /// Of the others (farther than T from every surface), those in the water: a straight segment
  /// from some sensor reaches them through no surface. The beam-volume model's uncarved shells
  /// (voxels in front of a face, at the echo's range but at an elevation where the face is farther);
  /// the rest lie behind or inside a surface.
  std::size_t occupied_in_water = 0;
  double precision = 0.0;

  std::size_t surface_voxels = 0;       ///< visible surface voxels of the region
  std::size_t surface_voxels_found = 0; ///< with an occupied voxel within T
  double recall = 0.0;
  std::size_t surface_voxels_free = 0;  ///< surface voxels the map holds free
  double erosion = 0.0;                 ///< surface_voxels_free / surface_voxels

  std::size_t free_voxels = 0;
  std::size_t free_in_water = 0;
  double free_accuracy = 0.0;

  std::size_t matched_voxels = 0;       ///< occupied voxels within match_distance_m of a surface
  double mean_distance_m = 0.0;         ///< over the matched voxels
  double rms_distance_m = 0.0;
  double surface_error_median_m = 0.0;  ///< over every occupied voxel of the region, metres
  double surface_error_p90_m = 0.0;     ///< its 90th percentile, metres
  std::vector<SurfaceOffset> surfaces;  ///< primitives with at least one matched voxel, in scene order
  /// The recall and erosion above split by nearest primitive: those with at least one visible
  /// surface voxel, in scene order (their counts sum to the totals above).
  std::vector<SurfaceRecall> recall_by_surface;
  /// Every occupied voxel of the region with its distance to the truth (occupied_voxels entries,
  /// in no particular order): the surface error's sample.
  std::vector<OccupiedVoxelError> occupied_errors;
};

/// Scores `map` against the ground truth `scene` (both in the map frame); definitions in the
/// file's comment. `progress`, when set, is called as the scoring advances: (done, 3000), three
/// equal stages of 1000 units (occupied voxels, surface voxels, free voxels), ending at 3000.
/// @throws ValueError for invalid options, an empty or invalid scene (validateScene), or when the
///         map has no known voxel in the evaluated slab.
GroundTruthReport evaluateAgainstScene(const OcTree16& map, const Scene& scene, const GroundTruthOptions& options = {},
                                       const ProgressCallback& progress = {});

}  // namespace sonarmap
