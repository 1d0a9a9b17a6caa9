#!/usr/bin/env bash
# Installs the Debian 12 packages sonarmap needs to build and test, when any is missing.
set -euo pipefail
packages=(build-essential cmake ninja-build pkg-config
  libopencv-dev libmatio-dev zlib1g-dev libcli11-dev libeigen3-dev libabsl-dev
  libgtest-dev libbenchmark-dev liboctomap-dev
  # the Python module, its tests and the example notebook (Debian's python3, not PyPI)
  python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib jupyter-nbconvert python3-ipykernel
  # sonarmap view: three.js inlined into the HTML, and headless Chromium for its browser test
  libjs-three chromium)
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
