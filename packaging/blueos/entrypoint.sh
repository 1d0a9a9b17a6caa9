#!/bin/sh
# The BlueOS extension's command: `sonarmap live` on the vehicle's Ping360 (as BlueOS serves it, UDP
# port 9092), ArduSub's navigation from a BlueOS MAVLink endpoint (UDP 14551), the page on
# SONARMAP_PORT (BlueOS finds it there by asking GET /register_service), the dive recorded and
# mapped into SONARMAP_DATA (a host folder bound by the image's permissions label).
# Each setting is an environment variable, set in BlueOS's extension settings (Env):
#   SONARMAP_SOURCE  the head's link: udp://HOST:PORT, a serial device, tcp://HOST:PORT (udp://192.168.2.2:9092)
#   SONARMAP_FORMAT  ping360 | seanet (ping360)
#   SONARMAP_RANGE   METRES, the range scale the head is set to (30)
#   SONARMAP_NAV     the navigation link, empty for none: the map is then in the head's frame (udp://:14551)
#   SONARMAP_PORT    the page's TCP port (8765)
#   SONARMAP_DATA    where dives are written (/data)
#   SONARMAP_ARGS    more `sonarmap live` options, e.g. "--gain high --3d"
#   SONARMAP_BIN     the tool (sonarmap, from the package)
set -eu
source=${SONARMAP_SOURCE:-udp://192.168.2.2:9092}
format=${SONARMAP_FORMAT:-ping360}
range=${SONARMAP_RANGE:-30}
nav=${SONARMAP_NAV-udp://:14551}
port=${SONARMAP_PORT:-8765}
data=${SONARMAP_DATA:-/data}
bin=${SONARMAP_BIN:-sonarmap}
mkdir -p "$data"
dive="$data/dive-$(date -u +%Y%m%dT%H%M%SZ)"
set -- "$source" --format "$format" --range "$range" --record "$dive.mcap" --serve "0.0.0.0:$port" -o "$dive.bt" -q
[ -z "$nav" ] || set -- "$@" --nav-stream "$nav"
# shellcheck disable=SC2086
set -- "$@" ${SONARMAP_ARGS:-}
echo "sonarmap extension: $bin live $*" >&2
exec "$bin" live "$@"
