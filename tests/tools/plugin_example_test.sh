#!/usr/bin/env bash
# The out-of-tree detector plugin example end to end, as a user builds it: install moorsim
# from its build directory into a scratch prefix, build examples/detector_plugin against it
# with find_package(moorsim), and run a small campaign with the plugin beside the built-in
# detectors (DHT, MLE, GLR and the force-deficit test), once named in the campaign by its
# path and once loaded with --plugin and named by its type alone; every run must finish and
# the table must carry the plugin's columns.
# Usage: plugin_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
source "$(dirname "$0")/example_build.sh"
build_example detector_plugin
plugin="$work/detector_plugin/libcusum_detector.so"
test -f "$plugin" || { echo "FAILED: no $plugin"; exit 1; }

cat >"$work/campaign.yaml" <<YAML
scenario: $source/scenarios/library/thesis_line6_current.yaml
seed: 11
set:
  simulation.duration: 120
  failure.time: 60
  detectors: [{type: dht}, {type: mle}, {type: glr}, {type: deficit}, {plugin: $plugin, type: bank_cusum, label: cusum, threshold: 8}]
blocks:
  - name: line6
    seeds: 2
YAML
"$work/prefix/bin/moorsim" batch "$work/campaign.yaml" --out "$work/out" --quiet --threads 2
sed -e "s|{plugin: $plugin, type: bank_cusum|{type: bank_cusum|" "$work/campaign.yaml" \
  >"$work/by_type.yaml"
"$work/prefix/bin/moorsim" batch "$work/by_type.yaml" --plugin "$plugin" --out "$work/out2" \
  --quiet --threads 2

/usr/bin/python3 - "$work/out/runs.csv" "$work/out2/runs.csv" <<'PY'
import csv, sys
for table in sys.argv[1:]:
    rows = list(csv.DictReader(open(table)))
    assert len(rows) == 2, f"{table}: {len(rows)} rows"
    for row in rows:
        assert row["status"] == "ok", row["status"]
        for label in ("dht", "mle", "glr", "deficit", "cusum"):
            assert f"{label}.false_alarms" in row, f"{table}: no {label} columns"
# The same campaign both ways: the same verdicts.
a, b = (list(csv.DictReader(open(t))) for t in sys.argv[1:])
for x, y in zip(a, b):
    assert x["cusum.alarm_time"] == y["cusum.alarm_time"], (x["cusum.alarm_time"], y["cusum.alarm_time"])
print("plugin example: built out of tree, ran in a campaign beside dht, mle, glr and deficit")
PY
