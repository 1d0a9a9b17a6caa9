#!/usr/bin/env bash
# libFuzzer harnesses of every reader (fuzz/), built with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-fuzz/.
#   bash scripts/fuzz.sh build                 configure and build the harnesses
#   bash scripts/fuzz.sh replay                run every harness once over its seed corpus
#                                              (build-fuzz/seeds/NAME, written by the build
#                                              with sonarmap_fuzz_seeds) and its crash regressions
#                                              (fuzz/regressions/NAME); fails on any finding
#   bash scripts/fuzz.sh run NAME SECONDS      fuzz one harness for SECONDS, growing a working
#                                              corpus in build-fuzz/work/NAME (seeded from
#                                              build-fuzz/seeds/NAME); findings land in
#                                              build-fuzz/work/NAME-findings/
#   bash scripts/fuzz.sh list                  the harness names
set -euo pipefail
cd "$(dirname "$0")/.."
names=(v4log seanet seanet_protocol ping360 ping_protocol wire_stream mat beam_csv nav_csv nav_stream trajectory scan_graph point_text octomap_bt octomap_ot scene map_beam_csv ros_bag mcap rosbag2 tlog dataflash point_scans gzip_text mavlink_stream)
# Files of the hand-made corpus each harness also starts from: tests/corpus/make_corpus.py builds
# it (binary files generated, text files copied) into build-fuzz/corpus.
declare -A corpus_glob=([v4log]='*.V4LOG' [seanet]='*.seanet' [seanet_protocol]='*.seanet' [ping360]='*.bin' [ping_protocol]='ping*.bin' [wire_stream]='*_small.seanet' [mat]='*.mat' [beam_csv]='beams*.csv' [nav_csv]='nav*.csv' [nav_stream]='nav*.csv'
  [trajectory]='tum_*'
  [scan_graph]='*.graph' [point_text]='*.xyz' [octomap_bt]='*.bt' [octomap_ot]='*.ot'
  [scene]='scene*' [map_beam_csv]='beams*.csv' [ros_bag]='bag*.bag' [mcap]='*.mcap' [rosbag2]='rosbag2*.db3' [tlog]='*.tlog' [dataflash]='*.BIN' [point_scans]='scans*.csv' [gzip_text]='*.csv.gz'
  [mavlink_stream]='*.tlog')
build=build-fuzz
# Shared by every run: 10 s per input is a hang; 2 GiB of memory (also the largest single
# allocation) is an out-of-memory finding.
common=(-timeout=10 -rss_limit_mb=2048 -max_len=65536)
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan-suppressions.txt  # leaks inside Debian libraries

build() {
  bash scripts/install-deps.sh
  # clang and its libFuzzer runtime (Debian 12: clang 14, libclang-rt-14-dev)
  if ! command -v clang++ >/dev/null || ! dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "ok installed"; then
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev >/dev/null
  fi
  source scripts/compiler-cache.sh
  # -O1 -g1, as libFuzzer's documentation builds its harnesses: findings keep function names and lines.
  # The ROS 1 node is left out: no harness reads through it (its decoder is the bag reader's, fuzzed).
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined" \
    -DSONARMAP_BUILD_FUZZERS=ON -DSONARMAP_BUILD_TESTS=OFF -DSONARMAP_BUILD_BENCHMARKS=OFF \
    -DSONARMAP_BUILD_CLI=OFF -DSONARMAP_BUILD_ROS=OFF "${compiler_cache[@]}" >/dev/null
  cmake --build "$build"
  rm -rf "$build"/seeds "$build"/corpus
  "$build"/fuzz/sonarmap_fuzz_seeds "$build"/seeds  # generated, not committed
  python3 tests/corpus/make_corpus.py "$build"/corpus
}

replay() {
  local name dirs files
  for name in "${names[@]}"; do
    dirs=()
    [ -d "$build"/seeds/"$name" ] && dirs+=("$build"/seeds/"$name")  # rosbag2, tlog, dataflash: the hand-made corpus only
    [ -d fuzz/regressions/"$name" ] && dirs+=(fuzz/regressions/"$name")
    mapfile -t files < <(if [ ${#dirs[@]} -gt 0 ]; then find "${dirs[@]}" -type f; fi; handmade "$name")
    echo "replay $name: ${#files[@]} inputs"
    "$build"/fuzz/fuzz_"$name" "${common[@]}" -runs=0 "${files[@]}" 2>"$build"/replay-"$name".log ||
      { tail -40 "$build"/replay-"$name".log >&2; echo "fuzz.sh: $name failed on a replayed input" >&2; exit 1; }
  done
}

# The hand-made corpus files for harness $1.
handmade() {
  [ -d "$build"/corpus ] || python3 tests/corpus/make_corpus.py "$build"/corpus >/dev/null
  find "$build"/corpus/valid "$build"/corpus/broken -name "${corpus_glob[$1]}" -type f
}

run() {
  local name=$1 seconds=$2 work=$build/work/$1
  mkdir -p "$work" "$work"-findings
  cp -n "$build"/seeds/"$name"/* "$work"/ 2>/dev/null || true
  handmade "$name" | xargs -r cp -n -t "$work"/
  "$build"/fuzz/fuzz_"$name" "${common[@]}" -max_total_time="$seconds" -print_final_stats=1 \
    -artifact_prefix="$work"-findings/ "$work"
}

case "${1:-}" in
  build) build ;;
  replay) replay ;;
  run) [ $# -eq 3 ] || { echo "usage: fuzz.sh run NAME SECONDS" >&2; exit 2; }; run "$2" "$3" ;;
  list) printf '%s\n' "${names[@]}" ;;
  *) echo "usage: fuzz.sh build | replay | run NAME SECONDS | list" >&2; exit 2 ;;
esac
