"""How fast sonar logs read: for each file, the best of 3 of sonarmap.read_sonar_log (the beams)
and of sonarmap.read_navigation (the vehicle's track, where the file records one), in seconds and
in MB/s of the file's size. The program's start is not counted (docs/performance.md, "Reading logs"; "Reading ROS
logs").

    PYTHONPATH=build/python /usr/bin/python3 bench/read_speed.py FILE...
"""

import os
import sys
import time

import sonarmap


def best_of(read, path, repeats=3):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        read(path)
        best = min(best, time.perf_counter() - start)
    return best


def main(paths):
    for path in paths:
        size_mb = os.path.getsize(path) / 1e6
        sonar_s = best_of(sonarmap.read_sonar_log, path)
        try:
            nav = f"{best_of(sonarmap.read_navigation, path):.3f} s"
        except sonarmap.FileError:
            nav = "none recorded"
        print(f"{os.path.basename(path)}: {size_mb:.2f} MB, sonar {sonar_s:.3f} s ({size_mb / sonar_s:.1f} MB/s), "
              f"navigation {nav}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
