#!/usr/bin/env bash
# The C coupling example end to end, as a user builds it: install moorsim from its build
# directory into a scratch prefix, build examples/c_coupling against it with
# find_package(moorsim), and run it on the seed mooring with a steady 1 MN toward north.
# Its own vessel integrator, stepping moorsim's lines through the C API, must come to rest
# where `moorsim static` finds the lines' load equal and opposite to that force (within
# 0.2 %, the rest being the damping of the last millimetres per second), with the same
# fairlead tensions (0.1 %); and its save/restore repeat must be identical.
# Usage: c_coupling_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
source "$(dirname "$0")/example_build.sh"
build_example c_coupling
scenario="$source/scenarios/library/thesis_no_failure.yaml"
"$work/c_coupling/vessel_coupling" "$scenario" 1e6 | tee "$work/run.txt"
read -r _ x y < <(grep '^offset:' "$work/run.txt")
"$work/prefix/bin/moorsim" static "$scenario" --offset "$x,$y,0" --json >"$work/static.json"

/usr/bin/python3 - "$work/run.txt" "$work/static.json" <<'PY'
import json, sys
run = dict(line.split(":", 1) for line in open(sys.argv[1]) if ":" in line)
static = json.load(open(sys.argv[2]))
assert run["at rest"].strip().startswith("yes"), run["at rest"]
assert run["repeat after restore"].strip() == "identical", run["repeat after restore"]
fx, fy = (float(v) for v in run["load"].split())
sx, sy = static["net_force"][:2]
assert abs(sx + 1e6) < 2e3, f"static surge load {sx} N at the coupled rest, expected -1e6 N"
assert abs(fx - sx) < 2e3 and abs(fy - sy) < 2e3, (fx, fy, sx, sy)
tensions = [float(v) for v in run["tensions"].split()]
for line, t in zip(static["lines"], tensions):
    assert abs(t - line["fairlead_tension"]) < 1e-3 * line["fairlead_tension"], (line["id"], t)
print(f"C coupling example: at rest at x = {run['offset'].split()[0]} m, static load "
      f"{sx / 1e3:.2f} kN against -1000 kN, tensions within 0.1 %, restore identical")
PY
