#!/usr/bin/env bash
# Instructions per beam of each stage of `sonarmap live` (docs/performance.md, "Cost per beam"): a
# Ping360 at 50 m and a Tritech Micron (SeaNet) at 10 m, emulated (harbour scene, harbour-loop, MAVLink
# navigation at 10 Hz) and recorded by `live --record`; each recording replayed by `live` under callgrind
# (no hardware counters here) with --serve (the map tiles are drawn with or without a page open), each
# beam shown at once. Stages, inclusive costs (callgrind_annotate --inclusive=yes --tree=caller):
#   read = LiveSession::replayStep - feedBeam (the recording decoded); fan = feedBeam - LiveMapping::addBeam;
#   detect = SonarMapper::detectRows + detectSweep; integrate = OnlineMapper::addBeam + addNavFix +
#   commitHeld + finish - detect; pictures = live::MapTiles::draw (tiles: calls of rasterizeTile);
#   write = live::writeLiveMapFiles + LiveMapping::shownSnapshot; status = LiveSession::report.
# Pictures (at most every 0.5 s, and 2x the last one's time) and writes (every 10 s) follow the wall
# clock, and the replay under callgrind runs at its own pace (--rate 0), not the head's: their per-beam
# figures are per tile and per write times their rate at the head's pace: the tiles a second from a
# replay at --rate 1 without callgrind (/state polled every 0.2 s), a write every 10 s, a status a second.
# Usage: bench/live/beam_cost.sh [OUT=/tmp/sonarmap-beam-cost] [PING360_SECONDS=85] [MICRON_SECONDS=60] [SONARMAP]
# Recordings already in OUT are reused (delete OUT to record new ones).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-/tmp/sonarmap-beam-cost} ping360_s=${2:-85} micron_s=${3:-60} sonarmap=${4:-build/apps/cli/sonarmap-full}
mkdir -p "$out"

record() {  # NAME SONAR FORMAT RANGE SECONDS: emulate the head and record `live` driving it
  local name=$1 port=$((20000 + RANDOM % 20000))
  [[ -s $out/$name.mcap ]] && return 0
  "$sonarmap" emulate --sonar "$2" --scene harbour --mission harbour-loop --udp "udp://:$port" \
    --mavlink "udp://127.0.0.1:$((port + 1))" >"$out/$name-emulate.out" 2>"$out/$name-emulate.err" &
  local emulator=$!
  sleep 0.5
  "$sonarmap" live "udp://127.0.0.1:$port" --format "$3" --range "$4" --nav-stream "udp://:$((port + 1))" \
    --record "$out/$name.mcap" -o "$out/$name-record.bt" >"$out/$name-record.out" 2>"$out/$name-record.err" &
  local live=$!
  sleep "$5"
  kill -INT "$live"; wait "$live" || true
  kill -TERM "$emulator"; wait "$emulator" || true
}

measure() {  # NAME: callgrind of the replay, then the tiles a second at the head's pace
  local name=$1 port=$((20000 + RANDOM % 20000))
  valgrind --tool=callgrind --callgrind-out-file="$out/$name.cg" "$sonarmap" live "$out/$name.mcap" --show beam \
    --serve 127.0.0.1:0 -o "$out/$name-cg.bt" >"$out/$name-cg.out" 2>"$out/$name-cg.err"
  callgrind_annotate --inclusive=yes --tree=caller --threshold=100 "$out/$name.cg" >"$out/$name.annotate"
  "$sonarmap" live "$out/$name.mcap" --rate 1 --show beam --serve "127.0.0.1:$port" -q -o "$out/$name-paced.bt" \
    >"$out/$name-paced.out" 2>"$out/$name-paced.err" &
  local live=$!
  : >"$out/$name-paced.pictures"
  while kill -0 "$live" 2>/dev/null; do  # the latest picture's version and tiles drawn
    curl -s "http://127.0.0.1:$port/state" | grep -o '"raster":{"v":[0-9]*,[^}]*' |
      sed 's/.*"v":\([0-9]*\),.*"drawn":\([0-9]*\),.*/\1 \2/' >>"$out/$name-paced.pictures" || true
    sleep 0.2
  done
  wait "$live" || true
  "$sonarmap" info "$out/$name.mcap" >"$out/$name.info"
}

record ping360 ping360 ping360 50 "$ping360_s"
record micron micron seanet 10 "$micron_s"
measure ping360
measure micron

python3 - "$out" ping360 micron <<'EOF'
import re, sys
out = sys.argv[1]
for name in sys.argv[2:]:
    incl, calls, pending = {}, {}, 0
    for line in open(f"{out}/{name}.annotate"):
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+([<*>])\s+[^:]*:(.*?)(?: \(([\d,]+)x\))? \[", line)
        if m and m.group(2) == "<": pending += int((m.group(4) or "0").replace(",", ""))
        elif m and m.group(2) == "*":
            fn = m.group(3)
            incl[fn] = incl.get(fn, 0) + int(m.group(1).replace(",", "")); calls[fn] = calls.get(fn, 0) + pending
        if not line.strip(): pending = 0
    total = int(re.search(r"([\d,]+) \([ \d.]+%\)\s+PROGRAM TOTALS", open(f"{out}/{name}.annotate").read()).group(1).replace(",", ""))
    def f(prefix, what=incl):  # inclusive cost (or calls) of the functions whose names start so
        return sum(v for k, v in what.items() if k.startswith("sonarmap::" + prefix))
    beams = int(re.search(r"(\d+) beams used", open(f"{out}/{name}-cg.out").read()).group(1))
    info = open(f"{out}/{name}.info").read()
    rate, span = float(re.search(r"([\d.]+) beams/s", info).group(1)), float(re.search(r"over ([\d.]+) s", info).group(1))
    seen = dict(tuple(map(int, line.split())) for line in open(f"{out}/{name}-paced.pictures"))  # version: tiles
    made = max(seen, default=0); tiles_s = sum(seen.values()) / max(len(seen), 1) * made / span
    detect = f("SonarMapper::detectRows(") + f("SonarMapper::detectSweep(")
    mapper = sum(f(f"OnlineMapper::{x}(") for x in ("addBeam", "addNavFix", "commitHeld", "finish"))
    draw, tiles, pictures = f("live::MapTiles::draw("), f("rasterizeTile(", calls), f("live::MapTiles::draw(", calls)
    write, writes = f("live::writeLiveMapFiles(") + f("LiveMapping::shownSnapshot("), f("live::writeLiveMapFiles(", calls)
    report, reports = f("LiveSession::report("), f("LiveSession::report(", calls)
    # (label, instructions in the callgrind run, per beam at the head's pace)
    rows = [("read: `replayStep` − `feedBeam`", f("LiveSession::replayStep(") - f("LiveSession::feedBeam("), None),
            ("fan: `feedBeam` − `LiveMapping::addBeam`", f("LiveSession::feedBeam(") - f("LiveMapping::addBeam("), None),
            ("detect: `SonarMapper::detectRows` + `detectSweep`", detect, None),
            ("integrate: `OnlineMapper::addBeam`, `addNavFix`, `finish` − detect", mapper - detect, None)]
    rows = [(label, v, v / beams) for label, v, _ in rows]
    rows += [(f"pictures: `MapTiles::draw`, {tiles} tiles in {pictures} (paced: {tiles_s:.0f} tiles/s)",
              draw, draw / max(tiles, 1) * tiles_s / rate),
             (f"write: `writeLiveMapFiles` + `shownSnapshot`, {writes} writes (paced: one / 10 s)",
              write, write / max(writes, 1) / 10 / rate),
             (f"status: `LiveSession::report`, {reports} calls (paced: one / s)", report, report / max(reports, 1) / rate)]
    rest = total - sum(v for _, v, _ in rows)
    print(f"\n{name}: {beams} beams, {total / 1e9:.2f} G instructions under callgrind; {rate} beams/s over {span} s; "
          f"paced replay: {len(seen)} of {made} pictures seen, {sum(seen.values())} tiles")
    print("| stage | instructions | per beam |\n|---|---:|---:|")
    for label, v, b in rows: print(f"| {label} | {v / 1e9:.3f} G | {b / 1e6:.2f} M |")
    print(f"| the rest (start-up, navigation read up front) | {rest / 1e9:.3f} G | |")
    per_s = rate * sum(b for _, _, b in rows)
    print(f"| **all, per beam at the head's pace** | | **{per_s / rate / 1e6:.2f} M** |")
    print(f"at {rate} beams/s: {per_s / 1e6:.0f} M instructions/s = {per_s / 1.5e9 * 100:.1f} to {per_s / 0.75e9 * 100:.1f} % "
          f"of one Cortex-A72 core at 1.5 GHz retiring 1 to 0.5 instruction a cycle (an assumption)")
EOF
