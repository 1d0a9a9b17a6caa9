"""sonarmap_ros_node's final map against `sonarmap map` of the same bag, at several playback rates,
with Debian's roscore (tests/ros/ros_harness.py): how far the node keeps up with a real bag.

    /usr/bin/python3 bench/ros/node_agreement.py NODE SONARMAP_CLI PYTHON_MODULE_DIR BAG TOPIC [RATE ...]

Prints per rate: the play's wall time, the agreement (bench/map_agreement.py's measure over the known
voxels), the node's largest queue delay and lag into the map. Without navigation in the bag the node
runs with pose_source none; with an Odometry topic, give it as a third parameter: ODOM_TOPIC=/odometry.
"""

import os
import pathlib
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tests" / "ros"))
from ros_harness import Master, agreement, bt_bytes, wait_for  # noqa: E402


def main(node, cli, python_dir, bag, topic, *rates):
    odom = os.environ.get("ODOM_TOPIC")
    params = {"sonar_topic": topic, "resolution": 0.1, "idle_commit_s": 1.0}
    params.update({"pose_source": "odometry", "odom_topic": odom} if odom else {"pose_source": "none"})
    with Master(python_dir) as master:
        ref = master.tmp / "ref.bt"
        subprocess.run([cli, "map", bag, "-o", str(ref), "-q", "--resolution", "0.1"], check=True)
        print("rate | played in | agreement | voxels | largest queue delay | largest lag into the map")
        for rate in rates or ("1", "5", "20"):
            node_process, log = master.start_node(node, params)
            maps = []
            subscriber = master.rospy.Subscriber("/octomap_binary", master.Octomap, lambda m: maps.append(m))
            master.rospy.wait_for_service("/sonarmap/reset", timeout=20)
            started = time.time()
            master.play(bag, rate=float(rate))
            played = time.time() - started - 2
            wait_for(lambda: "the sonar is silent" in log.read_text(errors="replace"), 30)
            time.sleep(1.5)
            node_bt = master.tmp / f"node_{rate}.bt"
            node_bt.write_bytes(bt_bytes(maps[-1]))
            same, voxels, _, known = agreement(node_bt, ref)
            line = [l for l in log.read_text(errors="replace").splitlines() if "the sonar is silent" in l][-1]
            delay = line.split("largest queue delay ")[1].split(" s")[0]
            lag = line.split("into the map ")[1].split(" s")[0]
            print(f"{rate}x | {played:.1f} s | {same:.6f} | {known} | {delay} s | {lag} s")
            subscriber.unregister()
            node_process.terminate()
            node_process.wait(10)


if __name__ == "__main__":
    main(*sys.argv[1:])
