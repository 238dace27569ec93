#!/usr/bin/env bash
# moorsim batch under `mpirun -np 2` (one thread per rank) gives the rows of the same
# campaign on two threads of one process: rank 0 deals the runs, receives the rows and
# alone writes the results; transient runs wait for the intact runs they take their
# instants from, wherever those ran. Usage: mpi_batch_test.sh MOORSIM SOURCE_DIR
set -euo pipefail
moorsim=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/campaign.yaml" <<YAML
scenario: $source_dir/scenarios/library/thesis_no_failure_current.yaml
seed: 3
set: {simulation.duration: 150}
blocks:
  - name: failures
    set: {failure.mode: fairlead}
    factors:
      - {key: failure.line, values: [1, 4, 8]}
      - {key: failure.time, uniform: [60, 90]}
    seeds: 1
  - name: intact
    seeds: 2
  - name: storm
    design: {condition: intact}
    seeds: {from: 1, to: 2}
  - name: parted
    design: {condition: transient, intact: storm}
    set: {failure.mode: fairlead}
    factors: [{key: failure.line, values: [2, 5]}]
    seeds: {from: 1, to: 2}
YAML

"$moorsim" batch "$work/campaign.yaml" --out "$work/threads" --threads 2 --quiet
# As root (CI containers) Open MPI wants to be told; --oversubscribe: the ranks may outnumber
# the cores the launcher sees.
mpirun --allow-run-as-root --oversubscribe -np 2 \
  "$moorsim" batch "$work/campaign.yaml" --out "$work/mpi" --threads 1 --quiet

/usr/bin/python3 - "$work/threads" "$work/mpi" <<'PY'
import json, pathlib, sys

def rows(directory):
    out = {}
    for path in sorted(pathlib.Path(directory, "rows").glob("*.json")):
        row = json.loads(path.read_text())
        row.pop("wall_time")
        for key in list(row.get("integrator", {})):
            if key.endswith("_seconds"):
                row["integrator"].pop(key)
        out[row["run"]] = row
    return out

threads, mpi = rows(sys.argv[1]), rows(sys.argv[2])
assert len(threads) == 11, f"threaded batch: {len(threads)} rows, expected 11"
assert threads == mpi, "rows differ between the threaded and the MPI batch"
for run in range(7, 11):
    intact = threads[5 + (run - 7) % 2]
    line = threads[run]["failure"]["line"]
    instant = intact["design"]["lines"][line - 1]["time_of_max_top_tension"]
    assert threads[run]["failure"]["time"] == instant, f"run {run}: not at its intact instant"
for name in ("runs.csv", "campaign.h5"):
    assert pathlib.Path(sys.argv[2], name).exists(), f"MPI batch wrote no {name}"
print("mpi batch: 11 rows equal to the threaded batch's, transients at their instants")
PY
