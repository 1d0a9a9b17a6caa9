#pragma once
/// @file builtin_scenes.hpp
/// Ready-made scenes for the MSIS simulator, in the map frame (NWU, metres) with the sonar's
/// nominal position at the origin: a static run (vehicle at the NED origin, sonar upright and
/// aligned) puts the head there.
///
/// Each scene is built for a head's reach R (its range scale, metres) and vertical beam width W.
/// Lengths across the plane scale with s = R / 5 m; heights of the horizontal surfaces (water
/// surface, floor, seabed) and of what stands near them scale with h = s · sin(W/2) / sin 17.5°, so
/// that a horizontal surface enters the −3 dB vertical aperture at the same fraction of the reach
/// for any head. At R = 5 m and W = 35° (the Micron) s = h = 1: the geometry below, in metres. Two
/// things do not scale: pile radii, which stay those of real piles, ρ(s) = clamp(0.2 · s, 0.2, 0.3) m
/// (0.2 m at 5 m, 0.3 m from 7.5 m on), so that a pile stays a thin target; and reflectivities.
///
///  - `tank`: the CRAS test tank (../shared/data/README.md, cras_micron_tank_static.mat). A box
///    seen from inside whose inner faces are 4.2 m (x) × 4.4 m (y) apart (about 4.4 × 4.6 m outside
///    with 0.1 m walls), placed off-centre: faces at x = −2.1 and +2.1 m, y = −1.8 and +2.6 m, so
///    the walls lie 1.8 m (nearest face, 0.36 R) to 3.34 m (farthest corner, 0.67 R) from the sonar.
///    The water surface is 0.47 m above the head, so it enters the top of the 35° vertical aperture
///    at 0.47 / sin 17.5° = 1.56 m (0.31 R): the constant-range ring of the real data. The floor is
///    1.5 m below the head; the aperture's lower edge would reach it only at 1.5 / sin 17.5° = 5.0 m
///    (R), behind the walls, so it is hardly seen (it takes part in multipath). A floater
///    (1.0 × 0.4 × 0.3 m box, half above the surface) has its near face 1.95 m from the head at
///    bearing 95°, long side across the line of sight, shadowing part of the +y wall like the
///    floater of the real data (a 1 m line at about that place in the real map). It lies above
///    z = 0. Reflectivities: walls (concrete) 0.9, floater 0.8, floor 0.5, surface 1.0. The only
///    scene with a reverberation (Scene::reverberation_db, −27 dB): the real log's level behind
///    its walls (msis_simulator.hpp).
///    Note: a floor 1.5 m below the head cannot enter a ±17.5° aperture at 1.56 m (that needs
///    0.47 m), so the ring is made by the surface.
///  - `harbour`: open water without tank walls. A quay wall (a 5 × 40 m solid block whose face runs
///    along y at x = 3.5 m, 0.7 R), a row of five piles (radius ρ(s)) 2 m (0.4 R) apart along y at
///    x = 2 m (0.4 R) in front of it, a seabed 1.3 m below the head (entering the aperture at
///    4.3 m, 0.87 R) and the surface 3 m above (entering it at 10 m, 2 R: out of reach). Quay and
///    piles stand from the seabed to 3.5 m above the head. Made for runs along the quay (vehicle
///    moving along ±y). Reflectivities: quay (concrete) 0.9, piles 0.85, seabed 0.5, surface 1.0.
///  - `hull`: a moored steel ship beside the sonar: its hull a box 4 m (0.8 R) long along x, from
///    x = −2 to +2 m, its near side along x at y = 2 m (0.4 R: 2 m to the sonar's port side, its
///    nearest point; its near corners 2.83 m, 0.57 R, away at bearings 45° and 135°), 2.5 m wide
///    (to y = 4.5 m), from its keel 0.9 m below the head to 1 m above the surface. Two mooring
///    piles (dolphins) stand off the bow and the stern on the hull's side, at (±3.25, 2.25) m
///    (3.95 m, 0.79 R, bearings 34.7° and 145.3°), seabed to 1 m above the surface. Seabed and
///    surface as in `harbour`. Reflectivities: hull (steel, hard) 0.95, piles 0.85, seabed 0.5,
///    surface 1.0. Strong echoes that are short in range (a flat face at normal incidence).
///  - `soft`: `harbour`'s layout with soft, weak reflectors: the quay is a rubble and weed covered
///    embankment whose face is vertical (so a 2D map needs no 3D reasoning) with reflectivity 0.06
///    (12 dB below concrete's 0.9), the piles are timber, 0.09 (10 dB below), the seabed mud, 0.3;
///    surface 1.0. Echoes 10–12 dB weaker than `harbour`'s at the same places.
///  - `open-water`: nothing within reach: only a seabed 5.5 m (1.1 R) below the head and the
///    surface 5.5 m above it (deeper than the reach: no direction of the head meets them within
///    R, whatever its vertical aperture). A log of it holds noise and the near-field band only,
///    for "no false obstacles" tests. Reflectivities: seabed 0.5, surface 1.0.
///
/// In every scene but `open-water` something crosses the sonar's plane z = 0 within reach (walls,
/// quay or embankment face, hull side, piles: all vertical), and nothing that does is sloped, so a
/// 2D map at z = 0 can be scored against the scene (eval/ground_truth.hpp).
///
/// The 3D scenes (builtinScene3dNames(); not in builtinSceneNames(), which lists the scenes of the
/// 2D accuracy table) have height structure for 3D maps of a moving vehicle. Every length of them,
/// heights and radii included, scales with s = R / 5 m; the vertical beam width changes nothing.
/// At s = 1, in metres:
///
///  - `quay3d`: a harbour corner made to be mapped in 3D from a vehicle moving around the origin
///    in plan, between 2.5 and 3.5 m depth (map z from −2.5 to −3.5 m), primitives in this order:
///     0. the water surface, a horizontal plane at z = 0, where a depth sensor reads 0 (the
///        navigation's depth is the map's −z, nedToMap); reflectivity 1.0;
///     1. a sloping seabed: the plane z = −5 − x / 8 (through (0, 0, −5), normal ∝ (1, 0, 8)),
///        −4.5 m at x = −4, −5.5 m at x = +4: 7.1° down towards the quay; 0.5 (sand);
///     2. a quay wall: a solid block x ∈ [3.5, 8.5], y ∈ [−20, 20], z ∈ [−6.5, 1.0] (from below
///        the seabed to 1 m above the surface), its face along y at x = 3.5 m; 0.9 (concrete);
///     3–5. three piles, cylinders of radius 0.2 m at (x, y) = (2.0, −2.5), (2.0, 2.5) and
///        (−3.0, −2.5), each from 0.3 m below the seabed under its axis to z = 1.0 m; 0.85;
///     6. a boulder: a 0.8 × 0.6 × 0.5 m box yawed 30°, centred at (−1.5, −1.0), its bottom 0.1 m
///        below the seabed under its centre (z ∈ [−4.9125, −4.4125]), so it rests on the slope
///        without a gap; 0.7 (rock);
///     7. a floating pontoon (caisson) with an overhanging face: a box x ∈ [−1.25, 1.25],
///        y ∈ [2.4, 3.6], z ∈ [−3.1, 0.3] (its top 0.3 m above the surface), whose underside, the
///        face z = −3.1 m seen from below, overhangs 1.7–2.1 m of water above the seabed; 0.9.
///    A vehicle at z ∈ [−3.5, −2.5] must keep clear of the pontoon's footprint at z above −3.1 m.
///    Everything lies within 4.2 m of the origin in plan except the quay's long block and the
///    planes; a horizontal ray at z = −3 m from (0, 0) towards +x meets the quay face at 3.5 m.
///    Unlike the 2D scenes (whose sonar sits at z = 0 for the 2D map), the 3D scene puts its water
///    surface where the navigation's depth 0 is, as a real depth sensor does (MapperOptions::
///    water_surface_depth_m).

#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Reach of the scenes as first built (the Micron's 5 m range scale), metres.
inline constexpr double kBuiltinSceneReach_m = 5.0;
/// Vertical beam width the scenes' heights were set for (the Micron's 35°), radians.
inline constexpr double kBuiltinSceneVerticalBeamWidth_rad = 35.0 * std::numbers::pi / 180.0;

/// Names of the scenes of the 2D accuracy table, which builtinScene() accepts, in a fixed order:
/// "tank", "harbour", "hull", "soft", "open-water".
std::vector<std::string> builtinSceneNames();

/// Names of the 3D scenes builtinScene() accepts as well, in a fixed order: "quay3d".
std::vector<std::string> builtinScene3dNames();

/// The built-in scene called `name` (one of builtinSceneNames() or builtinScene3dNames()) for a
/// head of range scale `reach_m` (metres, > 0) and vertical −3 dB beam width
/// `vertical_beam_width_rad` (radians, in (0, π); the 3D scenes ignore it once validated); see the
/// file's comment. The defaults give the scenes as first built, for the Micron (5 m, 35°).
/// @throws ValueError listing the known names when `name` is not one of them, or naming the
///         argument when reach_m or vertical_beam_width_rad is out of range or not finite.
Scene builtinScene(std::string_view name, double reach_m = kBuiltinSceneReach_m,
                   double vertical_beam_width_rad = kBuiltinSceneVerticalBeamWidth_rad);

/// The depth a vehicle sits at in the built-in scene `name` built for `reach_m` (metres, > 0), when
/// nothing else says: 0 (the sonar at z = 0) in the 2D scenes, 3 s m in `quay3d` (below its surface
/// at z = 0, 2 s m above its seabed at the origin). Metres, NED down.
/// @throws ValueError as builtinScene for an unknown name or a reach that is not > 0.
double builtinSceneDepth_m(std::string_view name, double reach_m = kBuiltinSceneReach_m);

}  // namespace sonarmap
