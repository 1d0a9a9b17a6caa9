#!/usr/bin/env bash
# Installs the Debian 12 packages sonarmap needs to build, when any is missing; `install-deps.sh test`
# also what its tests need (the notebook's runner, pytest, headless Chromium).
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config
  libopencv-dev libpng-dev libmatio-dev zlib1g-dev libicu-dev libnanoflann-dev libcli11-dev nlohmann-json3-dev libeigen3-dev libabsl-dev libceres-dev
  # ROS 1 bags: the container (chunks, bz2, lz4, index) from Debian's rosbag_storage; ROS 2's MCAP
  # chunks: zstd and lz4 frames
  librosbag-storage-dev libzstd-dev liblz4-dev libsqlite3-dev
  libgtest-dev libbenchmark-dev liboctomap-dev
  # positions on the Earth (src/nav/geodetic.cpp) and the GeoTIFF writer (src/geotiff)
  libgeographiclib-dev libgdal-dev
  # the Python module and its examples (Debian's python3, not PyPI)
  python3-dev pybind11-dev python3-numpy python3-matplotlib python3-scipy
  # sonarmap view: three.js, compiled into the tool and inlined into each page
  libjs-three
  # live --serve: the page's HTTP server
  libcpp-httplib-dev
  # the ROS 1 node (ros/sonarmap_ros, SONARMAP_BUILD_ROS: on when roscpp is found): roscpp, tf2, topic_tools'
  # ShapeShifter and the messages it publishes and subscribes
  libroscpp-dev libtf2-ros-dev libtopic-tools-dev libsensor-msgs-dev libnav-msgs-dev libvisualization-msgs-dev
  libgeometry-msgs-dev libstd-srvs-dev libtf2-msgs-dev)
if [ "${1:-}" = test ]; then
  # pytest, the notebook run by nbconvert, headless Chromium for the viewer's browser tests, and
  # ccache for the repeated builds of CI and the sanitizers (scripts/compiler-cache.sh)
  packages+=(python3-pytest jupyter-nbconvert python3-ipykernel chromium ccache)
  # the ROS node's test against a real master: roscore, rosbag play, rostopic, rospy (tests/ros); rosrun
  # and rospack, which find the installed node (tests/ros/test_ros_install.py; ros-core only recommends them)
  packages+=(ros-core python3-roslaunch python3-rosmaster python3-rosbag python3-rospy python3-genpy librosbag-dev
    rosbash rospack-tools)
  # gdalinfo and gdallocationinfo read the GeoTIFFs back (tests/cli/test_cli_geo.cpp); python3-gdal
  # draws the chart of docs/geo.md (scripts/geotiff_chart.py)
  packages+=(gdal-bin python3-gdal)
  # node and npm for the live page's browser test (tests/live/page_test.js), unless a node is there
  command -v node >/dev/null || packages+=(nodejs npm)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The tests' npm packages, at the versions their package-lock.json pin: node-mavlink for the MAVLink
# interop tests (tests/interop) and playwright-core, which drives Debian's chromium for the live
# page's browser test (tests/live; it downloads no browser). Node.js and npm come from Debian unless a
# node is already installed. Each step only warns when it fails (no network): the build does not
# need them, and those tests skip themselves, saying why.
if [ "${1:-}" = test ]; then
  root="$(cd "$(dirname "$0")/.." && pwd)"
  if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null; } ||
      echo "install-deps.sh: warning: Node.js and npm not installed: the npm-based tests will be skipped" >&2
  fi
  for folder in interop live; do
    if command -v npm >/dev/null && [ ! -d "$root/tests/$folder/node_modules" ]; then
      (cd "$root/tests/$folder" && npm ci --no-audit --no-fund --loglevel=error) ||
        echo "install-deps.sh: warning: npm ci in tests/$folder failed: its tests will be skipped" >&2
    fi
  done
fi
