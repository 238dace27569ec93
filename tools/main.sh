#!/usr/bin/env bash
# Quick start, main job: installs the dependencies (Debian packages), builds moorsim
# (release preset) and runs the main job end to end: the static solution of the seed
# mooring from the FEM lines settled to rest, then a 1000 s simulate-lines run of the seed
# case with the turret surging 5 m / 100 s plus 2 m / 10 s, writing out/seed_surge.csv.
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
./build/release/tools/moorsim simulate-lines scenarios/library/seed_tapm.yaml \
  --motion surge:5,100,2,10 --duration 1000 --out out/seed_surge.csv
echo "wrote out/seed_surge.csv"
