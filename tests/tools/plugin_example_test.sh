#!/usr/bin/env bash
# The out-of-tree detector plugin example end to end, as a user builds it: install moorsim
# from its build directory into a scratch prefix, build examples/detector_plugin against it
# with find_package(moorsim), and run a small campaign with the plugin beside the built-in
# detectors; every run must finish and the table must carry the plugin's columns.
# Usage: plugin_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
cmake -S "$source/examples/detector_plugin" -B "$work/plugin" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
cmake --build "$work/plugin" >"$work/build.log"
plugin="$work/plugin/libcusum_detector.so"
test -f "$plugin" || { echo "FAILED: no $plugin"; exit 1; }

cat >"$work/campaign.yaml" <<YAML
scenario: $source/scenarios/library/thesis_line6_current.yaml
seed: 11
set:
  simulation.duration: 120
  failure.time: 60
  detectors: [{type: mle}, {type: deficit}, {plugin: $plugin, type: bank_cusum, label: cusum, threshold: 8}]
blocks:
  - name: line6
    seeds: 2
YAML
"$work/prefix/bin/moorsim" batch "$work/campaign.yaml" --out "$work/out" --quiet --threads 2

/usr/bin/python3 - "$work/out/runs.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2, f"{len(rows)} rows"
for row in rows:
    assert row["status"] == "ok", row["status"]
    for label in ("mle", "deficit", "cusum"):
        assert f"{label}.false_alarms" in row, f"no {label} columns"
print("plugin example: built out of tree, ran in a campaign beside mle and deficit")
PY
