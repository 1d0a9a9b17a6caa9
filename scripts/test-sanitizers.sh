#!/usr/bin/env bash
# Builds the library, the CLI and the whole test suite with AddressSanitizer and
# UndefinedBehaviorSanitizer (gcc) into build-asan/ and runs every test under them (the Python module
# is left out: an instrumented extension needs the sanitizer runtime preloaded into python3). Any sanitizer
# report fails the test that triggered it (UBSan does not recover; LeakSanitizer is on).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh test
source scripts/compiler-cache.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -O1 -g1 (line tables), as the sanitizers' documentation advises: reports keep function names and
# lines, and the build takes a third of the time RelWithDebInfo's -O2 -g takes (variable tracking
# through Eigen and GoogleTest under instrumentation: 112 s against 40 s for scan_matcher.cpp).
# The ROS 1 node is left out: its test needs the Python module (off here), and Debian's roscpp is not
# instrumented.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DSONARMAP_BUILD_TESTS=ON \
  -DSONARMAP_BUILD_BENCHMARKS=OFF -DSONARMAP_BUILD_PYTHON=OFF -DSONARMAP_BUILD_ROS=OFF "${compiler_cache[@]}" >/dev/null
cmake --build build-asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/lsan-suppressions.txt  # leaks inside Debian libraries
# Left out here, run by scripts/test.sh: the 2 cm twins of the OctoMap parity tests (their 5 cm
# twins run the same code, in a third of the time under the sanitizers) and the pages opened in
# Chromium (the browser is not instrumented, and the live page's test times its latency; the page
# writers and the live server run here in the other cliView, live and CliLiveHeads tests).
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1500 -E '_2cm|/2cm|InChromium|InHeadlessChromium'
