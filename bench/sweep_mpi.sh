#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Throughput of flexbond sweep on 1 and 2 MPI ranks, and on 1 and 2 threads
# for comparison (docs/cluster.md). Needs hyperfine and the MPI build
# (make mpi). Usage: bench/sweep_mpi.sh [MPI_BUILD_DIR]
#
# The study: System 1 at 48 speeds (5..52 km/h) over a 60 s run instead of
# the example's 15 s, so that a case (about 0.065 s on one thread)
# outweighs handing it out.
# No figure: gnuplot would add the same 0.2 s to every line.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
build=${1:-build-mpi}
exe=$build/flexbond
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
# No OPENBLAS_NUM_THREADS: flexbond sweep runs OpenBLAS on one thread
# itself, in every mode (docs/sweep.md).

sed 's/^  t_end: 15 /  t_end: 60 /' examples/apc6x6.yaml >"$out/study.yaml"
ncases=48
study="sweep $out/study.yaml --set speed_kmh=5:1:52 --no-figures -q"

# line LABEL COMMAND: hyperfine's median over 7 runs (after one warm-up),
# and cases per second.
line() {
  hyperfine -N --warmup 1 --runs 7 --style none --export-json "$out/h.json" \
    --prepare "rm -rf $out/sweep" "$2" >/dev/null
  python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))["results"][0]
n = int(sys.argv[3])
print("%-22s median %6.2f s (min %.2f, max %.2f), %5.1f cases/s" %
      (sys.argv[2], r["median"], r["min"], r["max"], n / r["median"]))' "$out/h.json" "$1" "$ncases"
}

echo "== flexbond sweep, System 1, $ncases cases of 60 s, $(nproc) cores"
line "threads, -j 1" "$exe $study -j 1 -o $out/sweep"
line "threads, -j 2" "$exe $study -j 2 -o $out/sweep"
line "MPI, 1 rank" "mpirun -np 1 $exe $study --mpi -o $out/sweep"
line "MPI, 2 ranks" "mpirun -np 2 $exe $study --mpi -o $out/sweep"

# The same file whichever way it ran.
"$exe" $study -j 2 -o "$out/threads"
mpirun -np 2 "$exe" $study --mpi -o "$out/ranks"
cmp "$out/threads/sweep.csv" "$out/ranks/sweep.csv" && echo "sweep.csv: identical on threads and ranks"
