#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# What running the vehicle through its FMU costs (docs/fmi.md,
# docs/benchmarks.md "The FMU"), on examples/apc6x6.yaml (15 s, sampled
# at 1 kHz):
#   1. Co-Simulation, System 1: the FMU (flexbond fmu --system rigid) run by
#      our own importer (build/fmu_import cs, tests/tools/fmu_import.c) with
#      a 1 ms communication step to 15 s, every output read at each step
#      (the scenario's and the tires' contact forces) and the scenario's
#      written to CSV as `flexbond run` writes them (the same columns and
#      digits: --columns), against `flexbond run --system rigid
#      --no-figures` (the same solver, one run, its CSV at 1 kHz); and the
#      same with every output written (A2). A, A2 and B run in turn, RUNS
#      times each (default 5); the medians of the whole processes' wall and
#      CPU times (bench/proctime.py) and their ratios are printed.
#      Target: A / B <= 1.5.
#   2. Co-Simulation, System 2 on one core (taskset -c 0,
#      OPENBLAS_NUM_THREADS=1): the same 15 s at 1 ms; the median wall time
#      against the 15 s simulated. Target: real time or faster (<= 15 s).
#
# usage: bench/fmu.sh [BUILD_DIR] [RUNS]   (from the repository root)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
runs=${2:-5}
exe=$build/flexbond
imp=$build/fmu_import
py=/usr/bin/python3
[ -x "$exe" ] && [ -x "$imp" ] || { echo "fmu: no $exe or $imp (build first)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# median of the numbers on stdin
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "== exporting System 1 and System 2" >&2
"$exe" fmu examples/apc6x6.yaml --system rigid -o "$out/s1.fmu" -q
"$exe" fmu examples/apc6x6.yaml --system flexible -o "$out/s2.fmu" -q
mkdir "$out/s1" "$out/s2"
(cd "$out/s1" && unzip -q ../s1.fmu) && (cd "$out/s2" && unzip -q ../s2.fmu)

"$exe" run examples/apc6x6.yaml --system rigid --no-figures -q -o "$out/run0"
ncols=$(($(head -1 "$out/run0/system1.csv" | tr ',' '\n' | wc -l) - 1))
: >"$out/a" && : >"$out/a2" && : >"$out/b" && : >"$out/c"
for i in $(seq "$runs"); do
  echo "== run $i of $runs" >&2
  "$py" bench/proctime.py "$out/err" "$imp" --columns "$ncols" cs "$out/s1" 0.001 15 \
    "$out/fmu1.csv" >>"$out/a"
  "$py" bench/proctime.py "$out/err" "$imp" cs "$out/s1" 0.001 15 "$out/fmu1all.csv" >>"$out/a2"
  "$py" bench/proctime.py "$out/err" "$exe" run examples/apc6x6.yaml --system rigid \
    --no-figures -q -o "$out/run1" >>"$out/b"
  OPENBLAS_NUM_THREADS=1 "$py" bench/proctime.py "$out/err" taskset -c 0 \
    "$imp" cs "$out/s2" 0.001 15 "$out/fmu2.csv" >>"$out/c"
done
wa=$(cut -d' ' -f1 "$out/a" | median) && wb=$(cut -d' ' -f1 "$out/b" | median)
ca=$(cut -d' ' -f2 "$out/a" | median) && cb=$(cut -d' ' -f2 "$out/b" | median)
wc=$(cut -d' ' -f1 "$out/c" | median) && cc=$(cut -d' ' -f2 "$out/c" | median)
wa2=$(cut -d' ' -f1 "$out/a2" | median) && ca2=$(cut -d' ' -f2 "$out/a2" | median)
printf 'System 1, 15 s at 1 kHz, %s runs each, medians of the whole process:\n' "$runs"
printf '  FMU, Co-Simulation, 1 ms steps, the run'"'"'s %s columns written: wall %.3f s, cpu %.3f s\n' \
  "$ncols" "$wa" "$ca"
printf '  the same, every output written:  wall %.3f s, cpu %.3f s\n' "$wa2" "$ca2"
printf '  flexbond run --no-figures:        wall %.3f s, cpu %.3f s\n' "$wb" "$cb"
printf '  ratio:                            wall %.3f, cpu %.3f (target <= 1.5); every output: %.3f\n' \
  "$(echo "$wa / $wb" | bc -l)" "$(echo "$ca / $cb" | bc -l)" "$(echo "$wa2 / $wb" | bc -l)"
printf 'System 2, FMU, Co-Simulation, 1 ms steps, one core: wall %.3f s, cpu %.3f s for 15 s (%.1fx real time)\n' \
  "$wc" "$cc" "$(echo "15 / $wc" | bc -l)"
