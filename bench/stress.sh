#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# What System 2's hull stresses cost a run (docs/stresses.md "Over a run",
# docs/benchmarks.md "Hull stresses over a run"): examples/apc6x6.yaml at
# hull.mesh.density D (default 3: 2160 elements),
#   - A: `flexbond run --system flexible --no-figures` (the stresses on, as
#     by default), B: the same with --no-stress; A and B run in turn, RUNS
#     times each (default 5), each run's wall and CPU time and peak RSS of
#     the whole process (bench/proctime.py: wait4's rusage); the medians and
#     the ratio of the medians A / B are printed;
#   - then one run with -v, whose lines say the simulation's own seconds
#     and the stress recovery's (elements, samples, coordinates, seconds).
#
# usage: bench/stress.sh [BUILD_DIR] [RUNS] [DENSITY]   (from the repository root)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
runs=${2:-5}
density=${3:-3}
exe=$build/flexbond
py=/usr/bin/python3
[ -x "$exe" ] || { echo "stress: no $exe (build first)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# median of the numbers on stdin
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

sed "s/^\(    density: \)1 /\1$density /" examples/apc6x6.yaml >"$out/d.yaml"
grep -q "^    density: $density " "$out/d.yaml" || { echo "stress: cannot set the density" >&2; exit 1; }
run=("$exe" run "$out/d.yaml" --system flexible --no-figures -q)
: >"$out/a" && : >"$out/b"
for i in $(seq "$runs"); do
  echo "== run $i of $runs" >&2
  "$py" bench/proctime.py "$out/stderr.txt" "${run[@]}" -o "$out/with" >>"$out/a"
  "$py" bench/proctime.py "$out/stderr.txt" "${run[@]}" -o "$out/without" --no-stress >>"$out/b"
done
wa=$(cut -d' ' -f1 "$out/a" | median) && wb=$(cut -d' ' -f1 "$out/b" | median)
ca=$(cut -d' ' -f2 "$out/a" | median) && cb=$(cut -d' ' -f2 "$out/b" | median)
ra=$(cut -d' ' -f3 "$out/a" | median) && rb=$(cut -d' ' -f3 "$out/b" | median)
printf 'density %s, %s runs each, medians of the whole process:\n' "$density" "$runs"
printf '  with the stresses:  wall %.3f s, cpu %.3f s, peak %.0f MiB\n' "$wa" "$ca" "$(echo "$ra / 1024" | bc -l)"
printf '  --no-stress:        wall %.3f s, cpu %.3f s, peak %.0f MiB\n' "$wb" "$cb" "$(echo "$rb / 1024" | bc -l)"
printf '  ratio:              wall %.3f, cpu %.3f\n' "$(echo "$wa / $wb" | bc -l)" "$(echo "$ca / $cb" | bc -l)"
echo "inside one run (-v):"
"${run[@]/-q/-v}" -o "$out/verbose" 2>&1 | grep -E "samples, [0-9]+ steps|hull stresses of" | sed 's/^/  /'
