#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond ride-limit --mpi (docs/ride-limit.md, docs/cluster.md), in an
# MPI build: a study of two bump heights on 3 ranks (and on 1) writes the
# same ride_limit.csv, byte for byte, as on threads in one process, with
# runs on every rank; a study killed on threads resumes on 2 ranks to the
# same file; -j is refused with --mpi, once, not once per rank.
#
# usage: MPIEXEC=mpiexec bash tests/mpi/cli_ride_limit_mpi.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_ride_limit_mpi
# shellcheck source=../clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/../clilib.sh"

MPIEXEC=${MPIEXEC:-mpiexec}
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
mpirun_flexbond() {
  local np=$1
  shift
  "$MPIEXEC" -np "$np" --oversubscribe "$FLEXBOND" "$@" >"$OUT" 2>"$ERR"
  status=$?
}

STUDY=(ride-limit "$REPO_ROOT/examples/apc6x6.yaml" --vary road.bump.height=0.1,0.15
  --metric abs_peak --limit 9.81 --no-figures)

run "${STUDY[@]}" -j 2 -q -o "$WORK/threads"
expect_status 0 "threads"

for np in 3 1; do
  mpirun_flexbond "$np" "${STUDY[@]}" --mpi -o "$WORK/ranks$np"
  expect_status 0 "$np ranks"
  checks=$((checks + 1))
  cmp -s "$WORK/threads/ride_limit.csv" "$WORK/ranks$np/ride_limit.csv" ||
    fail "$np ranks and threads write different ride_limit.csv files"
done
# The progress lines of the 3-rank study: runs on every rank.
mpirun_flexbond 3 "${STUDY[@]}" --mpi -o "$WORK/ranks3b"
for rank in 0 1 2; do
  expect_in "$ERR" "on rank $rank, " "a run on rank $rank"
done

# Killed on threads, resumed on 2 ranks: the same file.
JOURNAL=ride_limit.partial.csv
rows() {
  local n
  n=$(grep -c '^[0-9]' "$WORK/killed/$JOURNAL" 2>/dev/null) || n=0
  echo "$n"
}
"$FLEXBOND" "${STUDY[@]}" -j 1 -o "$WORK/killed" >/dev/null 2>&1 &
pid=$!
waited=0
while [ "$(rows)" -lt 5 ] && [ "$waited" -lt 1000 ]; do
  sleep 0.01
  waited=$((waited + 1))
done
kill -s KILL "$pid"
{ wait "$pid"; } 2>/dev/null
mpirun_flexbond 2 "${STUDY[@]}" --mpi --resume -o "$WORK/killed"
expect_status 0 "resumed on 2 ranks"
expect_in "$ERR" "resuming:" "the resumed runs said"
checks=$((checks + 1))
cmp -s "$WORK/threads/ride_limit.csv" "$WORK/killed/ride_limit.csv" ||
  fail "resumed on ranks and threads differ"

# -j with --mpi: a usage error, said once.
mpirun_flexbond 2 "${STUDY[@]}" --mpi -j 2 -o "$WORK/bad"
checks=$((checks + 1))
[ "$(grep -c -- '--mpi runs one run per rank' "$ERR")" -eq 1 ] || fail "-j with --mpi said once"
expect_absent "$WORK/bad/ride_limit.csv" "-j with --mpi: no output"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
