#!/usr/bin/env bash
# The C API from Fortran: install moorsim from its build directory into a scratch prefix,
# build examples/fortran_coupling against it with find_package(moorsim), step the seed
# mooring's lines along a surge-heave motion for 60 s, and compare its fairlead tensions
# with the same steps through the installed Python module (moorsim.Lines): the same code
# behind both interfaces, so the same numbers bit for bit.
# Usage: fortran_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
source "$(dirname "$0")/example_build.sh"
build_example fortran_coupling
scenario="$source/scenarios/library/seed_tapm.yaml"
"$work/fortran_coupling/surge" "$scenario" | tee "$work/fortran.txt"
site=$(/usr/bin/python3 -c 'import sys; print("lib/python%d.%d/site-packages" % sys.version_info[:2])')
PYTHONPATH="$work/prefix/$site" /usr/bin/python3 - "$scenario" "$work/fortran.txt" <<'PY'
import math, sys
import numpy as np
import moorsim
lines = moorsim.Lines(sys.argv[1])
lines.init(np.zeros(6), np.zeros(6))
pi = 4.0 * math.atan(1.0)
ws, wh = 2.0 * pi / 60.0, 2.0 * pi / 10.0
for k in range(1, 601):
    x = np.zeros(6)
    xd = np.zeros(6)
    x[0] = 5.0 * math.sin(ws * k * 0.1)
    xd[0] = 5.0 * ws * math.cos(ws * k * 0.1)
    x[2] = math.sin(wh * k * 0.1)
    xd[2] = wh * math.cos(wh * k * 0.1)
    lines.step(x, xd, 0.1)
fortran = [float(v) for v in open(sys.argv[2]).read().split()[4:]]
python = list(lines.fairlead_tensions())
assert len(fortran) == len(python) == 8, (fortran, python)
assert fortran == python, "\n".join(f"{a!r} {b!r}" for a, b in zip(fortran, python))
print("Fortran example: built against the installed library; its 8 tensions at 60 s are "
      "Python's bit for bit")
PY
