"""sonarmap: mechanically scanned imaging sonar (MSIS) logs to probabilistic 3D occupancy maps.

Python bindings of the sonarmap C++ library (the same code as the ``sonarmap`` command-line tool,
not a second implementation). Maps are OctoMap-compatible octrees (``.bt``/``.ot``).

Frames and units: metres, radians (degrees only where the CLI takes degrees: beam widths,
apertures, sector and heading, as its option names say). The sonar frame has x along bearing 0
(the head's ahead), y starboard, z down, bearings clockwise (as the body frame: a mounting of
zeros is upright and aligned); a sonar map is in ENU (x east, y north, z up: ROS REP 103/105) unless
``map_sonar_log(..., map_frame="ned")`` asks for NED, and says so in ``OccupancyMap.frame``;
navigation is NED with body FRD attitudes (roll, pitch, yaw, Z-Y-X).

Quick start::

    import sonarmap
    log = sonarmap.read_sonar_log("cras.mat")          # SonarLog: intensities (beams, bins) uint8
    m = sonarmap.map_sonar_log(log, resolution=0.05)   # OccupancyMap, with m.stats
    centers, sizes = m.occupied_voxels()               # (M, 3) and (M,) float64, metres
    m.write("cras.bt")                                 # open in octovis

Errors are sonarmap.Error (a RuntimeError) and its subclasses FileError (also an OSError),
ValueError and OutOfMapError (also builtin ValueErrors).
"""

from ._sonarmap import (  # noqa: F401  (re-exported)
    Error,
    FileError,
    InsertStats,
    MappingStats,
    Mission,
    OccupancyMap,
    OnlineMapper,
    OutOfMapError,
    PolarImage,
    Scene,
    Simulation,
    SonarLog,
    ValueError,
    builtin_scene,
    builtin_scene_names,
    cartesian_image,
    detect_obstacles,
    eval_trajectory,
    evaluate,
    localize_point_scans,
    map_sonar_log,
    mapping_options,
    mission_names,
    mission_plan_names,
    polar_image,
    read_nav_csv,
    read_bag_topics,
    read_navigation,
    read_scene,
    read_sonar_log,
    simulate,
    simulate_mission,
    sonar_preset_names,
    write_nav_csv,
)

# The classes and exceptions are defined in the extension; name them by the package users import.
for _name in ("Error", "FileError", "ValueError", "OutOfMapError", "InsertStats", "MappingStats", "Mission",
              "OccupancyMap", "OnlineMapper", "PolarImage", "Scene", "Simulation", "SonarLog"):
    try:
        globals()[_name].__module__ = __name__
    except (AttributeError, TypeError):  # a type that refuses it keeps "sonarmap._sonarmap"
        pass
del _name

# sonarmap.ValueError is left out of __all__ so that `from sonarmap import *` does not shadow the
# builtin ValueError (it subclasses it: `except ValueError` catches both).
__all__ = [
    "Error",
    "FileError",
    "InsertStats",
    "MappingStats",
    "Mission",
    "OccupancyMap",
    "OnlineMapper",
    "OutOfMapError",
    "PolarImage",
    "Scene",
    "Simulation",
    "SonarLog",
    "builtin_scene",
    "builtin_scene_names",
    "cartesian_extent",
    "cartesian_image",
    "detect_obstacles",
    "eval_trajectory",
    "evaluate",
    "localize_point_scans",
    "map_sonar_log",
    "mapping_options",
    "mission_names",
    "mission_plan_names",
    "polar_image",
    "read_nav_csv",
    "read_bag_topics",
    "read_navigation",
    "read_scene",
    "read_sonar_log",
    "simulate",
    "simulate_mission",
    "sonar_preset_names",
    "write_nav_csv",
]


def cartesian_extent(image, pixel_size_m):
    """The matplotlib ``extent`` of a cartesian_image, in metres of the sonar frame.

    image: the (S, S) array cartesian_image returned; pixel_size_m: the pixel size it was made
    with (metres; the polar image's bin_length_m by default). Returns [left, right, bottom, top]
    = [-h, h, -h, h] with h = S / 2 · pixel_size_m, for ``plt.imshow(image, extent=...)`` (the
    sonar at (0, 0), +x right, +y up).
    """
    half_m = image.shape[0] / 2.0 * float(pixel_size_m)
    return [-half_m, half_m, -half_m, half_m]
