#!/usr/bin/env bash
# Reproducible timings of the flexbond command (needs hyperfine and GNU time:
# apt-get install hyperfine time). Usage: bench/run.sh [BUILD_DIR]
# Prints hyperfine's median wall time over repeated runs, the solver's own
# statistics, and the peak resident memory of one run.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
exe=$build/flexbond
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for model in examples/quarter_car.yaml examples/two_dof_fields.yaml; do
  echo "== $model"
  hyperfine --warmup 3 --runs 30 --style basic --export-json "$out/h.json" \
    "$exe sim $model -o $out/run -q" >/dev/null
  python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))["results"][0]; print("median wall %.2f ms (min %.2f, max %.2f) over %d runs" % (1e3*r["median"], 1e3*r["min"], 1e3*r["max"], len(r["times"])))' "$out/h.json"
  cat "$out/run/stats.json"
  echo
  /usr/bin/time -v "$exe" sim "$model" -o "$out/run" -q 2>&1 | grep "Maximum resident"
done
