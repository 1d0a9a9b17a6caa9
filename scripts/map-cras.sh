#!/usr/bin/env bash
# Installs what is missing, builds, and maps the paper's CRAS tank dataset into out/. The data is
# read from ../shared/data, or from the folder in SONARMAP_DATA. Without it, see scripts/demo.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
data=${SONARMAP_DATA:-../shared/data}/cras_micron_tank_static.mat
if [ ! -f "$data" ]; then
  echo "no CRAS data at $data: set SONARMAP_DATA to its folder, or run scripts/demo.sh (simulated tank)" >&2
  exit 1
fi
mkdir -p out
./build/apps/cli/sonarmap map "$data" -o out/cras_tank.bt --png out/cras_tank.png \
  --polar-png out/cras_polar.png --cartesian-png out/cras_cartesian.png --tank-report
echo "wrote out/cras_tank.bt (open it with octovis) and out/cras_tank.png, out/cras_polar.png, out/cras_cartesian.png"
