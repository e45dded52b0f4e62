#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Ride-limiting speeds of the paper's APC, System 1, on 2 threads
# (docs/ride-limit.md, docs/benchmarks.md): two curves of five values,
#   - 6 W of absorbed power on a random course of 5 roughnesses
#     (examples/apc6x6_rough_course.yaml: 256 harmonics; a 100 m course,
#     speeds 10 to 80 km/h, coarse grid every 10 km/h);
#   - the NRMM peak (30 Hz low-pass) against 2.5 g over half-rounds of 5
#     heights with enveloping tires (examples/apc6x6_halfround.yaml; 5 to
#     80 km/h every 5 km/h),
# each to 0.1 km/h, with the figures. Prints each command's wall time per
# run and the median of both together over RUNS runs (default 5).
# Usage: bench/ride_limit.sh [BUILD_DIR] [RUNS]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
exe=${1:-build}/flexbond
runs=${2:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

rough=(ride-limit examples/apc6x6_rough_course.yaml --vary road.iso8608.rms=0.01,0.02,0.03,0.04,0.05
  --metric absorbed_power --course-length 100 --speeds 10:80 --coarse-step 10 -j 2 -q)
bump=(ride-limit examples/apc6x6_halfround.yaml --vary road.halfround.height=0.1,0.15,0.2,0.25,0.3
  --metric nrmm_peak -j 2 -q)

# seconds COMMAND...: the command's wall time, s.
seconds() {
  local t0 t1
  t0=$(date +%s.%N)
  "$exe" "$@" >/dev/null
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}

totals=()
for ((r = 1; r <= runs; ++r)); do
  a=$(seconds "${rough[@]}" -o "$out/rough")
  b=$(seconds "${bump[@]}" -o "$out/bump")
  total=$(echo "$a + $b" | bc -l)
  totals+=("$total")
  printf 'run %d: roughness %.2f s, bump %.2f s, both %.2f s\n' "$r" "$a" "$b" "$total"
done
median=$(printf '%s\n' "${totals[@]}" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }')
printf 'median of %d runs, both commands: %.2f s\n' "$runs" "$median"
cut -d, -f1-4,8 "$out/rough/ride_limit.csv"
cut -d, -f1-4,8 "$out/bump/ride_limit.csv"
