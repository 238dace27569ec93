#!/usr/bin/env bash
# Installs moorsim's build and test dependencies from Debian 12 packages.
# Idempotent and non-interactive: only packages that are missing are installed.
# Run as root (or with sudo available). Nothing is downloaded from outside Debian.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev
  libsundials-dev          # CVODE 6.x with SUNLinSol_KLU
  libsuitesparse-dev       # KLU, AMD, COLAMD
  libyaml-cpp-dev
  nlohmann-json3-dev
  libcli11-dev
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  libhdf5-dev              # run.h5 writer (HDF5 C API)
  nettle-dev               # SHA-256 of detector plugin libraries
  libgeographiclib-dev     # the monitor: latitude and longitude to the scenario's frame
  libsqlite3-dev           # the monitor's record (SQLite in write-ahead-log mode)
  libopenmpi-dev openmpi-bin   # moorsim batch under mpirun
  python3-numpy python3-h5py python3-matplotlib   # tools/plot_run.py
  python3-scipy            # tools/report.py: the intervals' distributions
  python3-jsonschema python3-yaml   # tests: library scenarios against moorsim.schema.json
  pybind11-dev python3-dev python3-pytest   # the Python module (import moorsim) and its tests
  gfortran                 # tests: the C API from Fortran (examples/fortran_coupling)
  python3-pandas python3-xarray     # campaign tables as DataFrames, runs as xarray Datasets
  clang-format
  mkdocs                   # the user guide (docs/) as a site, checked by tools/dev/test.sh
  chromium nodejs          # tests: the monitor's display in a headless browser
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages already installed"
fi
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
# Debian's nodejs comes without npm (its own package); another build of nodejs may bring it.
if ! command -v npm > /dev/null; then missing+=(npm); fi
if ((${#missing[@]} > 0)); then
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# playwright-core from the npm registry (Debian has none), at the version package-lock.json
# pins, to drive Debian's chromium in the display's tests; it downloads no browser.
display_tests="$(cd "$(dirname "$0")/.." && pwd)/tests/display"
if [[ ! -f "$display_tests/node_modules/playwright-core/package.json" ]]; then
  echo "setup: installing playwright-core into tests/display"
  (cd "$display_tests" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund)
fi
