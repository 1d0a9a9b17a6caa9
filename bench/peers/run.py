#!/usr/bin/python3
"""The peers' table (docs/performance.md, "Peers"): whole-process point-cloud insertion by
`sonarmap cloud`, OctoMap, Bonxai and UFOMap on the same scan graphs at 5 cm.

    bench/peers/run.py SONARMAP PEERS_DIR INPUTS_DIR [--rounds 5] [--resolution 0.05] [--only GRAPH ...]

SONARMAP is the `sonarmap` executable; PEERS_DIR/bin holds the drivers built by build.sh; INPUTS_DIR
the graphs written by `sonarmap_cloud_inputs` plus octomap_spherical_scan.graph (../shared/data).
Each round runs every program once on the workload, in a rotated order (alternating runs); a
figure is the median of the rounds: wall seconds (time.perf_counter around the whole process),
peak RSS (/usr/bin/time -f %M), the insertion alone by the program's own clock,
and the finest voxels it knows free and occupied (sonarmap's are OctoMap's: the same traversal,
agreement 1.0 in sonarmap_bench's BM_Cloud rows)."""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

WORKLOADS = [("OctoMap's spherical scan graph", "octomap_spherical_scan.graph"),
             ("sphere, 129,600 rays to 5 m", "sphere_5m.graph"),
             ("corridor scan, 88,200 points", "corridor.graph"),
             ("building, 66 scans, 5,821,200 points (FR-079's size)", "building.graph")]


def run_once(command):
    """Wall seconds (perf_counter around the whole process, /usr/bin/time's fork included), peak RSS
    in MB (/usr/bin/time -f %M: the program's own, not ru_maxrss of a child forked from this Python
    process, which starts at Python's resident size) and the program's stdout."""
    with tempfile.NamedTemporaryFile("r") as measured:
        start = time.perf_counter()
        process = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", measured.name] + command,
                                 stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        wall_s = time.perf_counter() - start
        if process.returncode != 0:
            sys.exit(f"{' '.join(command)} failed with exit code {process.returncode}")
        peak_kb = int(measured.read().split()[-1])
    return wall_s, peak_kb / 1024.0, process.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sonarmap")
    parser.add_argument("peers_dir")
    parser.add_argument("inputs_dir")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--resolution", type=float, default=0.05)
    parser.add_argument("--only", nargs="+", metavar="GRAPH", help="only these workloads (e.g. building.graph)")
    args = parser.parse_args()
    bin_dir = os.path.join(args.peers_dir, "bin")
    res = str(args.resolution)
    with tempfile.TemporaryDirectory() as out:
        def programs(graph):
            return {
                "OctoMap": [os.path.join(bin_dir, "octomap_cloud"), graph, os.path.join(out, "o.bt"), res],
                "sonarmap": [args.sonarmap, "cloud", graph, "-o", os.path.join(out, "s.bt"), "--resolution", res, "-q"],
                "Bonxai": [os.path.join(bin_dir, "bonxai_cloud"), graph, os.path.join(out, "b.bx"), res],
                "UFOMap": [os.path.join(bin_dir, "ufomap_cloud"), graph, os.path.join(out, "u.um"), res],
            }
        print(f"| workload | {' | '.join(programs('x'))} |")
        print("|---|" + "---|" * len(programs('x')))
        details = []
        for title, name in WORKLOADS:
            if args.only and name not in args.only:
                continue
            graph = os.path.join(args.inputs_dir, name)
            if not os.path.exists(graph):
                print(f"| {title} | absent: {graph} |")
                continue
            runs = {program: [] for program in programs(graph)}
            order = list(runs)
            for r in range(args.rounds):
                for program in order[r % len(order):] + order[:r % len(order)]:
                    runs[program].append(run_once(programs(graph)[program]))
            wall = {p: statistics.median(w for w, _, _ in v) for p, v in runs.items()}
            rss = {p: statistics.median(m for _, m, _ in v) for p, v in runs.items()}
            cells = []
            for program in runs:
                speedup = wall["OctoMap"] / wall[program]
                cells.append(f"{wall[program]:.3f} s / {speedup:.1f}× / {rss[program]:.1f} MB "
                             f"({rss[program] / rss['OctoMap']:.2f}×)")
                line = runs[program][-1][2]
                inserted = re.search(r"insert_s ([0-9.]+) free (\d+) occupied (\d+)", line)
                own = re.search(r"([0-9.]+) s ->", line)
                if inserted:
                    details.append(f"{title}: {program} insertion {float(inserted[1]):.4f} s, "
                                   f"free {int(inserted[2]):,}, occupied {int(inserted[3]):,} voxels")
                elif own:
                    details.append(f"{title}: {program} insertion {float(own[1]):.4f} s")
            print(f"| {title} | {' | '.join(cells)} |")
        print()
        for line in details:
            print(line)


if __name__ == "__main__":
    main()
