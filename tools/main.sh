#!/usr/bin/env bash
# Quick start, main job: installs the dependencies (Debian packages), builds moorsim
# (release preset) and runs the main job end to end: a small Monte-Carlo campaign of the
# TAPM thesis's detection study (each of the eight lines parting at a drawn time, with and
# without current, 3 seeds each, plus two intact hours: 50 runs, a minute or two on two
# cores) written to out/thesis_detection_small/ (runs.csv, campaign.h5) and its report
# (report.html with figures). Then one run of the thesis case "line 6 parts at 400 s, with
# current" with its figures, the same run's detection replayed by `moorsim detect` from its
# recorded samples (the alarms as JSON lines, identical to the run's), and the static
# solution of the seed mooring. Installs the program, the library (C API) and the Python
# package under ~/.local (MOORSIM_PREFIX to change it), so that `moorsim` and
# `python3 -c "import moorsim"` work afterwards.
set -euo pipefail
cd "$(dirname "$0")/.."

./tools/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release
prefix=${MOORSIM_PREFIX:-$HOME/.local}
cmake --install build/release --prefix "$prefix" >/dev/null
site=$(/usr/bin/python3 -c 'import sys; print("lib/python%d.%d/site-packages" % sys.version_info[:2])')
PYTHONPATH="$prefix/$site${PYTHONPATH:+:$PYTHONPATH}" /usr/bin/python3 -c \
  "import moorsim; print('installed under $prefix: moorsim', moorsim.__version__, '(import moorsim)')"

mkdir -p out
# Afresh each time (a minute or two): a directory left by an older version of the campaign
# files would be refused, as `moorsim batch` refuses to mix two campaigns' rows.
rm -rf out/thesis_detection_small
./build/release/tools/moorsim batch scenarios/campaigns/thesis_detection_small.yaml \
  --out out/thesis_detection_small
/usr/bin/python3 tools/report.py out/thesis_detection_small
echo
./build/release/tools/moorsim run scenarios/library/thesis_line6_current.yaml \
  --out out/thesis_line6_current
/usr/bin/python3 tools/plot_run.py out/thesis_line6_current
echo
./build/release/tools/moorsim detect out/thesis_line6_current/run.h5 \
  --out out/thesis_line6_current_detect
echo
./build/release/tools/moorsim static scenarios/library/seed_tapm.yaml
echo
./build/release/tools/moorsim static scenarios/library/seed_tapm.yaml --json > out/seed_static.json
echo "wrote out/seed_static.json"
echo "report: out/thesis_detection_small/report.html"
