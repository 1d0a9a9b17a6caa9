"""sonarmap_ros installed, found by Debian's rosrun and roslaunch (issue 80, finding 9). Run by ctest
with /usr/bin/python3 (rospy, genpy):

    /usr/bin/python3 tests/ros/test_ros_install.py BUILD_DIR [CMAKE]

`cmake --install BUILD_DIR --prefix P` into a temporary P, then, in the environment a user of that
prefix sets (ROS_PACKAGE_PATH=P/share, CMAKE_PREFIX_PATH=P, nothing else of ROS's but the master's
ROS_MASTER_URI), beside roscore on a free port:
  (a) P has the node in catkin's layout: lib/sonarmap_ros/sonarmap_ros_node, share/sonarmap_ros/
      package.xml, launch/sonarmap.launch and README.md, docs/ros.md as share/doc/sonarmap/ros.md, and
      catkin's workspace marker P/.catkin;
  (b) `rosrun sonarmap_ros sonarmap_ros_node _pose_source:=none` starts P's node (the process behind
      /sonarmap, asked its pid over XML-RPC, runs P/lib/sonarmap_ros/sonarmap_ros_node) and its
      `/sonarmap/reset` (std_srvs/Empty) answers; it stops on SIGINT;
  (c) `roslaunch sonarmap_ros sonarmap.launch pose_source:=none` uses that master, starts P's node
      and its `/sonarmap/reset` answers.

Exits 77 (ctest's skip) when roscore, rosrun or roslaunch is absent (Debian: ros-core, rosbash).
"""

import os
import pathlib
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xmlrpc.client

from ros_harness import SKIP, Master, wait_for

NODE = "/sonarmap"
UP_TIMEOUT_S = 20


def node_executable(node_name):
    """The executable of the process behind `node_name`: its pid from the node's own XML-RPC API."""
    import rosgraph.masterapi
    try:
        uri = rosgraph.masterapi.Master("/sonarmap_install_test").lookupNode(node_name)
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid("/sonarmap_install_test")
        return os.readlink(f"/proc/{pid}/exe") if code == 1 else None
    except (rosgraph.masterapi.Error, OSError):
        return None


def answers_reset(master, process):
    """Whether /sonarmap/reset answers a std_srvs/Empty call within UP_TIMEOUT_S (False at once when
    `process` has exited)."""
    rospy = master.rospy
    deadline = time.time() + UP_TIMEOUT_S
    while time.time() < deadline:
        if process.poll() is not None:
            print(f"  exited with {process.returncode}")
            return False
        try:
            rospy.wait_for_service(NODE + "/reset", timeout=0.5)
            rospy.ServiceProxy(NODE + "/reset", master.srv.Empty)()
            return True
        except rospy.ROSException:
            continue
        except rospy.ServiceException as error:
            print(f"  {NODE}/reset: {error}")
            return False
    return False


def stop(process):
    process.send_signal(signal.SIGINT)
    try:
        process.wait(15)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def gone(master):
    """The node unregistered from the master (its reset service no longer listed)."""
    import rosgraph.masterapi
    try:
        rosgraph.masterapi.Master("/sonarmap_install_test").lookupService(NODE + "/reset")
        return False
    except rosgraph.masterapi.Error:
        return True


def started(master, what, command, env, expected_exe, log):
    """Runs `command`, checks that the node it starts is `expected_exe` and answers ~reset, stops it."""
    failures = []
    with open(log, "w+") as out:
        process = subprocess.Popen(command, env=env, stdout=out, stderr=subprocess.STDOUT)
        try:
            if not answers_reset(master, process):
                failures.append(f"{what}: {NODE}/reset did not answer (waited {UP_TIMEOUT_S} s at most)")
            exe = wait_for(lambda: node_executable(NODE), 5) if process.poll() is None else None
            if exe != str(expected_exe):
                failures.append(f"{what}: {NODE} runs {exe}, not {expected_exe}")
            else:
                print(f"{what}: {NODE} is {exe}; {NODE}/reset answered")
        finally:
            stop(process)
        if not wait_for(lambda: gone(master), 10):
            failures.append(f"{what}: {NODE} still registered after SIGINT")
        if failures:
            out.seek(0)
            print(f"--- {what}'s output:\n{out.read()}---")
    return failures


def main(build_dir, cmake):
    missing = [tool for tool in ("roscore", "rosrun", "roslaunch") if shutil.which(tool) is None]
    if missing:
        print(f"SKIP: {', '.join(missing)} not installed (Debian: ros-core, rosbash, rospack-tools)")
        return SKIP
    prefix = pathlib.Path(tempfile.mkdtemp(prefix="sonarmap_ros_install_"))
    try:
        subprocess.run([cmake, "--install", build_dir, "--prefix", str(prefix)], check=True, stdout=subprocess.DEVNULL)
        failures = []
        node_exe = prefix / "lib/sonarmap_ros/sonarmap_ros_node"
        for path in (node_exe, prefix / "share/sonarmap_ros/package.xml", prefix / "share/sonarmap_ros/launch/sonarmap.launch",
                     prefix / "share/sonarmap_ros/README.md", prefix / "share/doc/sonarmap/ros.md", prefix / ".catkin"):
            if not path.is_file():
                failures.append(f"not installed: {path.relative_to(prefix)}")
        with Master() as master:
            # the user's environment: the master's, ROS's search paths only the prefix (Debian's tools
            # add /usr/share and /usr themselves)
            env = {k: v for k, v in master.env.items() if k not in ("ROS_PACKAGE_PATH", "CMAKE_PREFIX_PATH")}
            env.update(ROS_PACKAGE_PATH=str(prefix / "share"), CMAKE_PREFIX_PATH=str(prefix))
            env.setdefault("HOME", str(master.tmp))  # sonarmap.launch's save_path is $(env HOME)/sonarmap.bt
            failures += started(master, "rosrun", ["rosrun", "sonarmap_ros", "sonarmap_ros_node", "_pose_source:=none"],
                                env, node_exe, master.tmp / "rosrun.log")
            failures += started(master, "roslaunch", ["roslaunch", "sonarmap_ros", "sonarmap.launch", "pose_source:=none"],
                                env, node_exe, master.tmp / "roslaunch.log")
        if failures:
            print("\n".join("FAIL: " + f for f in failures))
            return 1
        print("all cases passed")
        return 0
    finally:
        shutil.rmtree(prefix, ignore_errors=True)


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else "cmake"))
