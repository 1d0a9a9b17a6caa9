#!/usr/bin/env python3
"""sonarmap from Python: a sonar log's polar and Cartesian images, its occupancy map, and a
simulated mission scored against its ground truth.

    PYTHONPATH=build/python /usr/bin/python3 examples/map_sonar_log.py [LOG] [-o OUT_FOLDER]

LOG is any log `sonarmap map` reads (the CRAS tank's .mat, a SeaNet .V4LOG or capture, a Ping360
.bin, a beam CSV); without one it maps ../shared/data/cras_micron_tank_static.mat when that file
exists, else a simulated Micron in the built-in tank. Writes OUT_FOLDER/sonar_images.png,
OUT_FOLDER/map.png and OUT_FOLDER/map.bt (open it with octovis or `sonarmap view`).
Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).
"""

import argparse
import os
import pathlib

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sonarmap  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
SHARED_LOG = pathlib.Path(os.environ.get("SONARMAP_DATA", HERE.parent.parent / "shared" / "data")) / \
    "cras_micron_tank_static.mat"


def load_log(path):
    """The log to map and a name for the titles: the given file, the CRAS log, or a simulation."""
    if path:
        return sonarmap.read_sonar_log(path), pathlib.Path(path).name
    if SHARED_LOG.exists():
        return sonarmap.read_sonar_log(SHARED_LOG), SHARED_LOG.name
    return sonarmap.simulate("tank", sonar="micron", turns=4).log, "simulated Micron in the built-in tank"


def plot_sonar_images(log, name, out):
    """The last whole sweep (a full turn or a sector pass, not the few beams a log may end on) as a
    polar image (bearing x range) and as a Cartesian image; returns the polar image drawn."""
    whole = log.whole_sweeps()
    polar = sonarmap.polar_image(log, sweep=-1) if len(whole) else sonarmap.polar_image(log)  # else the largest
    cartesian = sonarmap.cartesian_image(polar)
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.5))
    bearings_deg = np.degrees(polar.bearing_rad)
    left.imshow(polar.intensities, aspect="auto", cmap="gray", origin="lower",
                extent=[0.0, polar.range_m[-1], 0, len(bearings_deg)])
    left.set(xlabel="range (m)", ylabel="beam of the sweep",
             title=f"polar image: {name}, {len(bearings_deg)} beams")
    right.imshow(cartesian, cmap="gray", extent=sonarmap.cartesian_extent(cartesian, polar.bin_length_m))
    right.set(xlabel="x, sonar frame (m)", ylabel="y, sonar frame (m)", title="Cartesian image")
    fig.tight_layout()
    fig.savefig(out / "sonar_images.png", dpi=100)
    plt.close(fig)
    return polar


def plot_map(occupancy_map, name, out):
    """Occupied voxels from above, coloured by height, over the free ones in grey."""
    occupied, _ = occupancy_map.occupied_voxels()
    free, _ = occupancy_map.free_voxels()
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.scatter(free[:, 0], free[:, 1], s=1, c="0.85", label="free")
    points = ax.scatter(occupied[:, 0], occupied[:, 1], s=4, c=occupied[:, 2], cmap="viridis", label="occupied")
    fig.colorbar(points, ax=ax, label="up z (m)")
    ax.set(aspect="equal", xlabel="east (m)", ylabel="north (m)",
           title=f"{name}: {len(occupied)} occupied voxels of {occupancy_map.resolution:g} m")
    ax.legend(loc="upper right")
    fig.savefig(out / "map.png", dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log", nargs="?", help="a sonar log (default: the CRAS tank log, or a simulation)")
    parser.add_argument("-o", "--out", default="out/python-example", help="output folder")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    log, name = load_log(args.log)
    print(f"{name}: {len(log)} beams, {log.intensities.shape[1]} bins of {log.bin_length_m[0]:.4f} m")
    polar = plot_sonar_images(log, name, out)
    print(f"sonar images: the last whole sweep, {len(polar.bearing_rad)} beams")

    occupancy_map = sonarmap.map_sonar_log(log)  # the CLI's defaults: resolution, detector... from the log
    print(f"map: {occupancy_map.stats.obstacles} obstacles, {occupancy_map.num_leaf_nodes()} leaves, "
          f"{occupancy_map.memory_bytes() / 1024:.0f} KiB")
    occupancy_map.write(out / "map.bt")
    plot_map(occupancy_map, name, out)

    # A Micron crossing the built-in tank at 3 cm/s, mapped with its navigation and scored against the scene.
    run = sonarmap.simulate("tank", sonar="micron", turns=6, speed=0.03, heading=30.0)  # 1.5 m across the tank in 52 s
    simulated_map = sonarmap.map_sonar_log(run.log, nav=run.nav, resolution=0.05)
    score = sonarmap.evaluate(simulated_map, run.scene, z_min=-0.05, z_max=0.05)
    print(f"simulated mission: precision {score['precision']:.3f}, recall {score['recall']:.3f}")
    print(f"wrote {out}/sonar_images.png, map.png and map.bt")


if __name__ == "__main__":
    main()
