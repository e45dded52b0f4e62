#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond sweep --mpi (docs/cluster.md), in an MPI build: a study with
# failing cases (a solver failure and a value the reader refuses) on 3
# ranks writes the same sweep.csv, byte for byte, as on threads in one
# process, with every other case complete and the cases spread over the
# ranks; 1 rank does too; so does a System 2 study on 2 ranks bound to a
# core each (one BLAS thread everywhere); a sweep killed on threads
# resumes on 2 ranks to the same file; ranks that read other scenario
# files, or other damper tables beside the same one, are refused before
# any case runs; a usage error is said once, not once per rank; -j is
# refused with --mpi.
#
# usage: MPIEXEC=mpiexec bash tests/mpi/cli_sweep_mpi.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_sweep_mpi
# shellcheck source=../clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/../clilib.sh"

MPIEXEC=${MPIEXEC:-mpiexec}
# OpenMPI refuses to start as root unless told (CI runs as root).
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
# mpirun NP ARGS...: flexbond ARGS on NP ranks (more than the cores: a
# test machine may have 2); sets $status.
mpirun_flexbond() {
  local np=$1
  shift
  "$MPIEXEC" -np "$np" --oversubscribe "$FLEXBOND" "$@" >"$OUT" 2>"$ERR"
  status=$?
}

# The example with a step budget in the file, so that --set can lower it.
sed 's/^  max_step: 0 .*/  max_step: 0\n  max_steps: 10000000/' "$REPO_ROOT/examples/apc6x6.yaml" \
  >"$WORK/apc.yaml"
# 2 x 5 cases: 30 steps are too few (a solver failure, exit 4), and 'fast'
# is no speed (the reader's error).
STUDY=(sweep "$WORK/apc.yaml" --set max_steps=10000000,30 --set speed_kmh=5,10,fast,20,25
  --no-figures)

run "${STUDY[@]}" -j 2 -o "$WORK/threads" -q
expect_status 4 "threads: the study with failing cases"

mpirun_flexbond 3 "${STUDY[@]}" --mpi -o "$WORK/ranks3"
expect_status 4 "3 ranks: the study with failing cases"
checks=$((checks + 1))
cmp -s "$WORK/threads/sweep.csv" "$WORK/ranks3/sweep.csv" ||
  fail "3 ranks and threads write different sweep.csv files"
for rank in 0 1 2; do
  expect_in "$ERR" "ok on rank $rank" "rank $rank ran a case"
done
expect_in "$ERR" "10 cases (0 resumed), 6 failed" "3 ranks: summary"
checks=$((checks + 1))
[ "$(ls -A "$WORK/ranks3" | tr '\n' ' ')" = ".flexbond-manifest sweep.csv " ] ||
  fail "3 ranks: only sweep.csv is left"
checks=$((checks + 1))
python3 - "$WORK/ranks3/sweep.csv" <<'EOF' || fail "3 ranks: the rows"
import csv, sys
# Columns by name, without the units of the header ("speed_kmh [km/h]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
assert len(rows) == 10
for r in rows:
    if r["speed_kmh"] == "fast":
        assert "expression 'fast'" in r["error"], r["error"]
    elif r["max_steps"] == "30":
        assert "CV_TOO_MUCH_WORK" in r["error"], r["error"]
    else:
        # The four good cases are complete.
        assert r["error"] == "" and float(r["tire_force_LF_peak"]) > 14000, r
EOF

mpirun_flexbond 1 "${STUDY[@]}" --mpi -o "$WORK/ranks1" -q
expect_status 4 "1 rank"
checks=$((checks + 1))
cmp -s "$WORK/threads/sweep.csv" "$WORK/ranks1/sweep.csv" || fail "1 rank and threads differ"

# ---- System 2 (a reduced hull over a short run: the last wheel leaves
# the bump at 8.132 s) on threads and on 2 ranks, each rank bound to one
# core (mpirun's default for 2 ranks, which is why --oversubscribe is left
# out where there are 2 cores): the same file. OpenBLAS
# sizes its thread pool from the CPUs a process may use, 2 in the
# threaded sweep and 1 in a bound rank, and with another pool size the
# dense eigen-solution of the reduced hull rounds otherwise, in every
# metric: the sweep runs BLAS on one thread in every mode (docs/sweep.md).
FLEX=(sweep "$WORK/apc.yaml" --system flexible --set hull.fe.modes=20 --set simulation.t_end=9
  --set speed_kmh=10,12,14 --no-figures)
run "${FLEX[@]}" -j 2 -o "$WORK/flex_threads" -q
expect_status 0 "System 2 on threads"
if [ "$(nproc)" -ge 2 ]; then
  "$MPIEXEC" -np 2 "$FLEXBOND" "${FLEX[@]}" --mpi -o "$WORK/flex_ranks" >"$OUT" 2>"$ERR"
  status=$?
else
  mpirun_flexbond 2 "${FLEX[@]}" --mpi -o "$WORK/flex_ranks"
fi
expect_status 0 "System 2 on 2 ranks"
for rank in 0 1; do
  expect_in "$ERR" "ok on rank $rank" "System 2: rank $rank ran a case"
done
checks=$((checks + 1))
cmp -s "$WORK/flex_threads/sweep.csv" "$WORK/flex_ranks/sweep.csv" ||
  fail "System 2: 2 bound ranks and threads write different sweep.csv files"

# ---- Killed on threads, resumed on 2 ranks. A longer run (60 s) makes a
# case last about 0.1 s, so the kill lands in the middle.
sed 's/^  t_end: 15 /  t_end: 60 /' "$WORK/apc.yaml" >"$WORK/long.yaml"
LONG=(sweep "$WORK/long.yaml" --set speed_kmh=6:4:50 --no-figures)
run "${LONG[@]}" -o "$WORK/long_ref" -q
expect_status 0 "the long study"
"$FLEXBOND" "${LONG[@]}" -j 1 -o "$WORK/long" -q &
pid=$!
waited=0
# rows: the case rows in the journal so far.
rows() {
  local n
  n=$(grep -c '^[0-9]' "$WORK/long/sweep.partial.csv" 2>/dev/null) || n=0
  echo "$n"
}
while [ "$(rows)" -lt 3 ] && [ "$waited" -lt 600 ]; do
  sleep 0.02
  waited=$((waited + 1))
done
kill -KILL "$pid"
wait "$pid" 2>/dev/null
done_before=$(rows)
mpirun_flexbond 2 "${LONG[@]}" --mpi --resume -o "$WORK/long"
expect_status 0 "resumed on 2 ranks"
expect_in "$ERR" "resuming: $done_before of 12 cases are done" "2 ranks: resuming"
checks=$((checks + 1))
cmp -s "$WORK/long_ref/sweep.csv" "$WORK/long/sweep.csv" ||
  fail "killed on threads and resumed on 2 ranks: sweep.csv differs"

# ---- One worker interrupted (SIGINT to rank 1 alone): it runs no more
# cases, the others run the rest, and the one it dropped is left for
# --resume.
rm -rf "$WORK/long"
"$MPIEXEC" -np 3 --oversubscribe "$FLEXBOND" "${LONG[@]}" --mpi -o "$WORK/long" >"$OUT" 2>"$ERR" &
pid=$!
waited=0
while [ "$(rows)" -lt 2 ] && [ "$waited" -lt 600 ]; do
  sleep 0.02
  waited=$((waited + 1))
done
signalled=0
for p in $(pgrep -f -- "--mpi -o $WORK/long"); do
  if tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then
    kill -INT "$p" && signalled=$((signalled + 1))
  fi
done
checks=$((checks + 1))
[ "$signalled" -eq 1 ] || fail "rank 1 interrupted: $signalled processes signalled"
wait "$pid"
status=$?
expect_status 130 "rank 1 interrupted"
expect_in "$ERR" "1 case did not run (a rank was interrupted); 11 of 12 cases are done" \
  "rank 1 interrupted: the others ran the rest"
mpirun_flexbond 2 "${LONG[@]}" --mpi --resume -o "$WORK/long"
expect_status 0 "resumed after rank 1 was interrupted"
checks=$((checks + 1))
cmp -s "$WORK/long_ref/sweep.csv" "$WORK/long/sweep.csv" ||
  fail "rank 1 interrupted, resumed: sweep.csv differs"

# ---- Refusals before any case runs end every rank (a worker waiting for
# a case would hang the job): a journal without --resume, and ranks that
# read different scenario files (MPMD: rank 0 one file, ranks 1-2 a
# copy with one byte changed).
mkdir -p "$WORK/left"
echo junk >"$WORK/left/sweep.partial.csv"
"$MPIEXEC" -np 3 --oversubscribe timeout 120 "$FLEXBOND" "${STUDY[@]}" --mpi -o "$WORK/left" \
  >"$OUT" 2>"$ERR"
status=$?
expect_status 1 "3 ranks, a journal left without --resume"
expect_in "$ERR" "an earlier sweep into this directory stopped" "a journal without --resume"
sed 's/^# /#  /' "$WORK/apc.yaml" >"$WORK/apc_other.yaml"
"$MPIEXEC" --oversubscribe -np 1 timeout 120 "$FLEXBOND" "${STUDY[@]}" --mpi -o "$WORK/mpmd" : \
  -np 2 timeout 120 "$FLEXBOND" sweep "$WORK/apc_other.yaml" "${STUDY[@]:2}" --mpi \
  -o "$WORK/mpmd" >"$OUT" 2>"$ERR"
status=$?
expect_status 5 "ranks with different scenario files"
expect_in "$ERR" "rank 1 could not set the study up, or read another scenario file than rank 0 or other files it names" \
  "ranks with different scenario files: message"
expect_absent "$WORK/mpmd" "ranks with different scenario files"
# The same scenario text, but ranks 1-2 see another damper table beside it
# (a node with a stale copy): refused in the same way.
for node in a b; do
  mkdir -p "$WORK/node_$node"
  cp "$REPO_ROOT/examples/apc6x6_shock_table.yaml" "$REPO_ROOT/examples/shock_front.csv" \
    "$REPO_ROOT/examples/shock_rear.csv" "$WORK/node_$node/"
done
awk -F, 'BEGIN { OFS = "," } /^[-0-9.]/ { $2 = 2 * $2 } { print }' \
  "$WORK/node_a/shock_rear.csv" >"$WORK/node_b/shock_rear.csv"
checks=$((checks + 1))
! cmp -s "$WORK/node_a/shock_rear.csv" "$WORK/node_b/shock_rear.csv" || fail "node b's table is not changed"
TABLE=(--set speed_kmh=10,20 --no-figures --mpi -o "$WORK/tables")
"$MPIEXEC" --oversubscribe -np 1 timeout 120 "$FLEXBOND" sweep "$WORK/node_a/apc6x6_shock_table.yaml" \
  "${TABLE[@]}" : -np 2 timeout 120 "$FLEXBOND" sweep "$WORK/node_b/apc6x6_shock_table.yaml" \
  "${TABLE[@]}" >"$OUT" 2>"$ERR"
status=$?
expect_status 5 "ranks with different damper tables"
expect_in "$ERR" "rank 1 could not set the study up, or read another scenario file than rank 0 or other files it names" \
  "ranks with different damper tables: message"
expect_absent "$WORK/tables" "ranks with different damper tables"

# ---- Usage errors: once, from rank 0.
mpirun_flexbond 3 sweep "$WORK/apc.yaml" --mpi --set sped_kmh=5 -o "$WORK/usage"
expect_status 1 "a usage error on 3 ranks"
checks=$((checks + 1))
[ "$(grep -c "no key 'sped_kmh'" "$ERR")" -eq 1 ] || fail "the usage error is said once"
expect_absent "$WORK/usage" "a usage error on 3 ranks"
mpirun_flexbond 2 "${STUDY[@]}" --mpi -j 2 -o "$WORK/usage"
expect_status 1 "-j with --mpi"
expect_in "$ERR" "--mpi runs one case per rank at a time" "-j with --mpi: message"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
