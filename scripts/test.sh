#!/usr/bin/env bash
# Installs what is missing, builds everything (library, CLI, tests, benchmarks) and runs all tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh test
bash scripts/build.sh -DSONARMAP_BUILD_TESTS=ON -DSONARMAP_BUILD_BENCHMARKS=ON
ctest --test-dir build --output-on-failure -j "$(nproc)"
