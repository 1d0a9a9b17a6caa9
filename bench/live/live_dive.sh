#!/usr/bin/env bash
# A dive flown without a vehicle, end to end, for docs/performance.md ("Live on a vehicle"): an
# emulated Ping360 at 50 m turning full circles over the harbour loop (`sonarmap emulate`, UDP) and
# the vehicle's navigation as MAVLink at 10 Hz; `sonarmap live` driving it on ONE core (taskset -c 1)
# with the page served, watched by headless Chromium (watch_page.js), and the dive recorded. Prints:
#  - whether live kept up: pings the head sent against beams live received, and live's CPU time;
#  - beam arrival → pixels on the page, fan and map (median, p95, max), from the page's acks;
#  - live's resident memory every 10 s of the wall clock (RSS, MB) and its growth;
#  - whether `map` of the recording gives the live map (cmp).
# Usage: bench/live/live_dive.sh [WALL_SECONDS=120] [RESOLUTION=auto] [TIME_SCALE=1] [OUT=/tmp/sonarmap-live-dive] [PAGE=page]
# PAGE: `page` serves the page and watches it; `none` runs live without --serve (the same dive: its
# CPU is what the page costs on top).
# A 2-hour dive in 15 minutes: bench/live/live_dive.sh 900 auto 8 (the head pings 8 times as fast,
# the vehicle flies 8 times as fast; the page is watched for the first 2 minutes only).
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-120}
resolution=${2:-auto}
scale=${3:-1}
out=${4:-/tmp/sonarmap-live-dive}
page=${5:-page}
sonarmap=build/apps/cli/sonarmap
rm -rf "$out" && mkdir -p "$out"
port=$((20000 + RANDOM % 20000)); nav_port=$((port + 1)); page_port=$((port + 2))
laps=$(( (seconds * ${scale%.*} + 599) / 600 + 1 ))
$sonarmap emulate --sonar ping360 --scene harbour --mission harbour-loop --laps "$laps" --udp "udp://:$port" \
  --mavlink "udp://127.0.0.1:$nav_port" --time-scale "$scale" >"$out/emulate.out" 2>"$out/emulate.err" &
emulator=$!
sleep 0.5
serve=(); [[ $page == page ]] && serve=(--serve "127.0.0.1:$page_port")
taskset -c 1 $sonarmap live "udp://127.0.0.1:$port" --format ping360 --range 50 --nav-stream "udp://:$nav_port" \
  "${serve[@]}" --resolution "$resolution" --record "$out/dive.mcap" -o "$out/live.bt" \
  >"$out/live.out" 2>"$out/live.err" &
live=$!
sleep 1
watch_s=$(( seconds > 130 ? 120 : seconds + 5 ))
watcher=
if [[ $page == page ]]; then
  node bench/live/watch_page.js "http://127.0.0.1:$page_port/" "$watch_s" >"$out/latency.json" 2>"$out/watch.err" &
  watcher=$!
else
  echo '"no page"' >"$out/latency.json"
fi
echo "wall_s,rss_mb" >"$out/rss.csv"
for ((t = 0; t < seconds; t += 10)); do
  echo "$t,$(awk '/VmRSS/ {printf "%.1f", $2 / 1024}' "/proc/$live/status")" >>"$out/rss.csv"
  sleep 10
done
# live's CPU over exactly the wall time above (the page watcher's own ending and live's shutdown are not counted)
cpu_s=$(awk '{printf "%.1f", ($14 + $15) / 100}' "/proc/$live/stat")
beams_then=$(grep -o ' [0-9]* beams (' "$out/live.err" | tail -1 | grep -o '[0-9]*')
[[ -z $watcher ]] || wait "$watcher" || echo "the page watcher failed: $out/watch.err" >&2
kill -INT "$live"; wait "$live" || true
kill -TERM "$emulator"; wait "$emulator" || true
pings=$(grep -o '[0-9]* pings sent' "$out/emulate.err" | grep -o '^[0-9]*')
beams=$(grep -o 'recorded [0-9]* beams' "$out/live.err" | grep -o '[0-9]*')
echo "dive: $seconds s wall x $scale = $((seconds * ${scale%.*})) s emulated, resolution $resolution"
echo "kept up: $beams beams received of $pings pings sent; live's CPU $cpu_s s in its first $seconds s ($beams_then beams) on one core"
echo "page latency (s): $(cat "$out/latency.json")"
awk -F, 'NR == 2 {first = $2} NR > 1 {last = $2; if ($2 > peak) peak = $2} NR == 9 {ten = $2}
  END {printf "RSS MB: first %s, at 80 s wall %s, last %s, peak %s\n", first, ten, last, peak}' "$out/rss.csv"
$sonarmap map "$out/dive.mcap" --resolution "$resolution" -q -o "$out/batch.bt" >/dev/null
if cmp -s "$out/live.bt" "$out/batch.bt"; then echo "map of the recording: the live map byte for byte"; else echo "map of the recording DIFFERS from the live map"; fi
tail -1 "$out/live.out"
