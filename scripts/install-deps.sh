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
  # the Python module and its examples (Debian's python3, not PyPI)
  python3-dev pybind11-dev python3-numpy python3-matplotlib
  # sonarmap view: three.js, compiled into the tool and inlined into each page
  libjs-three
  # live --serve: the page's HTTP server
  libcpp-httplib-dev)
if [ "${1:-}" = test ]; then
  # pytest, the notebook run by nbconvert, headless Chromium for the viewer's browser tests, and
  # ccache for the repeated builds of CI and the sanitizers (scripts/compiler-cache.sh)
  packages+=(python3-pytest jupyter-nbconvert python3-ipykernel chromium ccache)
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
if [ "${1:-}" = test ] && command -v npm >/dev/null; then
  # playwright-core at the version tests/live/package-lock.json pins, which drives Debian's chromium
  # (it downloads no browser). Without network the build goes on and that test is skipped.
  live_tests="$(cd "$(dirname "$0")/.." && pwd)/tests/live"
  (cd "$live_tests" && npm ci --no-audit --no-fund --loglevel=error) ||
    echo "warning: npm ci in tests/live failed (no network?): the live page's browser test will be skipped" >&2
fi
