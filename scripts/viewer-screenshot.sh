#!/usr/bin/env bash
# Regenerates the README's picture of the 3D viewer, docs/images/viewer.png: `sonarmap demo` into a
# temporary folder, then headless Chromium (software WebGL, no GPU needed) takes a 1280 x 800
# screenshot of the 3D mission's page, 3d-mission/map.html. Needs a built tool (scripts/build.sh;
# or name one in SONARMAP_BIN) and Debian's chromium (or one named in CHROMIUM).
set -euo pipefail
cd "$(dirname "$0")/.."
sonarmap=${SONARMAP_BIN:-build/apps/cli/sonarmap}
chromium=${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}
if [ ! -x "$sonarmap" ]; then
  echo "no sonarmap at $sonarmap: build it (bash scripts/build.sh) or set SONARMAP_BIN" >&2
  exit 1
fi
if [ -z "$chromium" ]; then
  echo "no Chromium: install Debian's chromium (apt-get install chromium) or set CHROMIUM" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sonarmap" demo -o "$work/demo" -q > /dev/null
page="$work/demo/3d-mission/map.html"
mkdir -p docs/images
"$chromium" --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
  --ignore-gpu-blocklist --no-first-run --hide-scrollbars --user-data-dir="$work/profile" \
  --window-size=1280,800 --virtual-time-budget=20000 --screenshot="$work/viewer.png" "file://$page" 2> "$work/chromium.log" \
  || { cat "$work/chromium.log" >&2; exit 1; }
# Chromium's --dump-dom of the same page reports what it drew (io/html_view.hpp's self-check).
check=$("$chromium" --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
  --ignore-gpu-blocklist --no-first-run --user-data-dir="$work/profile" --window-size=1280,800 \
  --virtual-time-budget=20000 --dump-dom "file://$page#selfcheck" 2> /dev/null | sed -n 's:.*<pre id="check">\([^<]*\)</pre>.*:\1:p')
case "$check" in
  *" ok") ;;
  *) echo "the page did not draw its boxes in Chromium: '${check}'" >&2; exit 1 ;;
esac
cp "$work/viewer.png" docs/images/.viewer.png.tmp  # then a rename: never half a picture
mv docs/images/.viewer.png.tmp docs/images/viewer.png
echo "wrote docs/images/viewer.png ($check)"
