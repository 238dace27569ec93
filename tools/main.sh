#!/usr/bin/env bash
# Quick start, main job: installs the dependencies (Debian packages), builds moorsim
# (release preset) and runs the main job end to end: the static solution of the seed
# mooring, then the thesis case "line 6 parts at 400 s, with current" as a coupled run
# (vessel, FEM lines, waves, current, PI controller, sensors) written to
# out/thesis_line6_current/run.h5 and summary.json, and its figures drawn by plot_run.py.
set -euo pipefail
cd "$(dirname "$0")/.."

./tools/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release

mkdir -p out
./build/release/tools/moorsim static scenarios/library/seed_tapm.yaml
echo
./build/release/tools/moorsim static scenarios/library/seed_tapm.yaml --json > out/seed_static.json
echo "wrote out/seed_static.json"
./build/release/tools/moorsim run scenarios/library/thesis_line6_current.yaml \
  --out out/thesis_line6_current
/usr/bin/python3 tools/plot_run.py out/thesis_line6_current
