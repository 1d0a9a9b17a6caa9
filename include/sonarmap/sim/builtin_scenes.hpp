#pragma once
/// @file builtin_scenes.hpp
/// Ready-made scenes for the MSIS simulator, in the map frame (NWU, metres) with the sonar's
/// nominal position at the origin: a static run (vehicle at the NED origin, sonar upright and
/// aligned) puts the head there.
///
///  - `tank`: the CRAS test tank (../shared/data/README.md, cras_micron_tank_static.mat). A box
///    seen from inside whose inner faces are 4.2 m (x) × 4.4 m (y) apart (about 4.4 × 4.6 m outside
///    with 0.1 m walls), placed off-centre: faces at x = −2.1 and +2.1 m, y = −1.8 and +2.6 m, so
///    the walls lie 1.8 m (nearest face) to 3.34 m (farthest corner) from the sonar. The water
///    surface is 0.47 m above the head, so it enters the top of the 35° vertical aperture at
///    0.47 / sin 17.5° = 1.56 m: the constant-range ring of the real data. The floor is 1.5 m below
///    the head; the aperture's lower edge would reach it only at 1.5 / sin 17.5° = 5.0 m, behind the
///    walls, so it is hardly seen (it takes part in multipath). A floater (1.0 × 0.4 × 0.3 m box,
///    half above the surface) has its near face 1.95 m from the head at bearing 95°, long side
///    across the line of sight, shadowing part of the +y wall like the floater of the real data
///    (a 1 m line at about that place in the real map).
///    Note: a floor 1.5 m below the head cannot enter a ±17.5° aperture at 1.56 m (that needs
///    0.47 m), so the ring is made by the surface.
///  - `harbour`: open water without tank walls. A quay wall (a long solid block whose face runs
///    along y at x = 3.5 m), a row of five piles (radius 0.2 m) 2 m apart along y at x = 2 m in
///    front of it, a seabed 1.3 m below the head (entering the aperture near 4.3 m) and the surface
///    3 m above (out of reach). Made for runs along the quay (vehicle moving along ±y).
///
/// Reflectivities: concrete walls 0.9, the floater 0.8, piles 0.85, floor and
/// seabed 0.5, the water surface 1.0 (the air–water interface reflects almost everything;
/// its backscatter at grazing incidence is still weak through the echo model's incidence falloff).

#include <string>
#include <string_view>
#include <vector>

#include "sonarmap/sim/scene.hpp"

namespace sonarmap {

/// Names builtinScene() accepts, in a fixed order: "tank", "harbour".
std::vector<std::string> builtinSceneNames();

/// The built-in scene called `name` (see the file's comment).
/// @throws ValueError listing the known names when `name` is not one of them.
Scene builtinScene(std::string_view name);

}  // namespace sonarmap
