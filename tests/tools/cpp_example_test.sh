#!/usr/bin/env bash
# The C++ interface from outside the tree: install moorsim from its build directory into a
# scratch prefix, build examples/cpp_library against it with find_package(moorsim) (every
# installed header it includes must be there and compile on its own), and run it on the
# thesis case: lines built from typed parameters step, a run stops on request after its
# first minute, a thrust of the program's own pushes the plant forward, and the plant's
# typed model changed in code (its setpoint moved north) makes the vessel go north.
# Usage: cpp_example_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
source "$(dirname "$0")/example_build.sh"
build_example cpp_library
"$work/cpp_library/library_tour" "$source/scenarios/library/thesis_line6_current.yaml" |
  tee "$work/tour.txt"
grep -q '^typed lines at 10.0 s: fairlead tensions' "$work/tour.txt"
grep -q '^run: interrupted after 61 rows, at 60 s' "$work/tour.txt"
forward=$(sed -n 's/^plant: \([0-9.-]*\) m forward.*/\1/p' "$work/tour.txt")
/usr/bin/python3 -c "import sys; sys.exit(0 if float('$forward') > 1.0 else 1)" ||
  { echo "FAILED: the plant moved $forward m forward under its thrust"; exit 1; }
north=$(sed -n 's/^typed plant: \([0-9.-]*\) m north.*/\1/p' "$work/tour.txt")
/usr/bin/python3 -c "import sys; sys.exit(0 if float('$north') > 1.0 else 1)" ||
  { echo "FAILED: the typed plant moved $north m toward its setpoint 10 m north"; exit 1; }
echo "C++ example: built out of tree against the installed headers and library, ran"
