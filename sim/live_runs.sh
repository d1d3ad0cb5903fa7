#!/usr/bin/env bash
# The simulated G4 grasp live over loopback DDS, N times in a row: `pomdar demo --physics`
# with the shipped glove script at its default noise, one line per run (correctness and the
# physics' real-time factor), then how many scored correctness 1.
#
# Usage: bash sim/live_runs.sh [N] [extra pomdar demo arguments, e.g. --config FILE]
#   (a release build with the simulator: bash sim/setup_mujoco.sh, then
#    cargo build --release --features physics --bin pomdar)
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-20}"
shift || true
pomdar=target/release/pomdar
if ! [ -x "$pomdar" ]; then
    echo "error: $pomdar is missing: build it with cargo build --release --features physics --bin pomdar" >&2
    exit 1
fi
ok=0
for i in $(seq 1 "$runs"); do
    line=$("$pomdar" demo --physics --task G4 --glove-script launch_configs/sim/grasp_place.toml \
        --duration 13 --json "$@" 2>/dev/null | python3 -c '
import json, sys
p = json.load(sys.stdin)["physics"]
print(p["correctness"], round(p["realtime_factor"], 1))')
    read -r correctness factor <<<"$line"
    echo "run $i: correctness $correctness (physics ${factor}x real time)"
    if [ "$correctness" = "1.0" ]; then ok=$((ok + 1)); fi
done
echo "correctness 1 in $ok of $runs live runs"
