#!/usr/bin/env bash
# What the waves on the lines (environment.waves.on_lines) change in fairlead tension, and
# what they cost: the seed mooring (1000 m) and a shallow one (100 m, made by `moorsim
# template`), each in the seed sea state and a severe one, run with the waves on the hull
# only and on the lines too (Wheeler stretching). 1200 s per run, tensions at 10 Hz, the
# first 200 s left out; the same seed, so the hull sees the same sea in both.
#
#   benchmarks/waves_on_lines.sh [MOORSIM]
#
# Prints a Markdown table: per case, the largest change over the lines of the tension's
# mean, standard deviation and maximum, and the run times. Needs python3-h5py.
set -euo pipefail
moorsim=${1:-build/release/tools/moorsim}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$moorsim" template turret --lines 8 --depth 100 --length 700 --pretension 1.2e6 \
  --out "$work/shallow.yaml" >/dev/null
declare -A scenario=([seed]="$root/scenarios/library/seed_tapm.yaml" [shallow]="$work/shallow.yaml")

echo "| mooring | sea (Hs, Tp) | mean | std | max | largest max with / without [kN] | run time with / without [s] |"
echo "|---|---|---|---|---|---|---|"
for mooring in seed shallow; do
  for sea in "2.5 7" "6 11"; do
    read -r hs tp <<<"$sea"
    times=()
    for on in false true; do
      out="$work/$mooring-$hs-$on"
      start=$(date +%s.%N)
      "$moorsim" run "${scenario[$mooring]}" --set simulation.duration=1200 \
        --set simulation.output_rate_hz=10 --set environment.waves.hs="$hs" \
        --set environment.waves.tp="$tp" --set environment.waves.on_lines="$on" \
        --out "$out" >/dev/null 2>&1
      times+=("$(echo "$(date +%s.%N) - $start" | bc)")
    done
    /usr/bin/python3 - "$work/$mooring-$hs-false/run.h5" "$work/$mooring-$hs-true/run.h5" \
      "$mooring" "$hs m, $tp s" "${times[1]}" "${times[0]}" <<'PY'
import sys
import h5py
import numpy as np

def tensions(path):
    with h5py.File(path, "r") as f:
        t = f["time"][:]
        return f["mooring/fairlead_tension"][:][t >= 200.0]

off, on = tensions(sys.argv[1]), tensions(sys.argv[2])
def change(stat):
    a, b = stat(off), stat(on)
    return f"{100.0 * np.max(np.abs(b / a - 1.0)):.2f} %"
print(f"| {sys.argv[3]} | {sys.argv[4]} | {change(lambda x: x.mean(0))} | "
      f"{change(lambda x: x.std(0))} | {change(lambda x: x.max(0))} | "
      f"{on.max() / 1e3:.0f} / {off.max() / 1e3:.0f} | "
      f"{float(sys.argv[5]):.1f} / {float(sys.argv[6]):.1f} |")
PY
  done
done
