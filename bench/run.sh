#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Reproducible timings (needs hyperfine and GNU time: apt-get install hyperfine
# time, and a build: make build). Usage: bench/run.sh [BUILD_DIR]
# For each case: hyperfine's median wall time of the whole command over
# repeated runs, the solver's own statistics, and the peak resident memory.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
exe=$build/flexbond
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { # hyperfine JSON -> "median X ms (min Y, max Z) over N runs"
  python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["results"][0]; print("median %.2f ms (min %.2f, max %.2f) over %d runs" % (1e3*r["median"], 1e3*r["min"], 1e3*r["max"], len(r["times"])))' "$1"
}

echo "== System 1 (rigid hull), 15 s at 1 kHz: fb_vehicle_simulate, 21 runs in one process"
"$build/bench_vehicle" examples/apc6x6.yaml 21 | tail -n 2

echo "== System 1, whole command: flexbond run --system rigid --no-figures (load, simulate, write CSV + JSON)"
hyperfine -N --warmup 3 --runs 30 --style none --export-json "$out/h.json" \
  "$exe run examples/apc6x6.yaml --system rigid -o $out/run -q --no-figures" >/dev/null
median "$out/h.json"
/usr/bin/time -v "$exe" run examples/apc6x6.yaml --system rigid -o "$out/run" -q --no-figures 2>&1 |
  grep "Maximum resident"

for model in examples/quarter_car.yaml examples/two_dof_fields.yaml; do
  echo "== flexbond sim $model"
  hyperfine -N --warmup 3 --runs 30 --style none --export-json "$out/h.json" \
    "$exe sim $model -o $out/sim -q" >/dev/null
  median "$out/h.json"
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print("solver %.2f ms, %d steps, %d rhs evals, %d factorisations" % (1e3*s["wall_seconds"], s["steps"], s["rhs_evals"], s["factorizations"]))' "$out/sim/stats.json"
  /usr/bin/time -v "$exe" sim "$model" -o "$out/sim" -q 2>&1 | grep "Maximum resident"
done

echo "== System 2 modal analysis: flexbond modes --system flexible -o (hull + vehicle modes, files, pictures)"
hyperfine -N --warmup 1 --runs 10 --style none --export-json "$out/h.json" \
  "$exe modes examples/apc6x6.yaml --system flexible -o $out/modes" >/dev/null
median "$out/h.json"
/usr/bin/time -v "$exe" modes examples/apc6x6.yaml --system flexible -o "$out/modes" 2>&1 >/dev/null |
  grep "Maximum resident"

echo "== System 2, the default basis (hull.fe.modes: auto), 15 s at 1 kHz: fb_vehicle_simulate, 5 runs (peak RSS of one)"
"$build/bench_vehicle" examples/apc6x6.yaml 5 flexible | tail -n 2
/usr/bin/time -v "$build/bench_vehicle" examples/apc6x6.yaml 1 flexible 2>&1 >/dev/null |
  grep "Maximum resident"

echo "== System 2, every mode in modal coordinates (hull.fe.modes: all), 15 s: fb_vehicle_simulate, 3 runs"
sed 's/^\(    modes:\) auto /\1 all /' examples/apc6x6.yaml >"$out/apc6x6_all.yaml"
grep -q '^    modes: all ' "$out/apc6x6_all.yaml" || { echo "run.sh: cannot set hull.fe.modes" >&2; exit 1; }
"$build/bench_vehicle" "$out/apc6x6_all.yaml" 3 flexible | tail -n 2

echo "== The default study, whole command: flexbond run (both systems, the converged mesh, figures, report)"
/usr/bin/time -v "$exe" run examples/apc6x6.yaml -o "$out/study" -q 2>&1 |
  grep -E "Elapsed|Maximum resident"

echo "== flexbond sweep: 12 speeds of System 1 (speed_kmh=5:5:60), whole command with the figure"
hyperfine -N --warmup 1 --runs 10 --style none --export-json "$out/h.json" \
  "$exe sweep examples/apc6x6.yaml --set speed_kmh=5:5:60 -o $out/sweep -q" >/dev/null
median "$out/h.json"
