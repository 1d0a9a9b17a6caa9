#!/usr/bin/env bash
# Builds and runs tests/consumer against an installed sonarmap, as a user's project would find the
# package (find_package with the prefix on CMAKE_PREFIX_PATH, nothing else): the whole library
# (sonarmap::sonarmap), then the octree alone (tests/consumer/octree: COMPONENTS octree), configured
# with every other dependency's find_package disabled and linked with nothing but its library.
# Usage: run_consumer_test.sh install BUILD_DIR SOURCE_DIR
#          `cmake --install` into a temporary prefix (not /usr/local, where a compiler looks anyway)
#        run_consumer_test.sh deb BUILD_DIR SOURCE_DIR
#          `cpack -G DEB`, the package's control fields and files checked, then unpacked into a
#          temporary root (dpkg -x) and used from its /usr: the consumer, the CLI, the Python module
set -euo pipefail
mode=$1
build=$(cd "$2" && pwd)
source_dir=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "run_consumer_test.sh ($mode): $*" >&2; exit 1; }

case "$mode" in
  install)
    cmake --install "$build" --prefix "$tmp/install" >/dev/null
    prefix=$tmp/install
    ;;
  deb)
    command -v dpkg-deb >/dev/null || { echo "SKIPPED: dpkg-deb is absent (not a Debian system)"; exit 77; }
    (cd "$tmp" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/package" >/dev/null)
    deb=$(ls "$tmp"/package/sonarmap_*.deb)
    depends=$(dpkg-deb -f "$deb" Depends)
    for needed in libopencv-dev libeigen3-dev libmatio-dev libopencv-core406 libgeographiclib-dev libgdal32; do
      [[ ",$depends," == *"$needed"* ]] || fail "Depends lacks $needed: $depends"
    done
    files=$(dpkg-deb -c "$deb" | awk '{print $6}')
    for needed in ./usr/bin/sonarmap ./usr/libexec/sonarmap/sonarmap-full ./usr/include/sonarmap/io/octomap_binary.hpp \
                  ./usr/lib/cmake/sonarmap/sonarmapConfig.cmake ./usr/lib/cmake/sonarmap/sonarmap_octreeTargets.cmake \
                  ./usr/lib/libsonarmap_octree.a ./usr/lib/libsonarmap_mapping.a ./usr/lib/libsonarmap_geotiff.so \
                  ./usr/lib/sonarmap/sonarmap_geotiff_gdal.so; do
      grep -qxF "$needed" <<<"$files" || fail "the package lacks $needed"
    done
    dpkg -x "$deb" "$tmp/root"
    prefix=$tmp/root/usr
    # The unpacked root's /usr/lib stands for the system's, where the loader finds the package's
    # shared library (libsonarmap_geotiff.so) once installed.
    export LD_LIBRARY_PATH="$prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    "$prefix/bin/sonarmap" --version >/dev/null || fail "the packaged CLI does not run"
    # Every command but cloud is the full tool's, which the lean sonarmap finds in ../libexec/sonarmap.
    "$prefix/bin/sonarmap" --help | grep -q "^  map " || fail "the packaged CLI does not reach the full tool"
    # GDAL is the plugin's (/usr/lib/sonarmap/sonarmap_geotiff_gdal.so, loaded beside
    # libsonarmap_geotiff.so), not the full tool's: --geotiff loads it, nothing else does.
    gdal=$(ldd "$prefix/libexec/sonarmap/sonarmap-full" | grep -i gdal || true)
    [ -z "$gdal" ] || fail "the packaged full tool loads GDAL at start-up: $gdal"
    "$prefix/bin/sonarmap" simulate tank -o "$tmp/sim" --turns 1 -q
    "$prefix/bin/sonarmap" map "$tmp/sim/beams.csv" -o "$tmp/geo.bt" --geotiff "$tmp/geo.tif" --geo-origin 43.2961,5.37 -q ||
      fail "the packaged CLI does not write a GeoTIFF"
    head -c 4 "$tmp/geo.tif" | od -An -tx1 | grep -q "49 49 2a 00" || fail "the packaged CLI's GeoTIFF is not a TIFF"
    if grep -q "^./usr/lib/python3/dist-packages/sonarmap/" <<<"$files"; then
      [[ ",$depends," == *"python3-numpy"* ]] || fail "Depends lacks python3-numpy: $depends"
      PYTHONPATH="$tmp/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c \
        "import sonarmap, os; assert os.path.dirname(sonarmap.__file__).startswith('$tmp'), sonarmap.__file__" ||
        fail "the packaged Python module does not import"
    fi
    ;;
  *) fail "mode must be install or deb" ;;
esac

# The build's own compiler flags (a sanitizer build's library needs the sanitizer runtime too).
cached() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
cmake -S "$source_dir/tests/consumer" -B "$tmp/build" -G Ninja -DCMAKE_BUILD_TYPE="$(cached CMAKE_BUILD_TYPE)" \
  -DCMAKE_CXX_FLAGS="$(cached CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cached CMAKE_EXE_LINKER_FLAGS)" \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$tmp/build" >/dev/null
"$tmp/build/consumer" "$tmp/map.bt"

# The octree alone: a find_package of anything but Eigen fails the configure, and the program links
# libsonarmap_octree.a and nothing else of sonarmap or its other dependencies.
disabled=()
for package in OpenCV PNG Ceres nanoflann absl ZLIB ICU BZip2 PkgConfig; do
  disabled+=("-DCMAKE_DISABLE_FIND_PACKAGE_$package=ON")
done
cmake -S "$source_dir/tests/consumer/octree" -B "$tmp/octree" -G Ninja -DCMAKE_BUILD_TYPE="$(cached CMAKE_BUILD_TYPE)" \
  -DCMAKE_CXX_FLAGS="$(cached CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cached CMAKE_EXE_LINKER_FLAGS)" \
  -DCMAKE_PREFIX_PATH="$prefix" --no-warn-unused-cli "${disabled[@]}" >/dev/null || fail "find_package(sonarmap COMPONENTS octree) needs more than Eigen"
link=$(cd "$tmp/octree" && ninja -t commands octree_consumer | tail -1)
[[ "$link" == *libsonarmap_octree.a* ]] || fail "the octree consumer does not link libsonarmap_octree.a: $link"
others=$(tr ' ' '\n' <<<"$link" | grep -E '\.(a|so)$|^-l' | grep -v 'libsonarmap_octree\.a$' || true)
[ -z "$others" ] || fail "the octree consumer links more than the octree: $others"
cmake --build "$tmp/octree" >/dev/null
"$tmp/octree/octree_consumer"

# Point clouds (COMPONENTS octree algorithms io): the program loads none of the other components'
# shared libraries, and neither does the installed `sonarmap` that runs `cloud`.
cmake -S "$source_dir/tests/consumer/cloud" -B "$tmp/cloud" -G Ninja -DCMAKE_BUILD_TYPE="$(cached CMAKE_BUILD_TYPE)" \
  -DCMAKE_CXX_FLAGS="$(cached CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cached CMAKE_EXE_LINKER_FLAGS)" \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null || fail "find_package(sonarmap COMPONENTS octree algorithms io) failed"
cmake --build "$tmp/cloud" >/dev/null
"$tmp/cloud/cloud_consumer" "$tmp/cloud.bt"
heavy='opencv|matio|hdf5|boost|rosbag|roscpp|ceres|gdal|sonarmap_geotiff|png|icu|glog|gflags|httplib'
for program in "$tmp/cloud/cloud_consumer" "$prefix/bin/sonarmap"; do
  loaded=$(ldd "$program" | grep -Ei "$heavy" || true)
  [ -z "$loaded" ] || fail "$program loads more than point clouds need: $loaded"
done
