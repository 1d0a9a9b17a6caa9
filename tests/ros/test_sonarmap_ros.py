"""sonarmap_ros_node against a real ROS 1 master (Debian's roscore, started here on a free port):
`rosbag play` of a bag at 10x its rate, the node's final octomap_binary decoded and compared with
`sonarmap map` of the same bag (agreement over the known volume, bench/map_agreement.py's measure;
with ~slam, `map --slam` of a compass-only bag, and map → odom on /tf),
~save_map writing what octomap_binary holds, ~reset emptying the map, and the message received by
rospy with octomap_msgs' real definition (generated here by genpy from Octomap.msg, so its md5 is
genmsg's). Run by ctest with /usr/bin/python3 (rospy, genpy):

    /usr/bin/python3 tests/ros/test_sonarmap_ros.py NODE SONARMAP_CLI PYTHON_MODULE_DIR SHARED_DATA

Exits 77 (ctest's skip) when roscore or rosbag is absent.
"""

import math
import pathlib
import subprocess
import sys
import time

from ros_harness import agreement, bt_bytes, run_test, voxel_classes


def main(node, cli, python_dir, shared):
    return run_test(python_dir, lambda master: all_cases(master, node, cli, shared))


def all_cases(master, node, cli, shared):
    """Each bag's case against the master; returns the failures."""
    tmp = master.tmp
    cases = []
    sim = tmp / "sim.bag"
    subprocess.run([cli, "simulate", "harbour", "-o", str(tmp / "sim"), "--turns", "3", "--speed", "0.1", "--heading",
                    "30", "--mounting", "0.3,0,0.2,0,20,0", "--bag", str(sim), "-q"], check=True)
    cases.append(("simulated, navigation and a tilted mounting", sim, "/sonar/scan_line",
                  {"pose_source": "odometry", "odom_topic": "/odometry"}, []))
    # A vehicle without a DVL (heading only, north and east 0), localized by the scans (~slam)
    compass = tmp / "compass.bag"
    subprocess.run([cli, "simulate", "harbour", "-o", str(tmp / "compass"), "--turns", "8", "--speed", "0.1",
                    "--heading", "30", "--heading-bias", "2", "--no-position", "--bag", str(compass), "-q"], check=True)
    cases.append(("simulated, compass only, ~slam", compass, "/sonar/scan_line",
                  {"pose_source": "odometry", "odom_topic": "/odometry", "slam": "true"}, ["--slam"]))
    pool = pathlib.Path(shared) / "micron_pool_ros1.bag"
    if pool.exists():
        cases.append(("pool", pool, "/micron_driver/scan_line", {"pose_source": "none"}, []))
    else:
        print(f"note: {pool} absent, the pool bag's case skipped")
    failures = []
    for name, bag, topic, params, map_args in cases:
        failures += run_case(master, name, bag, topic, params, map_args, node, cli)
    return failures


def run_case(master, name, bag, topic, params, map_args, node, cli):
    tmp, env, rospy, Octomap, TFMessage = master.tmp, master.env, master.rospy, master.Octomap, master.TFMessage
    failures = []
    resolution = "0.1"
    saved = tmp / f"saved_{len(master.processes)}.bt"
    node_process, log_path = master.start_node(node, dict({"sonar_topic": topic, "resolution": resolution,
                                                           "idle_commit_s": 1.0, "publish_period_s": 0.5,
                                                           "save_path": saved}, **params))
    received, raw = [], []
    subscriber = rospy.Subscriber("/octomap_binary", Octomap, lambda m: received.append((time.time(), m)))
    corrections = []  # map → odom, as any TF listener receives it
    tf_subscriber = rospy.Subscriber("/tf", TFMessage, lambda m: corrections.extend(
        t for t in m.transforms if t.header.frame_id == "map" and t.child_frame_id == "odom"))
    # the connection as any subscriber sees it: type, md5 and definition the node announces
    raw_subscriber = rospy.Subscriber("/octomap_binary", rospy.AnyMsg, lambda m: raw.append(m._connection_header))
    rospy.wait_for_service("/sonarmap/reset", timeout=20)
    started = time.time()
    # -d: rosbag play waits after advertising, so that the node's subscriptions connect before the first message
    master.play(bag)
    played = time.time()
    # the final map: the one published after the node said the sonar fell silent (idle_commit_s)
    deadline = played + 30
    silent_at = None
    while time.time() < deadline:
        if silent_at is None and "the sonar is silent" in log_path.read_text(errors="replace"):
            silent_at = time.time()
        if silent_at is not None and received and received[-1][0] > silent_at - 0.2 and time.time() - silent_at > 1.0:
            break
        time.sleep(0.2)
    if silent_at is None or not received:
        subscriber.unregister()
        return [f"{name}: no final octomap_binary received"]
    final = received[-1][1]
    raw_subscriber.unregister()
    if not raw or raw[-1]["md5sum"] != Octomap._md5sum or raw[-1]["type"] != "octomap_msgs/Octomap":
        failures.append(f"{name}: the connection says {raw[-1] if raw else None}, genmsg's md5 is {Octomap._md5sum}")
    elif "int8[] data" not in raw[-1]["message_definition"]:
        failures.append(f"{name}: the announced definition lacks octomap_msgs/Octomap's data field")
    kind = subprocess.run(["rostopic", "type", "/octomap_binary"], env=env, capture_output=True, text=True).stdout.strip()
    if kind != "octomap_msgs/Octomap":
        failures.append(f"{name}: rostopic type says {kind!r}")
    node_bt = tmp / "node.bt"
    node_bt.write_bytes(bt_bytes(final))
    ref_bt = tmp / "ref.bt"
    subprocess.run([cli, "map", str(bag), "-o", str(ref_bt), "-q", "--resolution", resolution] + map_args, check=True)
    same, node_voxels, map_voxels, known = agreement(node_bt, ref_bt)
    print(f"{name}: bag played at 10x in {played - started - 2:.1f} s; node {node_voxels} voxels, map {map_voxels}; "
          f"agreement {same:.6f} over {known}")
    if not known or same < 0.999:
        failures.append(f"{name}: agreement {same:.6f} < 0.999")
    tf_subscriber.unregister()
    if "--slam" in map_args:
        # the scans moved the compass-only track (north and east 0): map → odom is not the identity
        moved = [math.hypot(t.transform.translation.x, t.transform.translation.y) for t in corrections]
        # the last is the final correction: the odom frame's origin (where the compass-only poses
        # stay) at the corrected track's end, which `map --slam --trajectory` writes (NED)
        track = tmp / "slam_track.csv"
        subprocess.run([cli, "map", str(bag), "-o", str(tmp / "slam.bt"), "-q", "--resolution", resolution, "--trajectory",
                        str(track)] + map_args, check=True)
        north, east = (float(v) for v in track.read_text().strip().splitlines()[-1].split(",")[1:3])
        print(f"{name}: {len(corrections)} map → odom transforms on /tf, the last {moved[-1] if moved else 0:.2f} m; "
              f"the track ends {math.hypot(north, east):.2f} m from its start")
        last = corrections[-1].transform.translation if corrections else None
        if not moved or moved[-1] < 1.0 or math.hypot(last.x - east, last.y - north) > 0.01:
            failures.append(f"{name}: map → odom on /tf: {len(moved)} transforms, the last at {last}, the track's "
                            f"end at east {east:.3f} north {north:.3f} m")
    elif corrections:
        failures.append(f"{name}: map → odom published without ~slam")
    save = rospy.ServiceProxy("/sonarmap/save_map", master.srv.Trigger)()
    if not save.success:
        failures.append(f"{name}: save_map failed: {save.message}")
    else:
        written = saved.read_bytes()
        data = written[written.index(b"\ndata\n") + 6:]
        if data != bytes(x & 0xFF for x in final.data):
            failures.append(f"{name}: save_map's file holds other data than octomap_binary")
    # ~clear_bbx (octomap_server's service type): the voxels of x < 0 become unknown, the others stay
    count = len(received)
    srv = master.srv
    rospy.ServiceProxy("/sonarmap/clear_bbx", srv.BoundingBoxQuery)(srv.Point(-1e4, -1e4, -1e4), srv.Point(0, 1e4, 1e4))
    deadline = time.time() + 10
    while len(received) == count and time.time() < deadline:
        time.sleep(0.1)
    cleared_bt = tmp / "cleared.bt"
    cleared_bt.write_bytes(bt_bytes(received[-1][1]))
    cleared = voxel_classes(cleared_bt)
    resolution_m = float(resolution)
    a = voxel_classes(node_bt)
    kept = {k: v for k, v in a.items() if (k[0] + 0.5) * resolution_m > 0}
    if len(received) == count or cleared != kept or len(kept) == len(a):
        failures.append(f"{name}: clear_bbx left {len(cleared)} voxels, expected the {len(kept)} of x > 0 of {len(a)}")
    count = len(received)
    rospy.ServiceProxy("/sonarmap/reset", master.srv.Empty)()
    deadline = time.time() + 10
    while len(received) == count and time.time() < deadline:
        time.sleep(0.1)
    if len(received) == count or len(received[-1][1].data) != 0:
        failures.append(f"{name}: reset did not publish an empty map")
    subscriber.unregister()
    node_process.terminate()
    node_process.wait(10)
    for line in log_path.read_text(errors="replace").splitlines():
        if "silent" in line or "ERROR" in line or "WARN" in line:
            print(f"{name}: node: {line.strip()}")
        if "largest queue delay" in line:
            # keeping up at 10x: no beam waited in the queue for as long as a second
            delay = float(line.split("largest queue delay ")[1].split(" s")[0])
            if delay >= 1.0:
                failures.append(f"{name}: a beam waited {delay} s in the queue at 10x")
    return failures


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
