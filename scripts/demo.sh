#!/usr/bin/env bash
# Installs what is missing, builds the sonarmap tool and runs its demo: the built-in simulated
# tank is mapped into out/demo/. Needs no data. Extra arguments go to `sonarmap demo` (e.g. -q).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DSONARMAP_BUILD_TESTS=OFF -DSONARMAP_BUILD_BENCHMARKS=OFF  # the tool only: faster
./build/apps/cli/sonarmap demo -o out/demo "$@"
echo "wrote out/demo/tank.bt (open it with octovis), tank.html (open it in a browser), tank.png," \
  "tank_polar.png, tank_cartesian.png, the simulated input: beams.csv, scene.txt (its ground truth)," \
  "and the 3D mission in out/demo/3d-mission/ (map.html, map.bt, map_top.png, map_side.png)"
