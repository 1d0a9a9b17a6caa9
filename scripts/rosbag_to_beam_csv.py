#!/usr/bin/python3
"""Writes the sonar beams of a ROS 1 bag as a beam CSV (docs/formats.md, "Beam CSV") that
`sonarmap map` reads, until sonarmap reads bags itself. Uses Debian's python3-rosbag
(apt-get install python3-rosbag); run it with Debian's /usr/bin/python3.

    /usr/bin/python3 scripts/rosbag_to_beam_csv.py BAG.bag OUT.csv [--topic TOPIC]

The sonar topic is the first whose messages carry a bearing (`angle` or `bearing`, degrees), a bin
length (`bin_distance_step`, metres) and intensities (`bins[].intensity` or `intensities`), as the
micron_driver_ros driver's `ScanLine` does; `--topic` picks another. Times are the header stamps
from the first beam, seconds. Bearings are written as the message states them (degrees,
counter-clockwise positive in the beam CSV): the driver's direction is not in the bag.
"""
import argparse
import sys

import rosbag


def intensities_of(msg):
    if hasattr(msg, "bins"):
        return [b.intensity for b in msg.bins]
    return list(bytearray(msg.intensities)) if isinstance(msg.intensities, (bytes, bytearray)) else list(msg.intensities)


def is_sonar(msg):
    return (hasattr(msg, "angle") or hasattr(msg, "bearing")) and hasattr(msg, "bin_distance_step") and (
        hasattr(msg, "bins") or hasattr(msg, "intensities"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bag")
    parser.add_argument("csv")
    parser.add_argument("--topic")
    args = parser.parse_args()
    rows = []
    topic = args.topic
    with rosbag.Bag(args.bag) as bag:
        for name, msg, _ in bag.read_messages(topics=[topic] if topic else None):
            if topic is None:
                if not is_sonar(msg):
                    continue
                topic = name
            elif name != topic:
                continue
            bearing = msg.angle if hasattr(msg, "angle") else msg.bearing
            rows.append((msg.header.stamp.to_sec(), bearing, msg.bin_distance_step, intensities_of(msg)))
    if not rows:
        sys.exit("%s: no sonar messages%s" % (args.bag, " on " + topic if topic else ""))
    start = rows[0][0]
    bins = max(len(r[3]) for r in rows)
    with open(args.csv, "w") as out:
        out.write("time_s,bearing_deg,bin_length_m," + ",".join("b%d" % i for i in range(bins)) + "\n")
        for time_s, bearing, step, values in rows:
            out.write("%.6f,%r,%r,%s\n" % (time_s - start, float(bearing), float(step), ",".join(map(str, values))))
    print("%d beams of %s -> %s" % (len(rows), topic, args.csv))


if __name__ == "__main__":
    main()
