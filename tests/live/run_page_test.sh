#!/usr/bin/env bash
# Runs page_test.js, the live page in headless Chromium, for ctest:
#   run_page_test.sh FAKE_SESSION CHROMIUM WORK_DIR
# Exits 77 (ctest: skipped) saying why when node, the test's node_modules (`npm ci` in tests/live,
# which scripts/install-deps.sh test runs) or Chromium is missing. SONARMAP_CHROMIUM overrides
# CHROMIUM.
set -u
session=$1
chromium=${SONARMAP_CHROMIUM:-$2}
work=$3
here=$(cd "$(dirname "$0")" && pwd)
if ! command -v node >/dev/null; then
  echo "skipped: node not found: install nodejs (scripts/install-deps.sh test)"
  exit 77
fi
if [ ! -f "$here/node_modules/playwright-core/package.json" ]; then
  echo "skipped: $here/node_modules/playwright-core is missing: run 'npm ci' in tests/live (scripts/install-deps.sh test does)"
  exit 77
fi
if [ -z "$chromium" ] || [ ! -x "$chromium" ]; then
  echo "skipped: Chromium not found ('$chromium'): install Debian's chromium and configure again"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
exec node "$here/page_test.js" --session "$session" --chromium "$chromium" --work "$work"
