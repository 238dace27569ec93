#!/usr/bin/env bash
# Rewrites the regression (golden) files in tests/data/golden/ from the current release
# build: the lines-alone surge (mooring_fem), the two coupled library runs (simulation) and
# the run.h5 that `moorsim compare` checks a fresh run against (cli).
# Run it only after an intended change of the numbers, look at `git diff tests/data/golden`
# and say why in the commit. Refuses to run under CI=true: CI compares, it never rewrites.
set -euo pipefail
cd "$(dirname "$0")/../.."
if [[ "${CI:-}" == "true" ]]; then
  echo "update_golden.sh: refusing to rewrite golden files under CI=true" >&2
  exit 1
fi
cmake --preset release >/dev/null
cmake --build --preset release --target moorsim_mooring_fem_tests moorsim_simulation_tests \
  moorsim_cli_tests
MOORSIM_UPDATE_GOLDEN=1 build/release/tests/moorsim_mooring_fem_tests --gtest_filter='Golden.*'
MOORSIM_UPDATE_GOLDEN=1 build/release/tests/moorsim_simulation_tests \
  --gtest_filter='Library/CoupledGolden.*'
MOORSIM_UPDATE_GOLDEN=1 build/release/tests/moorsim_cli_tests --gtest_filter='CompareGolden.*'
git status --short tests/data/golden
