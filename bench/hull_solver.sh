#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# System 2 on refined hulls against SciPy's eigsh, side by side on the same
# matrices (README "Benchmarks", docs/benchmarks.md "Refined hulls").
#
# For each hull.mesh.density D of examples/apc6x6.yaml (default 3 and 4):
#   - flexbond mesh --export-matrices writes the hull's K.mtx and M.mtx;
#   - A: the whole `flexbond run --system flexible --no-figures` with the
#     default basis (hull.fe.modes: auto), wall time and peak RSS of the
#     process (bench/proctime.py: wait4's rusage);
#   - B: SciPy's eigsh (ARPACK's shift-invert Lanczos with SuperLU) for the
#     101 lowest modes of the same K and M, shifted as flexbond shifts
#     (sigma = -1e-8 trace K / trace M): the eigsh call alone, and its whole
#     Python process (reading the two files included);
#   A and B run in turn, RUNS times each (default 5), and the medians and
#   the ratio A / B are printed. Then the paper's mesh (density 1) and the
#   default study with figures (`flexbond run examples/apc6x6.yaml`).
#
# Needs the build and Debian's /usr/bin/python3 with python3-scipy.
# usage: bench/hull_solver.sh [BUILD_DIR] [RUNS] [DENSITY ...]   (from the repository root)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build}
runs=${2:-5}
shift $(($# > 2 ? 2 : $#))
densities=${*:-3 4}
exe=$build/flexbond
py=/usr/bin/python3
[ -x "$exe" ] || { echo "hull_solver: no $exe (build first)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# eigsh on DIR/K.mtx and DIR/M.mtx: prints the seconds of the call alone.
cat >"$out/eigsh.py" <<'EOF'
import sys, time
import scipy.io, scipy.sparse.linalg as sla
K = scipy.io.mmread(sys.argv[1] + "/K.mtx").tocsc()
M = scipy.io.mmread(sys.argv[1] + "/M.mtx").tocsc()
shift = 1e-8 * K.diagonal().sum() / M.diagonal().sum()
t0 = time.perf_counter()
sla.eigsh(K, k=101, M=M, sigma=-shift, which="LM")
print("%.6f" % (time.perf_counter() - t0))
EOF

# median of the numbers on stdin
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# proc LOG CMD...: one run, "WALL_S CPU_S MAXRSS_KB" appended to LOG
proc() {
  local log=$1
  shift
  "$py" bench/proctime.py "$out/stderr.txt" "$@" >>"$log"
}

for d in $densities; do
  sed "s/^\(    density: \)1 /\1$d /" examples/apc6x6.yaml >"$out/d$d.yaml"
  grep -q "^    density: $d " "$out/d$d.yaml" || { echo "hull_solver: cannot set the density" >&2; exit 1; }
  echo "== density $d: exporting K and M" >&2
  "$exe" mesh "$out/d$d.yaml" --export-matrices "$out/mat$d" >/dev/null
  : >"$out/a$d" && : >"$out/b$d" && : >"$out/call$d"
  for r in $(seq 1 "$runs"); do
    echo "   run $r of $runs: flexbond, then eigsh" >&2
    proc "$out/a$d" "$exe" run "$out/d$d.yaml" --system flexible --no-figures -q -o "$out/run$d"
    "$py" bench/proctime.py "$out/stderr.txt" sh -c "'$py' '$out/eigsh.py' '$out/mat$d' >>'$out/call$d'" >>"$out/b$d"
  done
  a=$(cut -d' ' -f1 "$out/a$d" | median)
  rss=$(cut -d' ' -f3 "$out/a$d" | median)
  b=$(cut -d' ' -f1 "$out/b$d" | median)
  call=$(median <"$out/call$d")
  dofs=$(($(wc -l <"$out/mat$d/dofs.csv") - 1))
  basis=$("$py" -c 'import json,sys; b=json.load(open(sys.argv[1]))["system2"]["hull_basis"]; print("%d coordinates (%d rigid-body modes + %d Ritz vectors in %d blocks), eigen-solve %.3f s" % (b["coordinates_count"], b["kept_modes"], b["static_vectors"], b["ritz_blocks"], b["eigen_seconds"]))' "$out/run$d/summary.json")
  echo "density $d ($dofs DOFs): flexbond run --system flexible --no-figures: median ${a} s, peak RSS $((rss / 1024)) MB; $basis"
  echo "    SciPy eigsh, 101 modes: the call ${call} s, the whole process ${b} s"
  awk -v a="$a" -v c="$call" -v b="$b" 'BEGIN { printf "    ratio: %.3f of the eigsh call, %.3f of its process\n", a / c, a / b }'
done

echo "== the paper's mesh and the default study" >&2
: >"$out/p1" && : >"$out/study"
for r in $(seq 1 "$runs"); do
  proc "$out/p1" "$exe" run examples/apc6x6.yaml --system flexible --no-figures -q -o "$out/p1run"
  proc "$out/study" "$exe" run examples/apc6x6.yaml -q -o "$out/studyrun"
done
echo "density 1: flexbond run --system flexible --no-figures: median $(cut -d' ' -f1 "$out/p1" | median) s"
echo "default study, flexbond run examples/apc6x6.yaml (figures, converged mesh): median $(cut -d' ' -f1 "$out/study" | median) s, peak RSS $(($(cut -d' ' -f3 "$out/study" | median) / 1024)) MB"
