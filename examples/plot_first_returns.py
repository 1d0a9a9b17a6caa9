#!/usr/bin/python3
"""Draws a log's first returns (bench/first_returns.cpp, --returns-csv) over its last sweeps' polar
images, and their ranges against time: what docs/accuracy.md shows of the shared ROS pool log.

    PYTHONPATH=build/python /usr/bin/python3 examples/plot_first_returns.py LOG RETURNS.csv OUT.png [DETECTOR]

LOG: any log sonarmap reads; RETURNS.csv: detector,beam,time_s,bearing_deg,range_m,mapped; the
returns of DETECTOR (default: evidence) are drawn, green where the map holds them, red where not.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sonarmap  # noqa: E402


def main():
    log_path, returns_path, out_path = sys.argv[1:4]
    detector = sys.argv[4] if len(sys.argv) > 4 else "evidence"
    log = sonarmap.read_sonar_log(log_path)
    with open(returns_path) as f:
        returns = [r for r in csv.DictReader(f) if r["detector"] == detector]
    beam = np.array([int(r["beam"]) for r in returns])
    time_s = np.array([float(r["time_s"]) for r in returns])
    bearing = np.array([float(r["bearing_deg"]) for r in returns])
    range_m = np.array([float(r["range_m"]) for r in returns])
    mapped = np.array([r["mapped"] == "1" for r in returns])
    sweeps = log.sweeps()[-3:]
    fig = plt.figure(figsize=(15, 9))
    for k, (first, last) in enumerate(sweeps):
        ax = fig.add_subplot(2, 3, k + 1)
        polar = sonarmap.polar_image(log, first=first, last=last)
        image = np.asarray(polar.intensities)
        rows = np.degrees(np.asarray(polar.bearing_rad))
        order = np.argsort(rows)
        reach = image.shape[1] * polar.bin_length_m
        ax.imshow(image[order], aspect="auto", origin="lower", cmap="inferno", vmin=0, vmax=200,
                  extent=[0, reach, rows[order][0], rows[order][-1]])
        inside = (beam >= first) & (beam < last)
        for ok, colour in ((True, "lime"), (False, "red")):
            pick = inside & (mapped == ok)
            ax.plot(range_m[pick], bearing[pick], ".", ms=4, color=colour,
                    label="first return, %s" % ("mapped" if ok else "not mapped"))
        ax.set_title("beams %d-%d (%.0f-%.0f s)" % (first, last, log.time_s[first], log.time_s[last - 1]))
        ax.set_xlabel("range (m)")
        ax.set_ylabel("bearing (deg)")
        if k == 0:
            ax.legend(loc="lower right", fontsize=8)
    ax = fig.add_subplot(2, 1, 2)
    scatter = ax.scatter(time_s, range_m, c=bearing, s=6, cmap="twilight")
    fig.colorbar(scatter, ax=ax, label="bearing (deg)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("first return's range (m)")
    ax.set_title("%s: each beam's first return (rise 6 dB over the water in front, staying up 0.2 m), %s detector's map"
                 % (log_path.split("/")[-1], detector))
    fig.tight_layout()
    fig.savefig(out_path, dpi=70)


if __name__ == "__main__":
    main()
