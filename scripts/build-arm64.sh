#!/usr/bin/env bash
# sonarmap for arm64 (aarch64: a Raspberry Pi running a 64-bit BlueOS, or any 64-bit Arm Debian 12),
# cross-built on an amd64 Debian 12 and tested there under qemu-user. Not run by CI (it takes
# 20 to 40 minutes on two cores); docs/blueos.md has its figures. As root (or through sudo):
#   1. installs the host's amd64 tools with apt-get: the cross compiler (crossbuild-essential-arm64),
#      mmdebstrap, qemu-user, cmake, ninja, pkg-config. The host's dpkg architectures are left as
#      they are: no `dpkg --add-architecture arm64`, no :arm64 package on the host;
#   2. makes an arm64 Debian 12 sysroot with the build dependencies, unpacked, not installed
#      (mmdebstrap --variant=extract), and rewrites its absolute library symlinks as relative ones;
#   3. configures (a toolchain file written into the build folder) and builds, Release, without the
#      Python module, the ROS 1 node and the benchmarks (see SONARMAP_ARM64_CMAKE_ARGS);
#   4. runs the arm64 `sonarmap` under qemu-aarch64 (--version, simulate, map) and compares its map
#      with the amd64 tool's (build/apps/cli/sonarmap, when built), then the GoogleTest suite (ctest
#      with qemu-aarch64 as CMAKE_CROSSCOMPILING_EMULATOR);
#   5. builds the arm64 Debian package sonarmap_<version>_arm64.deb (cpack), which
#      packaging/blueos/Dockerfile installs.
#   6. checks the BlueOS extension's content without Docker: an arm64 root with what
#      packaging/blueos/Dockerfile installs, and packaging/blueos/check.sh on it under qemu.
#   gtest (not in all): each GoogleTest executable run directly under qemu, one line each.
# Usage: bash scripts/build-arm64.sh [all|sysroot|build|test|deb|image|gtest]   (default all)
# Environment: SYSROOT (default /var/tmp/sonarmap-arm64-sysroot), BUILD_DIR (default
#   /var/tmp/sonarmap-build-arm64), JOBS (default 2), CTEST_ARGS (extra ctest arguments, e.g.
#   "-R octree"), BUILD_TARGET (the targets built, default all: e.g. "sonarmap_cli test_octree"),
#   AMD64_SONARMAP (the amd64 tool to compare with, default build/apps/cli/sonarmap).
# The figures it prints (build time, ctest's counts, sizes) are logged in $BUILD_DIR/arm64-*.log.
set -euo pipefail
cd "$(dirname "$0")/.."
src=$PWD
stage=${1:-all}
sysroot=${SYSROOT:-/var/tmp/sonarmap-arm64-sysroot}
build=${BUILD_DIR:-/var/tmp/sonarmap-build-arm64}
jobs=${JOBS:-2}
amd64_tool=${AMD64_SONARMAP:-$src/build/apps/cli/sonarmap}
say() { echo "build-arm64.sh: $*" >&2; }
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"

# The arm64 build dependencies: scripts/install-deps.sh's, less the Python module's, ROS 1's and the
# benchmarks'. libc6-dev and libstdc++-12-dev: the sysroot's C and C++ runtime for the linker.
sysroot_packages=(libc6-dev libstdc++-12-dev
  libopencv-dev libpng-dev libmatio-dev zlib1g-dev libicu-dev libnanoflann-dev libcli11-dev nlohmann-json3-dev
  libeigen3-dev libabsl-dev libceres-dev librosbag-storage-dev libbz2-dev libzstd-dev liblz4-dev libsqlite3-dev
  libgeographiclib-dev libgdal-dev libjs-three libcpp-httplib-dev
  libgtest-dev liboctomap-dev
  # Ceres's SuiteSparse finds BLAS and LAPACK by their development libraries
  libblas-dev liblapack-dev)

host_tools() {
  if dpkg --print-foreign-architectures | grep -qx arm64; then
    say "note: the host already has arm64 as a dpkg architecture; this script neither needs nor changes that"
  fi
  local packages=(crossbuild-essential-arm64 mmdebstrap qemu-user cmake ninja-build pkg-config file python3)
  local missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p:amd64" 2>/dev/null | grep -q "install ok installed" ||
      dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    say "installing on the host (amd64): ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

# soname -> package, version: the sysroot has no dpkg database (nothing was installed), so the
# package's shared-library dependencies are found from the .debs' file lists (deb_depends below).
# BLAS and LAPACK are in blas/ and lapack/ (the reference ones, which update-alternatives points at).
soname_map() {
  local deb
  for deb in "$sysroot"/var/cache/apt/archives/*.deb; do
    dpkg-deb -c "$deb" | awk -v pkg="$(dpkg-deb -f "$deb" Package)" -v ver="$(dpkg-deb -f "$deb" Version)" \
      '$6 ~ /\/lib\/aarch64-linux-gnu\/((blas|lapack)\/)?[^\/]*\.so\.[0-9]/ {n=split($6, p, "/"); print p[n], pkg, ver}'
  done | $sudo tee "$sysroot/.sonarmap-sonames" >/dev/null
}

make_sysroot() {
  local stamp="$sysroot/.sonarmap-packages"
  if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "${sysroot_packages[*]}" ]; then
    say "sysroot $sysroot is up to date"
    return
  fi
  say "making the arm64 Debian 12 sysroot $sysroot (mmdebstrap --variant=extract)"
  local start=$SECONDS
  $sudo rm -rf "$sysroot"
  # --skip=cleanup/apt/cache keeps the .debs: the package's Depends are found from their file lists
  $sudo mmdebstrap --variant=extract --arch=arm64 --components=main --skip=cleanup/apt/cache \
    --include="$(IFS=,; echo "${sysroot_packages[*]}")" bookworm "$sysroot" \
    "deb http://deb.debian.org/debian bookworm main" \
    "deb http://deb.debian.org/debian bookworm-updates main" \
    "deb http://deb.debian.org/debian-security bookworm-security main"
  # A library's development symlink may be absolute (/usr/lib/aarch64-linux-gnu/libz.so ->
  # /lib/aarch64-linux-gnu/libz.so.1.2.13): the linker would follow it on the host. Made relative.
  local link target dir
  while IFS= read -r -d '' link; do
    target=$(readlink "$link")
    dir=$(dirname "$link")
    $sudo ln -sfn "$(realpath -m --relative-to="$dir" "$sysroot$target")" "$link"
  done < <(find "$sysroot/usr" "$sysroot/lib" -type l -lname '/*' -print0)
  # Debian points libblas.so and liblapack.so at an implementation through update-alternatives, in
  # postinst scripts an extracted root has not run: the reference ones are linked here as they would be.
  local lib
  for lib in blas lapack; do
    for link in lib$lib.so lib$lib.so.3; do
      [ -e "$sysroot/usr/lib/aarch64-linux-gnu/$lib/$link" ] &&
        $sudo ln -sfn "$lib/$link" "$sysroot/usr/lib/aarch64-linux-gnu/$link"
    done
  done
  # Some CMake packages name their dependencies by absolute paths (CeresTargets.cmake:
  # /usr/lib/aarch64-linux-gnu/liblapack.so): prefixed with the sysroot, as CMake's own find_* would.
  grep -rlE '^ *(INTERFACE_LINK_LIBRARIES|INTERFACE_INCLUDE_DIRECTORIES|IMPORTED_LOCATION[A-Z_]*) .*/usr/' \
    --include='*.cmake' "$sysroot/usr/lib" "$sysroot/usr/share" 2>/dev/null |
    xargs -r $sudo sed -i -E '/^ *(INTERFACE_LINK_LIBRARIES|INTERFACE_INCLUDE_DIRECTORIES|IMPORTED_LOCATION[A-Z_]*) /s#([";])/usr/#\1${CMAKE_SYSROOT}/usr/#g'
  soname_map
  echo "${sysroot_packages[*]}" | $sudo tee "$stamp" >/dev/null
  say "sysroot made in $((SECONDS - start)) s: $(du -sh "$sysroot" | cut -f1)"
}

# The toolchain file: Debian's aarch64-linux-gnu-gcc/g++ against the sysroot, CMake's find_* and
# pkg-config looking there only, and qemu-aarch64 running what the build runs (gtest_discover_tests,
# ctest).
write_toolchain() {
  mkdir -p "$build"
  cat >"$build/aarch64-toolchain.cmake" <<EOF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_SYSROOT "$sysroot")
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_FIND_ROOT_PATH "$sysroot")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L "$sysroot")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "$sysroot")
set(ENV{PKG_CONFIG_LIBDIR} "$sysroot/usr/lib/aarch64-linux-gnu/pkgconfig:$sysroot/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "")
EOF
  # cpack reads this after CPackConfig.cmake (CPACK_PROJECT_CONFIG_FILE): the package's architecture
  # is the target's, not `dpkg --print-architecture`'s; dpkg-shlibdeps needs a dpkg database the
  # sysroot does not have, so the shared libraries' packages are added by deb_depends instead.
  cat >"$build/arm64-cpack.cmake" <<EOF
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS OFF)
if(EXISTS "$build/arm64-shlibs-depends.txt")
  file(READ "$build/arm64-shlibs-depends.txt" _sonarmap_shlibs)
  string(STRIP "\${_sonarmap_shlibs}" _sonarmap_shlibs)
  if(_sonarmap_shlibs)
    string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", \${_sonarmap_shlibs}")
  endif()
endif()
EOF
}

configure_arm64() {
  write_toolchain
  # CMAKE_SKIP_INSTALL_ALL_DEPENDENCY: cpack installs what is built without building `all` first
  # (the package holds no test; BUILD_TARGET may have left tests unbuilt)
  local args=(-DCMAKE_TOOLCHAIN_FILE="$build/aarch64-toolchain.cmake" -DCMAKE_BUILD_TYPE=Release
    -DSONARMAP_BUILD_TESTS=ON -DSONARMAP_BUILD_BENCHMARKS=OFF -DSONARMAP_BUILD_PYTHON=OFF
    -DSONARMAP_BUILD_ROS=OFF -DCPACK_PROJECT_CONFIG_FILE="$build/arm64-cpack.cmake"
    -DCMAKE_SKIP_INSTALL_ALL_DEPENDENCY=ON)
  # shellcheck disable=SC2206
  args+=(${SONARMAP_ARM64_CMAKE_ARGS:-})
  say "configuring $build"
  cmake -S "$src" -B "$build" -G Ninja "${args[@]}" >"$build/arm64-configure.log"
}

build_arm64() {
  configure_arm64
  local start=$SECONDS target=${BUILD_TARGET:-all}
  say "building $target with -j$jobs under nice -n 10 (log: $build/arm64-build.log)"
  # shellcheck disable=SC2086
  nice -n 10 cmake --build "$build" -j "$jobs" --target $target >>"$build/arm64-build.log" 2>&1 ||
    { tail -40 "$build/arm64-build.log" >&2; exit 1; }
  echo "arm64 build ($target, -j$jobs): $((SECONDS - start)) s" | tee -a "$build/arm64-figures.log" >&2
}

qemu() { qemu-aarch64 -L "$sysroot" "$@"; }

test_arm64() {
  local tool="$build/apps/cli/sonarmap" full="$build/apps/cli/sonarmap-full" out="$build/arm64-smoke"
  file "$full" | grep -q "ARM aarch64" || { say "$full is not an aarch64 executable"; exit 1; }
  rm -rf "$out" && mkdir -p "$out"
  # The lean `sonarmap` hands every command but `cloud` to sonarmap-full by execv, which qemu-user
  # without binfmt_misc cannot follow into another aarch64 executable: the full tool is run directly.
  say "qemu: $(qemu "$full" --version)"
  local start=$SECONDS
  qemu "$full" simulate tank -o "$out/sim" --turns 1 -q
  qemu "$full" map "$out/sim/beams.csv" -o "$out/tank-arm64.bt" -q
  echo "arm64 under qemu: simulate tank --turns 1 and map: $((SECONDS - start)) s" | tee -a "$build/arm64-figures.log" >&2
  say "qemu: the lean sonarmap: $(qemu "$tool" --version)"
  if [ -x "$amd64_tool" ]; then
    "$amd64_tool" simulate tank -o "$out/sim-amd64" --turns 1 -q
    "$amd64_tool" map "$out/sim-amd64/beams.csv" -o "$out/tank-amd64.bt" -q
    "$amd64_tool" map "$out/sim/beams.csv" -o "$out/tank-amd64-from-arm64-beams.bt" -q
    local verdict
    cmp -s "$out/sim/beams.csv" "$out/sim-amd64/beams.csv" && verdict="same beams.csv" || verdict="beams.csv differ"
    if cmp -s "$out/tank-arm64.bt" "$out/tank-amd64.bt"; then verdict+=", same map byte for byte"
    else verdict+=", maps differ"; fi
    cmp -s "$out/tank-arm64.bt" "$out/tank-amd64-from-arm64-beams.bt" &&
      verdict+=", arm64's beams mapped on amd64: the same map" || verdict+=", arm64's beams mapped on amd64: another map"
    echo "arm64 vs amd64 (tank, 1 turn): $verdict" | tee -a "$build/arm64-figures.log" >&2
    "$amd64_tool" info "$out/tank-arm64.bt" >"$out/info-arm64.txt" 2>&1 || true
    "$amd64_tool" info "$out/tank-amd64.bt" >"$out/info-amd64.txt" 2>&1 || true
  else
    say "no amd64 tool at $amd64_tool: the maps are not compared"
  fi
  say "ctest under qemu-aarch64 (log: $build/arm64-ctest.log)"
  start=$SECONDS
  # Not run under qemu: the tests that are not GoogleTest executables (the packaging tests install
  # and build with the host's compiler; the page's test drives the host's Chromium at the tool; the
  # Python client runs the host's python3 on a pty) and those of executables not built (BUILD_TARGET).
  local exclude='_NOT_BUILT$|^packaging[.]|^live[.]pageInHeadlessChromium$|^devices[.]pingPythonClient$'
  # shellcheck disable=SC2086
  (cd "$build" && nice -n 10 ctest -j "$jobs" --timeout 600 -E "$exclude" ${CTEST_ARGS:-} >"$build/arm64-ctest.log" 2>&1) || true
  grep -E "tests passed|tests failed" "$build/arm64-ctest.log" | tee -a "$build/arm64-figures.log" >&2 || true
  echo "ctest under qemu: $((SECONDS - start)) s" | tee -a "$build/arm64-figures.log" >&2
}

# The Depends the amd64 package gets from dpkg-shlibdeps, found here from the sysroot's .debs: each
# shared library an installed ELF file needs, as "package (>= version)", less libc's, which the
# -dev dependencies bring anyway.
deb_depends() {
  local stage_dir="$build/arm64-install" dep
  rm -rf "$stage_dir"
  DESTDIR="$stage_dir" cmake --install "$build" --prefix /usr >/dev/null
  find "$stage_dir" -type f -exec file {} + | awk -F: '/ELF 64-bit.*aarch64/ {print $1}' |
    xargs -r aarch64-linux-gnu-readelf -d | awk '/NEEDED/ {gsub(/[\[\]]/, "", $5); print $5}' | sort -u |
    while read -r soname; do
      [ -e "$stage_dir/usr/lib/$soname" ] || [ -n "$(find "$stage_dir" -name "$soname" -print -quit)" ] && continue
      dep=$(awk -v s="$soname" '$1 == s {print $2 " (>= " $3 ")"; exit}' "$sysroot/.sonarmap-sonames")
      if [ -n "$dep" ]; then echo "$dep"; else say "warning: no package of the sysroot ships $soname"; fi
    done | sed -E 's/\+b[0-9]+\)$/)/' | sort -u | paste -sd, | sed 's/,/, /g' >"$build/arm64-shlibs-depends.txt"
  say "shared-library Depends: $(cat "$build/arm64-shlibs-depends.txt")"
}

make_deb() {
  configure_arm64
  deb_depends
  (cd "$build" && cpack -G DEB >/dev/null)
  local deb
  deb=$(ls -t "$build"/sonarmap_*_arm64.deb | head -1)
  dpkg-deb -f "$deb" Package Version Architecture Depends >"$build/arm64-deb-control.txt"
  echo "arm64 package: $deb $(stat -c %s "$deb") bytes; sonarmap-full $(stat -c %s "$build/apps/cli/sonarmap-full") bytes, sonarmap $(stat -c %s "$build/apps/cli/sonarmap") bytes (not stripped)" |
    tee -a "$build/arm64-figures.log" >&2
  mkdir -p "$src/packaging/blueos/dist"
  cp "$deb" "$src/packaging/blueos/dist/"
  say "copied to packaging/blueos/dist/ for the BlueOS image (docker build packaging/blueos)"
}

# The extension image's content without Docker (no daemon, no Docker Hub here): an arm64 Debian 12
# root with what packaging/blueos/Dockerfile installs (the package's Depends less the -dev ones,
# unpacked), the package unpacked over it, and packaging/blueos/check.sh run on the arm64 tool
# under qemu-aarch64 with that root as its only library folder.
image_root() {
  local deb image=${IMAGE_ROOT:-/var/tmp/sonarmap-arm64-image} runtime
  deb=$(ls -t "$build"/sonarmap_*_arm64.deb | head -1)
  runtime=$(dpkg-deb -f "$deb" Depends | tr ',' '\n' | sed -E 's/\(.*\)//; s/^ +| +$//g' |
    grep -vE -- '-dev$|^pkg-config$|^python3|^$' | paste -sd,)
  say "the image's root $image: $runtime"
  $sudo rm -rf "$image"
  $sudo mmdebstrap --variant=extract --arch=arm64 --components=main --include="libc6,libstdc++6,$runtime" \
    bookworm "$image" "deb http://deb.debian.org/debian bookworm main" \
    "deb http://deb.debian.org/debian-security bookworm-security main" 2>"$build/arm64-image.log"
  local lib dir   # update-alternatives, as the postinst scripts of liblapack3 and libatlas3-base would
  for lib in blas lapack; do
    for dir in $lib atlas; do
      if [ -e "$image/usr/lib/aarch64-linux-gnu/$dir/lib$lib.so.3" ]; then
        $sudo ln -sfn "$dir/lib$lib.so.3" "$image/usr/lib/aarch64-linux-gnu/lib$lib.so.3"
        break
      fi
    done
  done
  $sudo dpkg-deb -x "$deb" "$image"
  echo "image root (runtime libraries + package): $(du -sh "$image" | cut -f1)" | tee -a "$build/arm64-figures.log" >&2
  qemu-aarch64 -L "$image" "$image/usr/libexec/sonarmap/sonarmap-full" --version >&2
  SONARMAP_QEMU="qemu-aarch64 -L $image" bash packaging/blueos/check.sh "$image/usr/libexec/sonarmap/sonarmap-full" |
    tee "$build/arm64-image-check.log" >&2
}

# Each GoogleTest executable run directly under qemu, two at a time (GTEST_TARGETS: which ones,
# default every one built), one line each: its passed and failed counts, its time. ctest's
# alternative when a build holds many executables: no per-test start-up, a time limit per
# executable (GTEST_TIMEOUT, 600 s). Logs in $BUILD_DIR/arm64-gtest/.
gtest_arm64() {
  local targets=${GTEST_TARGETS:-}
  mkdir -p "$build/arm64-gtest"
  if [ -z "$targets" ]; then
    targets=$(find "$build/tests" -type f -perm -u+x \( -name 'test_*' -o -name sonarmap_live_tests \) \
      -not -path '*/CMakeFiles/*' -printf '%f\n' | sort)
  fi
  export build sysroot
  export GTEST_TIMEOUT=${GTEST_TIMEOUT:-600}
  # shellcheck disable=SC2016
  tr ' ' '\n' <<<"$targets" | grep . | xargs -P "$jobs" -I{} bash -c '
    t={}; p=$(find "$build/tests" -type f -name "$t" -perm -u+x | head -1); out="$build/arm64-gtest/$t.log"; s=$SECONDS
    timeout "$GTEST_TIMEOUT" nice -n 10 qemu-aarch64 -L "$sysroot" "$p" --gtest_brief=1 >"$out" 2>&1; rc=$?
    pass=$(sed -nE "s/^\[  PASSED  \] ([0-9]+) tests?.*/\1/p" "$out" | tail -1)
    fail=$(grep -cE "^\[  FAILED  \] [A-Za-z]" "$out")   # --gtest_brief: each failure once
    echo "$t rc=$rc passed=${pass:-0} failed=${fail:-0} $((SECONDS - s))s"' | tee "$build/arm64-gtest.log" >&2
  awk '{split($3, p, "="); split($4, f, "="); P += p[2]; F += f[2]; if ($2 != "rc=0") bad++}
       END {print "gtest under qemu: " NR " executables, " P " tests passed, " F " failed, " bad+0 " executables not rc 0"}' \
    "$build/arm64-gtest.log" | tee -a "$build/arm64-figures.log" >&2
}

case $stage in
  sysroot) host_tools; make_sysroot ;;
  build) build_arm64 ;;
  test) test_arm64 ;;
  deb) make_deb ;;
  image) image_root ;;
  gtest) gtest_arm64 ;;
  all) host_tools; make_sysroot; build_arm64; test_arm64; make_deb; image_root ;;
  *) echo "usage: bash scripts/build-arm64.sh [all|sysroot|build|test|deb|image|gtest]" >&2; exit 2 ;;
esac
