#!/usr/bin/env bash
# moorsim's line model side by side with MoorDyn v2 on the same two moorings, the same
# prescribed fairlead motion and the same output: accuracy against tight references of
# both programs, and wall time.
#
#   benchmarks/moordyn_side_by_side.sh MOORDYN MOORSIM
#
# MOORDYN is a MoorDyn v2 install prefix (include/moordyn/MoorDyn2.h), a configured and
# built MoorDyn build directory (installed into a temporary folder), or a MoorDyn source
# tree (built there, Release, without wrappers; takes a few minutes). MOORSIM is the
# moorsim binary; nothing of moorsim is built. Environment: CPU (the core the timed runs
# are pinned to with taskset, default 1), RUNS (timed runs per setting, median; default 3),
# KEEP=1 to keep the work folder (MoorDyn files, scenarios, CSVs).
#
# What it does, in a temporary folder: writes the two MoorDyn input files (below),
# compiles benchmarks/moordyn_driver.cc against MoorDyn, imports each file with `moorsim
# import moordyn` (so both programs run literally the same model), and runs
#   * moorsim simulate-lines: reference (--tolerance-scale 0.001, rtol 1e-7), its default
#     solver settings and two tighter ones;
#   * MoorDyn through the driver: reference (RK4, dtM 1 ms, coupled every 1 ms) and the
#     time schemes and steps listed in md_settings below (each step near the largest the
#     scheme ran stably in our trials; larger ones diverged).
# Motion of every fairlead: surge 5 m at 100 s plus heave 2 m at 12 s, 600 s, tensions at
# 10 Hz. Accuracy: per line, the RMS difference of the fairlead tension over t >= 100 s as
# a % of the reference's range there; the table gives the worst of the 8 lines. Time: the
# stepping alone (moorsim's figure after its static start; the driver's loop after
# MoorDyn_Init), median of RUNS runs on one core. MoorDyn's code stays outside the project.
set -euo pipefail
usage="usage: benchmarks/moordyn_side_by_side.sh MOORDYN_PREFIX|BUILD_DIR|SOURCE_TREE MOORSIM"
md_arg=${1:?$usage}
moorsim=${2:?$usage}
cpu=${CPU:-1}
runs=${RUNS:-3}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
moorsim=$(cd "$(dirname "$moorsim")" && pwd)/$(basename "$moorsim")
[[ -x $moorsim ]] || { echo "not an executable: $moorsim" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/moordyn_sbs.XXXXXX")
if [[ -n ${KEEP:-} ]]; then
  echo "work folder: $work" >&2
else
  trap 'rm -rf "$work"' EXIT
fi
cd "$work"

duration=${DURATION:-600}  # DURATION: a shorter run, e.g. 150 for a smoke test
output_interval=0.1
from=100
motion=(surge:5,100 heave:2,12)

# --- MoorDyn: find or make an install ---------------------------------------------------
if [[ -f $md_arg/include/moordyn/MoorDyn2.h ]]; then
  prefix=$md_arg
elif [[ -f $md_arg/CMakeCache.txt ]]; then
  cmake --install "$md_arg" --prefix "$work/moordyn" >/dev/null
  prefix=$work/moordyn
elif [[ -f $md_arg/source/MoorDyn2.h ]]; then
  echo "building MoorDyn from $md_arg ..." >&2
  cmake -S "$md_arg" -B "$work/moordyn-build" -DCMAKE_BUILD_TYPE=Release -DPYTHON_WRAPPER=OFF \
    -DFORTRAN_WRAPPER=OFF -DMATLAB_WRAPPER=OFF -DRUST_WRAPPER=OFF -DBUILD_DOCS=OFF \
    -DBUILD_TESTING=OFF >"$work/moordyn-config.log" 2>&1
  cmake --build "$work/moordyn-build" -j2 >"$work/moordyn-build.log" 2>&1
  cmake --install "$work/moordyn-build" --prefix "$work/moordyn" >/dev/null
  prefix=$work/moordyn
else
  echo "$md_arg: neither a MoorDyn install prefix, build folder nor source tree" >&2
  exit 2
fi
libdir=$(dirname "$(ls "$prefix"/lib*/libmoordyn.so* | head -1)")
md_version=$(sed -n 's/.*MOORDYN_VERSION_STRING "\(.*\)".*/\1/p' "$prefix"/include/moordyn/Config.h \
  2>/dev/null | head -1)
${CXX:-c++} -O2 -std=c++17 -o driver "$here/moordyn_driver.cc" -I"$prefix/include" \
  -L"$libdir" -lmoordyn -Wl,-rpath,"$libdir"

# --- the models, in MoorDyn's v2 format (z up, y to port; anchors at z = -depth) ---------
# seed: scenarios/library/seed_tapm.yaml's eight 2250 m chains (50 segments), frictionless
#   seabed (MoorDyn-C's friction is a velocity damping, not Coulomb friction).
# composite: the same field with chain 400 m (16) + polyester 1650 m (30) + chain 150 m (6)
#   and a 20 t clump weight (2.55 m^3) where the bottom chain meets the rope
#   (scenarios/library/composite_line6.yaml's line).
# Tangential drag: moorsim's C_DT acts on d, MoorDyn's CdAx on pi d: CdAx = C_DT / pi.
write_moordyn() {  # MODEL TSCHEME DTM FILE
  local model=$1 scheme=$2 dtm=$3 file=$4 i
  {
    echo "--------------------- MoorDyn Input File ------------------------------------"
    echo "moorsim side-by-side benchmark, model '$model' (8 lines, 1000 m of water)"
    echo "----------------------- LINE TYPES ------------------------------------------"
    echo "TypeName   Diam   Mass/m  EA          BA/-zeta  EI  Cd   Ca   CdAx            CaAx"
    echo "(name)     (m)    (kg/m)  (N)         (N-s/-)   (-) (-)  (-)  (-)             (-)"
    echo "chain      0.08   275     2.28785e8   -0.5      0   0.3  1.5  0.3183098862    0.0"
    [[ $model == composite ]] &&
      echo "polyester  0.2    40      2.0e8       -0.5      0   1.2  1.0  0.002546479089  0.0"
    echo "---------------------- POINT PROPERTIES -------------------------------------"
    echo "ID  Type     X            Y            Z      Mass    Volume  CdA   Ca"
    echo "(#) (-)      (m)          (m)          (m)    (kg)    (m^3)   (m^2) (-)"
    awk -v model="$model" 'function z(v) { return v * v < 1e-20 ? 0 : v }
    BEGIN {
      split("0 90 180 270 45 135 225 315", b, " ")  # seed_tapm.yaml line order, NED bearings
      pi = atan2(0, -1); id = 0
      for (i = 1; i <= 8; ++i) {
        c = cos(b[i] * pi / 180); s = sin(b[i] * pi / 180)
        ax[i] = z(b[i] % 90 ? (c > 0 ? 1378.9 : -1378.9) : 1950 * c)
        ay[i] = z(b[i] % 90 ? (s > 0 ? 1378.9 : -1378.9) : 1950 * s)
        fx[i] = z(20 * c); fy[i] = z(20 * s)
      }
      # MoorDyn (x, y, z) = moorsim (x, -y, -z).
      for (i = 1; i <= 8; ++i) printf "%-3d Fixed    %-12.6f %-12.6f -1000  0       0       0     0\n", ++id, ax[i], z(-ay[i])
      for (i = 1; i <= 8; ++i) printf "%-3d Coupled  %-12.9f %-12.9f -12    0       0       0     0\n", ++id, fx[i], z(-fy[i])
      if (model == "composite") {  # first guesses; MoorDyn finds the free points at rest
        for (i = 1; i <= 8; ++i) printf "%-3d Free     %-12.6f %-12.6f -995   20000   2.55    2.0   1.0\n", ++id, z(0.79 * ax[i]), z(-0.79 * ay[i])
        for (i = 1; i <= 8; ++i) printf "%-3d Free     %-12.6f %-12.6f -110   0       0       0     0\n", ++id, z(0.07 * ax[i]), z(-0.07 * ay[i])
      }
    }'
    echo "---------------------- LINES ------------------------------------------------"
    echo "ID  LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs"
    echo "(#) (name)     (#)      (#)      (m)       (-)      (-)"
    for i in 1 2 3 4 5 6 7 8; do
      if [[ $model == seed ]]; then
        echo "$i   chain      $i        $((8 + i))       2250      50       -"
      else
        echo "$i   chain      $i        $((16 + i))       400       16       -"
      fi
    done
    if [[ $model == composite ]]; then
      for i in 1 2 3 4 5 6 7 8; do
        echo "$((8 + i))   polyester  $((16 + i))       $((24 + i))       1650      30       -"
      done
      for i in 1 2 3 4 5 6 7 8; do
        echo "$((16 + i))   chain      $((24 + i))       $((8 + i))        150       6        -"
      done
    fi
    echo "---------------------- OPTIONS ----------------------------------------------"
    echo "$dtm    dtM            mooring time step (s)"
    echo "$scheme    tScheme        time scheme"
    echo "1000     WtrDpth        water depth (m)"
    echo "1025     WtrDnsty       water density (kg/m^3)"
    echo "9.81     g              gravity (m/s^2)"
    echo "3.0e6    kBot           seabed stiffness (Pa/m)"
    echo "3.0e5    cBot           seabed damping (Pa s/m)"
    echo "1.0      dtIC           IC convergence window (s)"
    echo "600      TmaxIC         IC time limit (s)"
    echo "1e-6     threshIC       IC relative tolerance (-)"
    echo "0        writeLog       no log file"
    echo "1        disableOutput  quiet"
    echo "1        disableOutTime quiet"
    echo "------------------------- need this line ------------------------------------"
  } >"$file"
}

# MoorDyn settings timed per model: "SCHEME DTM COUPLING_DT" (the coupling interval must be
# >= dtM: MoorDyn never steps past it; OUTPUT_INTERVAL a multiple of it).
md_settings() {
  case $1 in
    seed) printf '%s\n' "RK2 0.002 0.01" "RK2 0.02 0.02" "Euler 0.002 0.01" "heun 0.01 0.01" \
      "RK4 0.0333333333333 0.0333333333333" "midpoint2 0.025 0.025" ;;
    composite) printf '%s\n' "RK2 0.002 0.01" "RK2 0.02 0.02" "Euler 0.002 0.01" \
      "heun 0.01 0.01" "RK4 0.025 0.025" "midpoint2 0.025 0.025" "midpoint5 0.05 0.05" ;;
  esac
}
md_reference="RK4 0.001 0.001"
# moorsim settings: --tolerance-scale (1 = the scenario's solver settings, rtol 1e-4).
ms_settings="1 0.5 0.1"
ms_reference=0.001

# Worst line's RMS difference (t >= from) as % of the reference's range, or "-".
compare() {  # REF.csv TEST.csv
  [[ -s $1 && -s $2 ]] || { echo "-"; return; }
  awk -F, -v t0="$from" '
    /^#/ || /^time/ { next }
    FNR == NR { if ($1 + 0 >= t0 - 1e-9) { k = sprintf("%.3f", $1); for (i = 2; i <= NF; ++i) r[k, i] = $i; nc = NF }; next }
    $1 + 0 >= t0 - 1e-9 {
      k = sprintf("%.3f", $1); if (!((k, 2) in r)) next; ++n
      for (i = 2; i <= nc; ++i) {
        d = $i - r[k, i]; s[i] += d * d
        if (n == 1 || r[k, i] > hi[i]) hi[i] = r[k, i]
        if (n == 1 || r[k, i] < lo[i]) lo[i] = r[k, i]
      }
    }
    END {
      if (n < 100) { print "-"; exit }
      w = 0; for (i = 2; i <= nc; ++i) { e = 100 * sqrt(s[i] / n) / (hi[i] - lo[i]); if (e > w) w = e }
      printf "%.2f", w
    }' "$1" "$2"
}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR) printf "%.2f", v[int((NR + 1) / 2)] }'; }

run_moorsim() {  # SCENARIO SCALE OUT.csv -> stepping wall [s]
  taskset -c "$cpu" "$moorsim" simulate-lines "$1" "${motion[@]/#/--motion=}" \
    --duration "$duration" --output-interval "$output_interval" --tolerance-scale "$2" \
    --out "$3" --quiet | sed -n 's/.* in \([0-9.]*\) s wall.*/\1/p'
}

run_moordyn() {  # MODEL SCHEME DTM DTC OUT.csv -> stepping wall [s]; status in OUT.err
  local file=${5%.csv}.txt
  write_moordyn "$1" "$2" "$3" "$file"
  if taskset -c "$cpu" ./driver "$file" "$5" "$duration" "$4" "$output_interval" "${motion[@]}" \
       >"${5%.csv}.log" 2>&1; then
    sed -n 's/.* in \([0-9.]*\) s wall.*/\1/p' "${5%.csv}.log"
  else
    grep 'moordyn_driver:' "${5%.csv}.log" | tail -1 | sed 's/moordyn_driver: //' >"${5%.csv}.err"
    rm -f "$5"
  fi
}

echo "MoorDyn ${md_version:-2} ($prefix), moorsim $("$moorsim" --version 2>/dev/null | head -1)" >&2
echo "$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); timed runs pinned to core $cpu, median of $runs" >&2
declare -A best_ms best_md
rows=()
# The same rows for plotting (benchmarks/plot_moordyn_side_by_side.py, with KEEP=1).
echo "model,program,setting,wall_s,rms_vs_moorsim_ref_pct,rms_vs_moordyn_ref_pct,csv" >results.csv
result() { (IFS=,; echo "$*") >>results.csv; }  # MODEL PROGRAM SETTING WALL MS MD CSV
for model in seed composite; do
  write_moordyn "$model" RK2 0.002 "$model.txt"
  "$moorsim" import moordyn "$model.txt" --out "$model.yaml" >/dev/null
  echo "$model: references ..." >&2
  ms_ref=ms_${model}_ref.csv md_ref=md_${model}_ref.csv
  ms_ref_wall=$(run_moorsim "$model.yaml" "$ms_reference" "$ms_ref")
  read -r s d c <<<"$md_reference"
  md_ref_wall=$(run_moordyn "$model" "$s" "$d" "$c" "$md_ref")
  [[ -s $md_ref ]] || { echo "MoorDyn reference failed: $(cat "${md_ref%.csv}.err")" >&2; exit 1; }
  ms_vs_md=$(compare "$md_ref" "$ms_ref") md_vs_ms=$(compare "$ms_ref" "$md_ref")
  rows+=("| $model | moorsim | reference: rtol 1e-7 (tolerance scale $ms_reference) | $ms_ref_wall (1 run) | - | $ms_vs_md |")
  rows+=("| $model | MoorDyn | reference: $s, dtM $d s, coupling $c s | $md_ref_wall (1 run) | $md_vs_ms | - |")
  result "$model" moorsim reference "$ms_ref_wall" 0 "$ms_vs_md" "$ms_ref"
  result "$model" MoorDyn reference "$md_ref_wall" "$md_vs_ms" 0 "$md_ref"
  best_ms[$model]="" best_md[$model]=""
  for scale in $ms_settings; do
    echo "$model: moorsim tolerance scale $scale ..." >&2
    out=ms_${model}_$scale.csv walls=()
    for ((r = 0; r < runs; ++r)); do walls+=("$(run_moorsim "$model.yaml" "$scale" "$out")"); done
    wall=$(printf '%s\n' "${walls[@]}" | median)
    own=$(compare "$ms_ref" "$out") other=$(compare "$md_ref" "$out")
    rtol=$(awk -v s="$scale" 'BEGIN { printf "%g", 1e-4 * s }')
    label="rtol $rtol"; [[ $scale == 1 ]] && label="default (rtol 1e-4, atol 1e-3)"
    rows+=("| $model | moorsim | $label | $wall | $own | $other |")
    result "$model" moorsim "rtol $rtol" "$wall" "$own" "$other" "$out"
    if awk -v e="$own" 'BEGIN { exit !(e <= 1.0) }'; then
      if [[ -z ${best_ms[$model]} ]] ||
         awk -v a="$wall" -v b="${best_ms[$model]##*|}" 'BEGIN { exit !(a < b) }'; then
        best_ms[$model]="$label|$wall"
      fi
    fi
  done
  while read -r s d c; do
    echo "$model: MoorDyn $s dtM $d ..." >&2
    out=md_${model}_${s}_$d.csv walls=()
    for ((r = 0; r < runs; ++r)); do
      w=$(run_moordyn "$model" "$s" "$d" "$c" "$out")
      [[ -n $w ]] || break
      walls+=("$w")
    done
    label="$s, dtM $(printf '%.3g' "$d") s, coupling $(printf '%.3g' "$c") s"
    if [[ ! -s $out ]]; then
      rows+=("| $model | MoorDyn | $label | failed: $(cat "${out%.csv}.err") | - | - |")
      continue
    fi
    wall=$(printf '%s\n' "${walls[@]}" | median)
    own=$(compare "$md_ref" "$out") other=$(compare "$ms_ref" "$out")
    rows+=("| $model | MoorDyn | $label | $wall | $other | $own |")
    result "$model" MoorDyn "$s dtM $(printf '%.3g' "$d") s" "$wall" "$other" "$own" "$out"
    if awk -v e="$own" 'BEGIN { exit !(e <= 1.0) }'; then
      if [[ -z ${best_md[$model]} ]] ||
         awk -v a="$wall" -v b="${best_md[$model]##*|}" 'BEGIN { exit !(a < b) }'; then
        best_md[$model]="$label|$wall"
      fi
    fi
  done < <(md_settings "$model")
done

echo
echo "| model | program | setting | wall [s] | RMS vs moorsim ref. [%] | RMS vs MoorDyn ref. [%] |"
echo "|---|---|---|---:|---:|---:|"
printf '%s\n' "${rows[@]}"
echo
echo "Accuracy: worst of the 8 lines' RMS fairlead-tension difference over t = $from..$duration s, % of"
echo "the reference's range. Wall: stepping only (no static start / MoorDyn_Init), median of $runs."
for model in seed composite; do
  ms=${best_ms[$model]:-} md=${best_md[$model]:-}
  if [[ -n $ms && -n $md ]]; then
    ratio=$(awk -v a="${md##*|}" -v b="${ms##*|}" 'BEGIN { printf "%.1f", a / b }')
    echo "$model: fastest within 1 % of its own reference: moorsim ${ms%|*} ${ms##*|} s," \
      "MoorDyn ${md%|*} ${md##*|} s; MoorDyn / moorsim wall time $ratio"
  else
    echo "$model: moorsim ${ms:-none} / MoorDyn ${md:-none} within 1 % of its own reference"
  fi
done
