#!/usr/bin/env bash
# bench/peers/build.sh PEERS_DIR: builds the peers' drivers of the table in docs/performance.md
# ("Peers") into PEERS_DIR/bin, against checkouts the user made there (the peers' code is never in
# this repository):
#   git clone https://github.com/facontidavide/Bonxai PEERS_DIR/bonxai        # v0.6.0-11-g3e8e63f
#   git clone -b v1.0.0 https://github.com/UnknownFreeOccupied/ufomap PEERS_DIR/ufomap
# OctoMap is Debian's liboctomap-dev (1.9.7); UFOMap needs liblz4-dev and libtbb-dev. Everything
# with g++ -O3 -march=native, as the peers' own benchmarks build.
set -euo pipefail
peers=$(realpath "${1:?usage: build.sh PEERS_DIR}")
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$peers/bin"
flags=(-std=c++17 -O3 -march=native -DNDEBUG -I"$here")
octomap=(-loctomap -loctomath)

g++ "${flags[@]}" "$here/octomap_cloud.cpp" -o "$peers/bin/octomap_cloud" "${octomap[@]}"

g++ "${flags[@]}" -I"$peers/bonxai/bonxai_core/include" -I"$peers/bonxai/bonxai_map/include" \
  "$here/bonxai_cloud.cpp" "$peers/bonxai/bonxai_map/src/probabilistic_map.cpp" \
  -o "$peers/bin/bonxai_cloud" "${octomap[@]}"

ufo="$peers/ufomap/ufomap"
g++ "${flags[@]}" -I"$ufo/include" "$here/ufomap_cloud.cpp" "$ufo/src/map/occupancy_map.cpp" \
  "$ufo/src/geometry/bounding_volume.cpp" "$ufo/src/geometry/collision_checks.cpp" \
  -o "$peers/bin/ufomap_cloud" "${octomap[@]}" -llz4 -ltbb
echo "built: $(ls "$peers/bin" | tr '\n' ' ')"
