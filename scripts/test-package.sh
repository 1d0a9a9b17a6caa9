#!/usr/bin/env bash
# The Debian package on a fresh Debian 12, as a vehicle computer gets it: builds
# sonarmap_<version>_<arch>.deb from build/ (cpack), makes a minimal Debian 12 root with debootstrap
# (root, and Debian's mirror, needed), installs the package there with
# `apt-get install ./sonarmap_*.deb` (pulling its dependencies from Debian), then, inside that root:
# builds and runs the consumer projects (tests/consumer, find_package(sonarmap); tests/consumer/octree,
# the octree component alone), runs the `sonarmap` tool (a map written as a GeoTIFF too: the GDAL
# plugin), and imports the Python module with the system's python3.
# Usage: bash scripts/test-package.sh [ROOT_DIR]   (default: a temporary folder, removed after; a
#        ROOT_DIR given is kept and reused). BUILD_DIR=... names the build folder (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
[ "$(id -u)" -eq 0 ] || { echo "test-package.sh: run as root (debootstrap, chroot)" >&2; exit 1; }
[ -f "$build"/CPackConfig.cmake ] || { echo "test-package.sh: build first (bash scripts/build.sh)" >&2; exit 1; }
command -v debootstrap >/dev/null ||
  { apt-get update -qq; DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null; }

keep=${1:+yes}
root=${1:-$(mktemp -d /tmp/sonarmap-deb12.XXXXXX)}
cleanup() {
  umount "$root/proc" 2>/dev/null || true
  [ -n "$keep" ] || rm -rf "$root"
}
trap cleanup EXIT

(cd "$build" && cpack -G DEB >/dev/null)
deb=$(ls -t "$build"/sonarmap_*.deb | head -1)
echo "test-package.sh: $deb ($(du -h "$deb" | cut -f1)) on a fresh Debian 12 in $root"
[ -x "$root/usr/bin/apt-get" ] || debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >/dev/null
cp /etc/resolv.conf "$root/etc/resolv.conf"
mountpoint -q "$root/proc" || mount -t proc proc "$root/proc"
mkdir -p "$root/tmp/sonarmap"
cp "$deb" "$root/tmp/sonarmap/"
cp -r tests/consumer "$root/tmp/sonarmap/consumer"
chroot "$root" /bin/bash -euo pipefail -c '
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends cmake g++ ninja-build >/dev/null
  apt-get install -y -qq --no-install-recommends /tmp/sonarmap/sonarmap_*.deb >/dev/null
  sonarmap --version
  # --geotiff: the GDAL plugin found in /usr/lib/sonarmap and GDAL (libgdal32) installed with the package
  sonarmap simulate tank -o /tmp/sonarmap/sim --turns 1 -q
  sonarmap map /tmp/sonarmap/sim/beams.csv -o /tmp/sonarmap/geo.bt --geotiff /tmp/sonarmap/geo.tif --geo-origin 43.2961,5.37 -q
  head -c 4 /tmp/sonarmap/geo.tif | od -An -tx1 | grep -q "49 49 2a 00"  # a little-endian TIFF
  cd /tmp/sonarmap
  cmake -S consumer -B consumer-build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build consumer-build >/dev/null
  ./consumer-build/consumer /tmp/sonarmap/map.bt
  cmake -S consumer/octree -B octree-build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build octree-build >/dev/null
  ./octree-build/octree_consumer
  python3 -c "import sonarmap, numpy as np
m = sonarmap.OccupancyMap(0.1)
m.insert_point_cloud(np.array([[1.0, 0.0, 0.0]]), np.zeros(3))
print(\"python: sonarmap from\", sonarmap.__file__, \"-\", m.num_leaf_nodes(), \"leaves\")"
'
echo "test-package.sh: the package installs on Debian 12 and serves the consumer, the tool and Python"
