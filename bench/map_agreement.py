"""How far two maps, and optionally two trajectories, agree: the share of the voxels known in
either map (at the finer map's resolution, leaves expanded) that both know with the same class
(occupied: log-odds > 0, else free), and the largest difference of two navigation CSVs' positions
and angles (angles compared modulo 2 pi). Used for the round trips of docs/formats.md.

    PYTHONPATH=build/python /usr/bin/python3 bench/map_agreement.py A.bt B.bt [A_TRAJ.csv B_TRAJ.csv]
"""

import math
import sys

import numpy as np

import sonarmap


def voxel_classes(path):
    centers, sizes, log_odds = sonarmap.OccupancyMap.read(path).leaves()
    resolution = sizes.min()
    classes = {}
    for center, size, value in zip(centers, sizes, log_odds):
        steps = int(round(size / resolution))
        corner = np.floor((center - size / 2) / resolution + 0.5).astype(np.int64)
        for i in range(steps):
            for j in range(steps):
                for k in range(steps):
                    classes[(corner[0] + i, corner[1] + j, corner[2] + k)] = value > 0
    return classes


def trajectory(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def main(args):
    a, b = voxel_classes(args[0]), voxel_classes(args[1])
    known = set(a) | set(b)
    same = sum(1 for key in known if key in a and key in b and a[key] == b[key])
    print(f"voxels known: {len(a)} and {len(b)}; agreement {same / len(known):.6f} over {len(known)}")
    if len(args) == 4:
        s, t = trajectory(args[2]), trajectory(args[3])
        if s.shape != t.shape:
            print(f"trajectories of {len(s)} and {len(t)} fixes")
            return
        position = np.abs(s[:, 1:4] - t[:, 1:4]).max()
        angle = np.abs((s[:, 4:7] - t[:, 4:7] + math.pi) % (2 * math.pi) - math.pi).max()
        print(f"trajectories: {len(s)} fixes, largest difference {position:.2e} m, {angle:.2e} rad")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    main(sys.argv[1:])
