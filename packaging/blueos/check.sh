#!/usr/bin/env bash
# Checks the BlueOS extension without Docker: (1) every JSON label of the Dockerfile parses (with its
# ARG defaults substituted, as `docker build` does) and the labels have the fields BlueOS reads;
# (2) the extension's entrypoint runs `sonarmap live` against `sonarmap emulate`'s Ping360 and its
# navigation for a few seconds; GET /register_service and GET / answer, and the name, company and
# version BlueOS shows agree with the labels; SIGTERM (docker stop) ends it with the map and the
# recording written.
# Usage: bash packaging/blueos/check.sh [SONARMAP]   (default build/apps/cli/sonarmap; with
#        SONARMAP_QEMU="qemu-aarch64 -L SYSROOT" the tool is an arm64 one run under qemu-user)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
tool=${1:-$root/build/apps/cli/sonarmap}
work=$(mktemp -d /tmp/sonarmap-blueos-check.XXXXXX)
pids=()
cleanup() {
  local pid
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT

python3 - "$here/Dockerfile" >"$work/labels.json" <<'EOF'
import json, re, shlex, sys
text = open(sys.argv[1]).read().replace("\\\n", "")   # continuation lines joined, as Docker does
args, labels = {}, {}
for line in text.splitlines():
    line = line.strip()
    if line.startswith("ARG ") and "=" in line:
        name, value = line[4:].split("=", 1)
        args[name.strip()] = value.strip()
    elif line.startswith("LABEL "):
        key, value = line[6:].split("=", 1)
        quoted = value.strip().startswith('"')
        value = shlex.split(value)[0]
        if quoted:   # Docker substitutes ${ARG} outside single quotes only
            value = re.sub(r"\$\{(\w+)\}", lambda m: args[m.group(1)], value)
        labels[key.strip()] = value
for key in ("permissions", "authors", "company", "tags", "links"):
    labels[key] = json.loads(labels[key])   # raises on invalid JSON
missing = {"version", "permissions", "authors", "company", "type", "tags", "readme", "links", "requirements"} - labels.keys()
assert not missing, f"labels missing: {missing}"
assert labels["type"] in ("device-integration", "example", "theme", "other", "tool"), labels["type"]
assert all(re.fullmatch(r"[a-z0-9-]+", t) for t in labels["tags"]) and len(labels["tags"]) <= 10
assert re.fullmatch(r"\d+\.\d+\.\d+", labels["version"]), labels["version"]
host = labels["permissions"]["HostConfig"]
assert host["NetworkMode"] == "host"
print(json.dumps(labels))
EOF
echo "check.sh: the Dockerfile's labels are valid JSON and complete:"
python3 -c 'import json,sys; l=json.load(open(sys.argv[1])); print("  version", l["version"], "| type", l["type"], "| tags", ",".join(l["tags"]), "| network", l["permissions"]["HostConfig"]["NetworkMode"])' "$work/labels.json"

# The emulated vehicle: a Ping360 on a free UDP port, its navigation as MAVLink to a free port
nav_port=$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
page_port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
: >"$work/emulate.err"
"$root/build/apps/cli/sonarmap" emulate --sonar ping360 --scene tank --udp udp://:0 \
  --mavlink "udp://127.0.0.1:$nav_port" 2>"$work/emulate.err" &
pids+=($!)
for _ in $(seq 50); do grep -q "on udp://:" "$work/emulate.err" && break; sleep 0.1; done
head_port=$(sed -nE 's/.* on udp:\/\/:([0-9]+).*/\1/p' "$work/emulate.err" | head -1)
[ -n "$head_port" ] || { cat "$work/emulate.err" >&2; exit 1; }

# The entrypoint, as the container runs it, with the tool given
if [ -n "${SONARMAP_QEMU:-}" ]; then
  printf '#!/bin/sh\nexec %s %q "$@"\n' "$SONARMAP_QEMU" "$tool" >"$work/sonarmap" && chmod +x "$work/sonarmap"
  tool="$work/sonarmap"
fi
SONARMAP_BIN="$tool" SONARMAP_SOURCE="udp://127.0.0.1:$head_port" SONARMAP_NAV="udp://:$nav_port" \
  SONARMAP_PORT="$page_port" SONARMAP_DATA="$work/data" SONARMAP_RANGE=20 \
  "$here/entrypoint.sh" 2>"$work/live.err" &
live=$!
pids+=($live)
for _ in $(seq 100); do curl -sf "http://127.0.0.1:$page_port/register_service" >"$work/register.json" && break; sleep 0.2; done
sleep "${CHECK_SECONDS:-5}"
curl -sf "http://127.0.0.1:$page_port/register_service" >"$work/register.json"
page_bytes=$(curl -sf "http://127.0.0.1:$page_port/" | wc -c)
echo "check.sh: GET /register_service: $(cat "$work/register.json")"
echo "check.sh: GET /: $page_bytes bytes of HTML"
python3 - "$work/labels.json" "$work/register.json" <<'EOF'
import json, sys
labels, service = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert service["version"] == labels["version"], (service["version"], labels["version"])
assert service["company"] == labels["company"]["name"], (service["company"], labels["company"])
assert service["name"] and service["works_in_relative_paths"] is True
print("check.sh: /register_service agrees with the labels (version %s, company %s, name %r)"
      % (service["version"], service["company"], service["name"]))
EOF
kill -TERM "$live"
wait "$live" || { echo "check.sh: live ended with $?" >&2; cat "$work/live.err" >&2; exit 1; }
grep -E "recorded|page is at" "$work/live.err" | sed 's/^/check.sh: /'
ls "$work"/data/dive-*.bt "$work"/data/dive-*.mcap >/dev/null
echo "check.sh: after SIGTERM: $(stat -c %s "$work"/data/dive-*.bt) bytes of map, $(stat -c %s "$work"/data/dive-*.mcap) bytes of recording"
