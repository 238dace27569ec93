#!/usr/bin/env bash
# Imports every MoorDyn input file of a MoorDyn source tree (its examples, tests and
# benchmarks) with `moorsim import moordyn`, and runs each imported scenario: `moorsim
# static`, then `moorsim simulate-lines` for 60 s of a 1 m, 20 s surge motion. Prints one
# table row per file: what happened, and the first line of what moorsim said otherwise.
#
#   benchmarks/moordyn_examples.sh MOORDYN_SOURCE_TREE [MOORSIM]
#
# MoorDyn's files are read where they are; nothing of them enters this project.
set -euo pipefail
tree=${1:?usage: benchmarks/moordyn_examples.sh MOORDYN_SOURCE_TREE [MOORSIM]}
moorsim=${2:-build/release/tools/moorsim}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| file | import | static | simulate-lines | what moorsim said |"
echo "|---|---|---|---|---|"
imported=0 ran=0 refused=0 total=0
while IFS= read -r file; do
  # A MoorDyn input file has a line-types table under a dashed header.
  grep -qiE -- '---.*(LINE TYPES|LINE DICTIONARY)' "$file" || continue
  total=$((total + 1))
  name=${file#"$tree"/}
  scenario="$work/$(echo "$name" | tr '/ ' '__').yaml"
  if ! "$moorsim" import moordyn "$file" --out "$scenario" >/dev/null 2>"$work/err"; then
    refused=$((refused + 1))
    said=$( (grep -v warning "$work/err" || true) | head -1 | sed "s|$tree/||; s/|/\\\\|/g")
    echo "| $name | refused | | | $said |"
    continue
  fi
  imported=$((imported + 1))
  static=ok simulate=ok said=$( (grep warning "$work/err" || true) | head -1 | sed "s|$tree/||; s/|/\\\\|/g")
  if ! "$moorsim" static "$scenario" >/dev/null 2>"$work/err"; then
    static=failed
    said=$(head -1 "$work/err" | sed "s|$work/||; s/|/\\\\|/g")
  fi
  if ! "$moorsim" simulate-lines "$scenario" --motion surge:1,20 --duration 60 --quiet \
       >/dev/null 2>"$work/err"; then
    simulate=failed
    if [[ $static == ok ]]; then said=$(head -1 "$work/err" | sed "s|$work/||; s/|/\\\\|/g"); fi
  fi
  if [[ $static == ok && $simulate == ok ]]; then ran=$((ran + 1)); fi
  echo "| $name | imported | $static | $simulate | $said |"
done < <(find "$tree" -type f \( -name '*.txt' -o -name '*.dat' \) | sort)
echo
echo "$total MoorDyn input files: $imported imported ($ran of them ran static and simulate-lines), $refused refused"
