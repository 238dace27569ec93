#!/usr/bin/env bash
# Writes the user guide's figures (docs/figures/) from real runs, after a release build:
#   tools/dev/figures.sh [SENSOR_FAULTS_DIR]
# SENSOR_FAULTS_DIR: the held-out sensor-fault campaign's directory (default
# out/sensor_faults; made with `moorsim batch scenarios/campaigns/sensor_faults.yaml --out
# out/sensor_faults`, about 15 minutes on 2 cores), whose report gives the detectors'
# confusion matrices and delay curves.
set -euo pipefail
cd "$(dirname "$0")/../.."
moorsim=build/release/tools/moorsim
campaign=${1:-out/sensor_faults}
figures=docs/figures
mkdir -p "$figures" out/figures

# The thesis case: line 6 parts at its fairlead at 400 s, in waves and current.
"$moorsim" run scenarios/library/thesis_line6_current.yaml --out out/figures/line6 --quiet
/usr/bin/python3 tools/plot_run.py out/figures/line6 --out out/figures/line6 >/dev/null
for name in trajectory tensions detectors; do
  cp "out/figures/line6/$name.png" "$figures/line6_$name.png"
done

# The held-out sensor-fault campaign's report.
/usr/bin/python3 tools/report.py "$campaign" >/dev/null
cp "$campaign/confusion.png" "$figures/sensor_faults_confusion.png"
cp "$campaign/delay_ecdf.png" "$figures/sensor_faults_delays.png"
ls -l "$figures"
