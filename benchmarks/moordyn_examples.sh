#!/usr/bin/env bash
# Imports every MoorDyn input file of a MoorDyn source tree (its examples, tests and
# benchmarks) with `moorsim import moordyn`, and runs each imported scenario: `moorsim
# static`, then `moorsim simulate-lines` for 60 s of a 1 m, 20 s surge motion. Prints one
# table row per file: what happened, and the first line of what moorsim said otherwise.
#
#   benchmarks/moordyn_examples.sh MOORDYN_SOURCE_TREE [MOORSIM]
#
# With MOORDYN set to a MoorDyn v2 install prefix (include/moordyn/MoorDyn2.h), each file
# that ran and has coupled (vessel) points is also run by MoorDyn itself, through
# benchmarks/moordyn_driver.cc under the same motion (the file's own time step and scheme,
# coupled every 1 ms), and the row adds the worst coupled point's RMS difference of the
# fairlead tension over t >= 10 s as a % of MoorDyn's range (benchmarks/moordyn_compare.py)
# and the wall time of each program's stepping (moorsim at its default tolerances, after
# its static start; MoorDyn after MoorDyn_Init). MD_TIMEOUT (default 600) bounds a MoorDyn
# run [s].
#
# MoorDyn's files are read where they are; nothing of them enters this project.
set -euo pipefail
tree=${1:?usage: benchmarks/moordyn_examples.sh MOORDYN_SOURCE_TREE [MOORSIM]}
tree=$(cd "$tree" && pwd)
moorsim=$(realpath "${2:-build/release/tools/moorsim}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
side_by_side=
if [[ -n ${MOORDYN:-} ]]; then
  libdir=$(dirname "$(ls "$MOORDYN"/lib*/libmoordyn.so* | head -1)")
  ${CXX:-c++} -O2 -std=c++17 -o "$work/driver" "$here/moordyn_driver.cc" -I"$MOORDYN/include" \
    -L"$libdir" -lmoordyn -Wl,-rpath,"$libdir"
  side_by_side=1
fi

if [[ -n $side_by_side ]]; then
  echo "| file | import | static | simulate-lines | RMS vs MoorDyn [% of range (of mean)] | moorsim [s] | MoorDyn [s] | what moorsim said |"
  echo "|---|---|---|---|---|---|---|---|"
else
  echo "| file | import | static | simulate-lines | what moorsim said |"
  echo "|---|---|---|---|---|"
fi
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
    echo "| $name | refused | | |${side_by_side:+ | | |} $said |"
    continue
  fi
  imported=$((imported + 1))
  static=ok simulate=ok said=$( (grep warning "$work/err" || true) | head -1 | sed "s|$tree/||; s/|/\\\\|/g")
  if ! "$moorsim" static "$scenario" >/dev/null 2>"$work/err"; then
    static=failed
    said=$(head -1 "$work/err" | sed "s|$work/||; s/|/\\\\|/g")
  fi
  if ! "$moorsim" simulate-lines "$scenario" --motion surge:1,20 --duration 60 --quiet \
       --output-interval 0.1 --out "$work/ms.csv" >"$work/ms.log" 2>"$work/err"; then
    simulate=failed
    if [[ $static == ok ]]; then said=$(head -1 "$work/err" | sed "s|$work/||; s/|/\\\\|/g"); fi
  fi
  if [[ $static == ok && $simulate == ok ]]; then ran=$((ran + 1)); fi
  if [[ -z $side_by_side ]]; then
    echo "| $name | imported | $static | $simulate | $said |"
    continue
  fi
  rms=- ms_wall=- md_wall=-
  if [[ $simulate == ok ]]; then
    ms_wall=$(sed -n 's/.* in \([0-9.]*\) s wall.*/\1/p' "$work/ms.log")
    # MoorDyn runs a copy of the file's folder, without the file's fileIC option (some of
    # its tests load an initial condition a previous run of theirs wrote; here MoorDyn
    # finds its own, as moorsim does).
    rm -rf "$work/md" && cp -r "$(dirname "$file")" "$work/md"
    copy=$work/md/$(basename "$file")
    grep -viE '^[[:space:]]*[^[:space:]]+[[:space:]]+(fileIC|ICfile)([[:space:]]|$)' "$file" >"$copy"
    if (cd "$work/md" && timeout "${MD_TIMEOUT:-600}" "$work/driver" "$copy" "$work/md.csv" \
         60 0.001 0.1 surge:1,20) >"$work/md.log" 2>&1; then
      md_wall=$(sed -n 's/.* in \([0-9.]*\) s wall.*/\1/p' "$work/md.log")
      rms=$(python3 "$here/moordyn_compare.py" "$copy" "$scenario" "$work/md.csv" "$work/ms.csv" 10)
    else
      md_wall="failed: $( (grep 'moordyn_driver:' "$work/md.log" || echo timeout) | tail -1 |
        sed 's/moordyn_driver: //; s/|/\\|/g')"
    fi
  fi
  echo "| $name | imported | $static | $simulate | $rms | $ms_wall | $md_wall | $said |"
done < <(find "$tree" -type f \( -name '*.txt' -o -name '*.dat' \) | sort)
echo
echo "$total MoorDyn input files: $imported imported ($ran of them ran static and simulate-lines), $refused refused"
