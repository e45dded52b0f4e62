#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Work-precision benchmark of examples/apc6x6.yaml (bench/README.md): the
# error of each output against a tight reference versus the solver's wall
# time, at rtol 1e-4 ... 1e-8 (atol = rtol / 100, the scenario's ratio):
#   System 1: flexbond, the hand-written CVODE program (system1_hand),
#             SciPy's BDF and Radau on the exported descriptor model;
#   System 2: flexbond with the full-order hull and with the reduced hull
#             (80 free-free modes plus residual vectors, --hull-modes 80).
# The references are rtol 1e-10 (atol 1e-12) runs of flexbond for each
# formulation; the reduced hull is also measured against the full-order
# reference. Writes bench/work_precision.csv and bench/work_precision.png.
#
# usage: bench/work_precision.sh [BUILD_DIR]   (from the repository root)
# Needs: cmake and the build's packages, python3-numpy, python3-scipy,
# gnuplot. Each case runs WP_REPEAT times (default 5; System 2:
# WP_REPEAT2, default 3), each run after the machine has been idle for a
# moment (bench/quiet.py, at most QUIET_MAX s, default 5), on one CPU
# (BENCH_CPU, default the last; pinned, OpenBLAS starts no worker thread,
# for flexbond and NumPy alike). The table has the median and the least
# of the times, the plot the least, which other work on a shared machine
# disturbs least. The references run once. WP_RTOLS overrides the list of
# rtols, WP_REF_RTOL the references' rtol.
set -euo pipefail

build=${1:-build}
out=$build/work_precision
py=/usr/bin/python3
repeat=${WP_REPEAT:-5}
repeat2=${WP_REPEAT2:-3}
rtols=${WP_RTOLS:-"1e-4 1e-5 1e-6 1e-7 1e-8"}
ref_rtol=${WP_REF_RTOL:-1e-10}
cpu=${BENCH_CPU:-$(($(nproc) - 1))}

cmake -S . -B "$build" -DFLEXBOND_BENCH_HAND=ON >/dev/null
cmake --build "$build" -j2 --target flexbond_cli system1_hand >/dev/null
exe=$build/flexbond
rm -rf "$out"
mkdir -p "$out"
manifest=$out/manifest.tsv
printf 'system\tformulation\tsolver\trtol\tatol\tcsv\treference\tsolver_seconds\tprocess_seconds\tsteps\trhs_evals\n' >"$manifest"

atol_of() { "$py" -c "import sys; print('%g' % (float(sys.argv[1]) / 100))" "$1"; }

# The scenario with rtol and atol replaced (no other file is named in it).
scenario_at() {
  local rtol=$1 atol=$2 file=$out/apc6x6_rtol$1.yaml
  sed -e "s/^  rtol: .*/  rtol: $rtol/" -e "s/^  atol: .*/  atol: $atol/" \
    examples/apc6x6.yaml >"$file"
  echo "$file"
}

median() { tr ';' '\n' <<<"$1" | sort -g | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }

# add SYSTEM FORMULATION SOLVER RTOL ATOL CSV REFERENCE SOLVER_TIMES PROCESS_TIMES STEPS RHS
# (the times of the runs as a;b;c: wp_table.py takes their median and minimum)
add() {
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" "$5" "$6" "$7" \
    "$8" "$9" "${10}" "${11}" >>"$manifest"
}

# timed CMD...: one run on CPU $cpu (taskset: the machine's CPUs may run at different speeds
# under other work) after the machine has been idle for a moment (bench/quiet.py, at
# most QUIET_MAX s, default 5); its wall time (bench/proctime.py) into $wall, its stderr into $out/stderr.txt.
timed() {
  "$py" bench/quiet.py "${QUIET_MAX:-5}"
  wall=$("$py" bench/proctime.py "$out/stderr.txt" taskset -c "$cpu" "$@")
  wall=${wall%% *}
}

# flexbond run: the solver's own time (summary.json) and the process's.
flexbond_case() { # SYSTEM FORMULATION RTOL RUNS REFERENCE [RUN OPTIONS...]
  local sys=$1 form=$2 rtol=$3 runs=$4 ref=$5
  shift 5
  local atol dir file solver="" process="" stats
  atol=$(atol_of "$rtol")
  dir=$out/$sys-$form-$rtol
  file=$(scenario_at "$rtol" "$atol")
  for ((i = 0; i < runs; ++i)); do
    timed "$exe" run "$file" -o "$dir" --no-figures --plain-header -q "$@"
    process+="${process:+;}$wall"
    stats=$("$py" -c 'import json,sys; s=json.load(open(sys.argv[1]))[sys.argv[2]]["solver"]; print(s["wall_seconds"], s["steps"], s["rhs_evals"])' \
      "$dir/summary.json" "$sys")
    solver+="${solver:+;}${stats%% *}"
  done
  local rest=${stats#* }
  add "$sys" "$form" flexbond "$rtol" "$atol" "$dir/$sys.csv" "$ref" "$solver" "$process" \
    "${rest% *}" "${rest#* }"
  echo "$sys $form flexbond rtol $rtol: solver $(median "$solver") s" >&2
}

hand_case() { # RTOL RUNS REFERENCE
  local rtol=$1 runs=$2 ref=$3 atol solver="" process=""
  atol=$(atol_of "$rtol")
  local csv=$out/system1-hand-$rtol.csv
  for ((i = 0; i < runs; ++i)); do
    timed "$build/system1_hand" -o "$csv" --rtol "$rtol" --atol "$atol"
    process+="${process:+;}$wall"
    solver+="${solver:+;}$(sed -n 's/.*solver \([0-9.]*\) ms.*/\1/p' "$out/stderr.txt" |
      awk '{print $1 / 1000}')"
  done
  local steps rhs
  steps=$(sed -n 's/.* \([0-9]*\) steps.*/\1/p' "$out/stderr.txt")
  rhs=$(sed -n 's/.* \([0-9]*\) rhs evals.*/\1/p' "$out/stderr.txt")
  add system1 rigid "CVODE by hand" "$rtol" "$atol" "$csv" "$ref" "$solver" "$process" "$steps" \
    "$rhs"
  echo "system1 hand rtol $rtol: solver $(median "$solver") s" >&2
}

scipy_case() { # METHOD RTOL RUNS REFERENCE
  local method=$1 rtol=$2 runs=$3 ref=$4 atol solver="" process=""
  atol=$(atol_of "$rtol")
  local csv=$out/system1-scipy-$method-$rtol.csv
  for ((i = 0; i < runs; ++i)); do
    timed "$py" bench/scipy_system1.py "$out/export1" --method "$method" --rtol "$rtol" \
      --atol "$atol" -o "$csv"
    process+="${process:+;}$wall"
    solver+="${solver:+;}$(sed -n 's/^solve_seconds \([0-9.]*\).*/\1/p' "$out/stderr.txt")"
  done
  local rhs
  rhs=$(sed -n 's/.*rhs_evals \([0-9]*\).*/\1/p' "$out/stderr.txt")
  add system1 "descriptor (export)" "SciPy $method" "$rtol" "$atol" "$csv" "$ref" "$solver" \
    "$process" "" "$rhs"
  echo "system1 SciPy $method rtol $rtol: solver $(median "$solver") s" >&2
}

ref1=$out/system1-rigid-$ref_rtol/system1.csv
ref2=$out/system2-full-$ref_rtol/system2.csv
ref2r=$out/system2-reduced80-$ref_rtol/system2.csv

echo "== references (rtol $ref_rtol)" >&2
flexbond_case system1 rigid "$ref_rtol" 1 - --system rigid
flexbond_case system2 full "$ref_rtol" 1 - --system flexible --hull-modes all
flexbond_case system2 reduced80 "$ref_rtol" 1 - --system flexible --hull-modes 80
hand_case "$ref_rtol" 1 "$ref1"

"$exe" export examples/apc6x6.yaml --system rigid -o "$out/export1" >/dev/null
scipy_case Radau "$ref_rtol" 1 "$ref1"

echo "== System 1" >&2
for rtol in $rtols; do
  flexbond_case system1 rigid "$rtol" "$repeat" "$ref1" --system rigid
  hand_case "$rtol" "$repeat" "$ref1"
  scipy_case BDF "$rtol" "$repeat" "$ref1"
  scipy_case Radau "$rtol" "$repeat" "$ref1"
done

echo "== System 2" >&2
for rtol in $rtols; do
  flexbond_case system2 full "$rtol" "$repeat2" "$ref2" --system flexible --hull-modes all
  flexbond_case system2 reduced80 "$rtol" "$repeat2" "$ref2r" --system flexible --hull-modes 80
  # The same runs against the full-order reference: the reduction's own error.
  tail -n 1 "$manifest" | awk -F'\t' -v ref="$ref2" 'BEGIN {OFS = FS} {$2 = "reduced80 vs full"; $7 = ref; print}' \
    >>"$manifest"
done

"$py" bench/wp_table.py "$manifest" bench/work_precision.csv "$out/curves.dat"
blocks=$(grep -c '^"' "$out/curves.dat")
gnuplot -e "data='$out/curves.dat'; out='bench/work_precision.png'; blocks=$blocks" bench/work_precision.gp
echo "wrote bench/work_precision.csv and bench/work_precision.png" >&2
