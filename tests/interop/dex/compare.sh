#!/usr/bin/env bash
# The station against dex-retargeting on glove recordings, scored by `pomdar eval`.
#
# Usage: tests/interop/dex/compare.sh [--out FILE] [--jobs N] [--work DIR] [--scaling S]
#                                     [--table-only] [RECORDING|DIR ...]
#
# For each recording (an .mcap file, or every .mcap under a directory, e.g. an evaluation set
# from `pomdar eval-set`; default: the three reference recordings in ../shared/reference):
# - the station: `pomdar eval REC --json`, its `live_path` figures (the station's command in
#   force at each distinct glove frame);
# - four dex-retargeting configurations, each written by retarget_recording.py into
#   WORK/<recording>.<config>.mcap and scored by `pomdar eval --commands /dex/joint_states
#   --json`: vector α 0.2, vector without filter, dexpilot α 0.2, dexpilot without filter
#   (scaling_factor S, default 1.0; origin the wrist body; see retarget_recording.py).
# Prints one table (recording × retargeter) and writes it as Markdown to FILE (default
# target/dex-compare.md); the JSON reports stay in WORK (default target/dex-compare).
# --jobs: how many runs at once (default: the number of processors). --table-only: no runs, only
# the table again from the reports already in WORK.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
out="$root/target/dex-compare.md"
work="$root/target/dex-compare"
jobs="$(nproc 2>/dev/null || echo 2)"
scaling=1.0
table_only=0
inputs=()
while [ $# -gt 0 ]; do
    case "$1" in
        --out) out="$2"; shift 2 ;;
        --jobs) jobs="$2"; shift 2 ;;
        --work) work="$2"; shift 2 ;;
        --scaling) scaling="$2"; shift 2 ;;
        --table-only) table_only=1; shift ;;
        -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) inputs+=("$1"); shift ;;
    esac
done
configs=(vector-a0.2 vector-nofilter dexpilot-a0.2 dexpilot-nofilter)
if [ "$table_only" = 1 ]; then
    python="$("$here/setup.sh")"
    [ -f "$work/run.txt" ] || { echo "compare: no finished run in $work" >&2; exit 2; }
    read -r elapsed scaling < "$work/run.txt"
    failed=0
else
    if [ ${#inputs[@]} -eq 0 ]; then
        ref="$root/../shared/reference"
        inputs=("$ref/rokoko_orca_2024-11-20.mcap" "$ref/mediapipe_video_right.mcap"
                "$ref/quest_handtracking_right.mcap")
    fi
    recordings=()
    for input in "${inputs[@]}"; do
        if [ -d "$input" ]; then
            while IFS= read -r f; do
                recordings+=("$f")
            done < <(find "$input" -name '*.mcap' | sort)
        elif [ -f "$input" ]; then
            recordings+=("$input")
        else
            echo "compare: no such recording or directory: $input" >&2
            exit 2
        fi
    done
    [ ${#recordings[@]} -gt 0 ] || { echo "compare: no .mcap recordings found" >&2; exit 2; }

    started=$(date +%s)
    python="$("$here/setup.sh")"
    (cd "$root" && cargo build --quiet --bin pomdar)
    mkdir -p "$work"
    # Every run uses this one build, even if target/debug/pomdar is rebuilt meanwhile.
    pomdar="$work/pomdar"
    cp "$root/target/debug/pomdar" "$pomdar"

    # One task per line: KIND<TAB>RECORDING<TAB>STEM (KIND: station or a dex configuration name).
    tasks="$work/tasks.tsv"
    : > "$tasks"
    : > "$work/recordings.tsv"
    i=0
    for rec in "${recordings[@]}"; do
        i=$((i + 1))
        stem="$(printf '%02d' "$i")-$(basename "$rec" .mcap)"
        printf '%s\t%s\n' "$stem" "$rec" >> "$work/recordings.tsv"
        printf 'station\t%s\t%s\n' "$rec" "$stem" >> "$tasks"
        for c in "${configs[@]}"; do
            printf '%s\t%s\t%s\n' "$c" "$rec" "$stem" >> "$tasks"
        done
    done

    run_task() {
        local kind="$1" rec="$2" stem="$3"
        local json="$work/$stem.$kind.json" log="$work/$stem.$kind.log" t0 t1
        t0=$(date +%s.%N)
        if [ "$kind" = station ]; then
            "$pomdar" eval "$rec" --json > "$json" 2> "$log"
        else
            local type="${kind%%-*}" alpha
            case "$kind" in *-nofilter) alpha=none ;; *) alpha="${kind##*-a}" ;; esac
            "$python" "$here/retarget_recording.py" "$rec" "$work/$stem.$kind.mcap" \
                --type "$type" --low-pass-alpha "$alpha" --scaling "$scaling" 2> "$log"
            "$pomdar" eval "$work/$stem.$kind.mcap" --commands /dex/joint_states --json \
                > "$json" 2>> "$log"
        fi
        t1=$(date +%s.%N)
        printf '%s\t%s\t%.1f\n' "$stem" "$kind" \
            "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" >> "$work/times.tsv"
        echo "  done $stem $kind" >&2
    }
    export -f run_task
    export work python here pomdar scaling
    : > "$work/times.tsv"
    echo "compare: ${#recordings[@]} recording(s) × (station + ${#configs[@]} dex" \
        "configurations), $jobs at once" >&2
    failed=0
    tr '\t' '\037' < "$tasks" | xargs -d '\n' -P "$jobs" -I{} bash -c \
        'IFS=$'"'"'\037'"'"' read -r k r s <<< "$1"
         run_task "$k" "$r" "$s" || { echo "  FAILED $s $k (see $work/$s.$k.log)" >&2; exit 1; }' \
        _ {} \
        || failed=1
    elapsed=$(( $(date +%s) - started ))
    echo "$elapsed $scaling" > "$work/run.txt"
fi

"$python" - "$work" "$out" "$elapsed" "$scaling" "${configs[@]}" <<'PY'
import json
import sys
from pathlib import Path

work, out, elapsed = Path(sys.argv[1]), Path(sys.argv[2]), int(sys.argv[3])
scaling, configs = sys.argv[4], sys.argv[5:]
recordings = [line.split("\t") for line in (work / "recordings.tsv").read_text().splitlines()]
times = {}
for line in (work / "times.tsv").read_text().splitlines():
    stem, kind, seconds = line.split("\t")
    times[(stem, kind)] = float(seconds)

LABEL = {"station": "station (live path)", "vector-a0.2": "dex vector α0.2",
         "vector-nofilter": "dex vector no filter", "dexpilot-a0.2": "dex dexpilot α0.2",
         "dexpilot-nofilter": "dex dexpilot no filter"}
MEAN_WIDTHS = [22, 3, 6, 10, 8, 12, 9]
COLUMNS = ["recording", "retargeter", "tip mm", "s*", "jerk rad", "max step rad",
           "pinches closed %", "own-scale mm", "flexion r", "lag ms", "limit-viol. frames",
           "beats station (tip & jerk)"]


def figures(stem, kind):
    path = work / f"{stem}.{kind}.json"
    try:
        report = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return report["live_path"] if kind == "station" else report


def fmt(value, digits):
    return "–" if value is None else f"{value:.{digits}f}"


rows, beats, sums = [], {c: [] for c in configs}, {}
for stem, path in recordings:
    station = figures(stem, "station")
    for kind in ["station", *configs]:
        q = figures(stem, kind)
        if q is None:
            rows.append([stem, LABEL[kind]] + ["failed"] + [""] * (len(COLUMNS) - 3))
            continue
        lag = q.get("flexion_lag_s")
        both = ""
        if kind != "station" and station is not None:
            win = (q["tip_error_mean_mm"] < station["tip_error_mean_mm"]
                   and q["jerk_rad"] < station["jerk_rad"])
            both = "yes" if win else "no"
            if win:
                beats[kind].append(stem)
        rows.append([
            stem, LABEL[kind], fmt(q["tip_error_mean_mm"], 1), fmt(q["tip_scale"], 2),
            fmt(q["jerk_rad"], 4),
            fmt(q["max_step_rad"], 3), fmt(q.get("pinches_closed_pct"), 0),
            fmt(q.get("tip_error_own_scale_mean_mm"), 1), fmt(q.get("flexion_correlation_mean"), 3),
            fmt(None if lag is None else lag * 1e3, 0), str(q["limit_violation_frames"]), both,
        ])
        s = sums.setdefault(kind, {"n": 0, "tip": 0.0, "rel": 0.0, "jerk": 0.0, "own": 0.0,
                                   "r": 0.0, "nr": 0})
        s["n"] += 1
        s["tip"] += q["tip_error_mean_mm"]
        s["rel"] += q["tip_error_mean_mm"] / q["tip_scale"]
        s["jerk"] += q["jerk_rad"]
        s["own"] += q.get("tip_error_own_scale_mean_mm") or 0.0
        if q.get("flexion_correlation_mean") is not None:
            s["r"] += q["flexion_correlation_mean"]
            s["nr"] += 1

widths = [max(len(COLUMNS[i]), *(len(r[i]) for r in rows)) for i in range(len(COLUMNS))]
line = lambda cells: "  ".join(c.ljust(w) for c, w in zip(cells, widths))
print(line(COLUMNS))
print(line(["-" * w for w in widths]))
for r in rows:
    print(line(r))

md = ["# Station vs dex-retargeting (scored by `pomdar eval`)", "",
      "Station: `pomdar eval REC --json`, its live path. dex-retargeting 0.5.0 (PyPI, MIT): "
      f"`tests/interop/dex/retarget_recording.py` (scaling {scaling}, origin link the wrist body, "
      "wrist joint held at 0, human palm frame turned onto the robot's), its commands scored by "
      "`pomdar eval REC --commands /dex/joint_states --json`. Tip and own-scale: mean fingertip "
      "error in the palm frame (mm), the human hand scaled by s* (the least-squares robot/human "
      "scale: a robot hand that curls, or stays small, has a small s* and so a small error in "
      "mm; tip/s* is the error in human-hand millimetres); jerk: mean |third difference| per "
      "joint and frame (rad); "
      "flexion r: mean per-digit correlation; lag: robot behind human (ms). dex's limit "
      "violations are its optimiser's 1e-3 rad widening of the joint limits.", "",
      "| " + " | ".join(COLUMNS) + " |", "|" + "|".join("---" for _ in COLUMNS) + "|"]
md += ["| " + " | ".join(r) + " |" for r in rows]
md += ["", "## Means over the recordings", "",
       "| retargeter | recordings | tip mm | tip/s* mm | jerk rad | own-scale mm | flexion r |",
       "|---|---|---|---|---|---|---|"]
print("\nmeans over the recordings:")
print("  " + "  ".join(h.ljust(w) for h, w in zip(
    ["retargeter", "n", "tip mm", "tip/s* mm", "jerk rad", "own-scale mm", "flexion r"],
    MEAN_WIDTHS)))
for kind in ["station", *configs]:
    s = sums.get(kind)
    if not s or not s["n"]:
        continue
    cells = [LABEL[kind], str(s["n"]), f"{s['tip'] / s['n']:.1f}", f"{s['rel'] / s['n']:.1f}",
             f"{s['jerk'] / s['n']:.4f}",
             f"{s['own'] / s['n']:.1f}", fmt(s["r"] / s["nr"] if s["nr"] else None, 3)]
    md.append("| " + " | ".join(cells) + " |")
    print("  " + "  ".join(c.ljust(w) for c, w in zip(cells, MEAN_WIDTHS)))
md += ["", "## dex configurations beating the station on both tip error and jerk", ""]
print("\ndex configurations beating the station on both tip error and jerk:")
for kind in configs:
    text = f"{LABEL[kind]}: {len(beats[kind])} of {len(recordings)}" + (
        f" ({', '.join(beats[kind])})" if beats[kind] else "")
    md.append(f"- {text}")
    print("  " + text)
total = sum(times.values())
dex_time = sum(t for (s, k), t in times.items() if k != "station")
md += ["", f"Wall time: {elapsed} s ({total:.0f} s of runs: {dex_time:.0f} s dex retargeting "
       f"and scoring, {total - dex_time:.0f} s station eval)."]
print(f"\ndex scaling_factor {scaling}; wall time {elapsed} s ({total:.0f} s of runs, "
      f"{dex_time:.0f} s of them dex)")
out.parent.mkdir(parents=True, exist_ok=True)
out.write_text("\n".join(md) + "\n")
print(f"wrote {out}")
PY
exit "$failed"
