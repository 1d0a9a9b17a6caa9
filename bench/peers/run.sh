#!/usr/bin/env bash
# bench/peers/run.sh SONARMAP PEERS_DIR [INPUTS_TOOL] [-- run.py options]: the peers' table of
# docs/performance.md ("Peers"). Writes the generated workloads with INPUTS_TOOL (default: this
# worktree's build/bench/sonarmap_cloud_inputs) into PEERS_DIR/inputs, links OctoMap's spherical scan
# graph from ../shared/data, and runs bench/peers/run.py: 5 alternating rounds of every program on
# every workload, medians of wall seconds and peak RSS (/usr/bin/time -f %M).
# SONARMAP is the `sonarmap` executable to measure; PEERS_DIR/bin holds the drivers of build.sh.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
sonarmap=$(realpath "${1:?usage: run.sh SONARMAP PEERS_DIR [INPUTS_TOOL]}")
peers=$(realpath "${2:?usage: run.sh SONARMAP PEERS_DIR [INPUTS_TOOL]}")
shift 2
tool="$root/build/bench/sonarmap_cloud_inputs"
if [[ $# -gt 0 && $1 != -- ]]; then tool=$1; shift; fi
[[ ${1:-} == -- ]] && shift
mkdir -p "$peers/inputs"
"$tool" "$peers/inputs"
graph="$root/../shared/data/octomap_spherical_scan.graph"
if [[ -f $graph ]]; then ln -sf "$(realpath "$graph")" "$peers/inputs/"; fi
echo "load before: $(uptime)"
"$here/run.py" "$sonarmap" "$peers" "$peers/inputs" "$@"
echo "load after: $(uptime)"
