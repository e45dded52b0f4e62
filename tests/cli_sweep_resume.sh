#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond sweep's journal (docs/sweep.md, "Resuming"): a sweep killed with
# SIGKILL, or one whose journal ends in a torn row, or one interrupted by
# SIGINT, resumes with --resume and then writes the same sweep.csv, byte for
# byte, as a sweep never stopped, running only the cases its journal lacks
# (a failed case is kept, not run again); a journal is refused without
# --resume, when it is another study's or has other columns, when a row
# does not belong to the study, when another flexbond wrote it, when a
# file the study reads (a damper table the scenario names, or one a --set
# value names) has changed since, and while another sweep writes it; a
# journal that cannot be written stops the sweep with the rows it holds
# counted; --resume with no journal runs the whole study.
#
# usage: bash tests/cli_sweep_resume.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_sweep_resume
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# System 1 over 60 s instead of 15 s, so that a case takes long enough
# (about 0.1 s) to stop the sweep in the middle; the first value is a word
# the reader refuses, a case that fails.
sed 's/^  t_end: 15 /  t_end: 60 /' "$REPO_ROOT/examples/apc6x6.yaml" >"$WORK/long.yaml"
grep -q '^  t_end: 60 ' "$WORK/long.yaml" || {
  echo "$NAME: cannot lengthen the example's run" >&2
  exit 2
}
SPEEDS=fast,6,10,14,18,22,26,30,34,38,42,46,50,54
STUDY=(sweep "$WORK/long.yaml" --set "speed_kmh=$SPEEDS" --no-figures -j 1)
JOURNAL=sweep.partial.csv

# rows DIR: the number of case rows in DIR's journal.
rows() {
  local n
  n=$(grep -c '^[0-9]' "$1/$JOURNAL" 2>/dev/null) || n=0
  echo "$n"
}

# stopped DIR SIGNAL [STUDY...]: starts the study (default: $STUDY) into
# DIR, sends SIGNAL once the journal holds at least 3 rows, and waits;
# sets $status.
stopped() {
  local dir=$1 signal=$2
  shift 2
  [ $# -gt 0 ] || set -- "${STUDY[@]}"
  rm -rf "$dir"
  "$FLEXBOND" "$@" -o "$dir" >"$OUT" 2>"$ERR" &
  local pid=$! waited=0
  while [ "$(rows "$dir")" -lt 3 ] && [ "$waited" -lt 600 ]; do
    sleep 0.02
    waited=$((waited + 1))
  done
  kill -s "$signal" "$pid"
  wait "$pid"
  status=$?
}

# ---- The reference: the study never stopped (one case fails: exit 4).
run "${STUDY[@]}" -o "$WORK/ref" -q
expect_status 4 "uninterrupted study (one failing case)"
checks=$((checks + 1))
[ "$(ls -A "$WORK/ref" | tr '\n' ' ')" = ".flexbond-manifest sweep.csv " ] ||
  fail "the journal is removed at the end"

# ---- Killed (SIGKILL): the journal stays, and the directory's lock file,
# which the next command takes over; nothing else.
stopped "$WORK/killed" KILL
checks=$((checks + 1))
[ "$(ls -A "$WORK/killed" | tr '\n' ' ')" = ".flexbond.lock $JOURNAL " ] ||
  fail "a killed sweep leaves only its journal: $(ls -A "$WORK/killed" | tr '\n' ' ')"
done_before=$(rows "$WORK/killed")
checks=$((checks + 1))
[ "$done_before" -ge 3 ] && [ "$done_before" -lt 14 ] ||
  fail "killed in the middle: $done_before of 14 cases in the journal"
# A row cut short by the kill: no line end. It is dropped.
printf '%s' "13,FB_OK,54,12345.6" >>"$WORK/killed/$JOURNAL"

# Without --resume the journal is refused and kept.
cp "$WORK/killed/$JOURNAL" "$WORK/journal.copy"
run "${STUDY[@]}" -o "$WORK/killed"
expect_status 1 "a journal without --resume"
expect_in "$ERR" "an earlier sweep into this directory stopped before it finished: add --resume" \
  "a journal without --resume: message"
checks=$((checks + 1))
cmp -s "$WORK/killed/$JOURNAL" "$WORK/journal.copy" || fail "the refused journal was changed"

run "${STUDY[@]}" -o "$WORK/killed" --resume
expect_status 4 "resumed after SIGKILL (the failing case is still failed)"
expect_in "$ERR" "resuming: $done_before of 14 cases are done" "resume says what it found"
checks=$((checks + 1))
[ "$(grep -c ': case [0-9]*/14 ' "$ERR")" -eq $((14 - done_before)) ] ||
  fail "resume runs only the $((14 - done_before)) missing cases: $(grep -c ': case ' "$ERR")"
checks=$((checks + 1))
! grep -q 'case 1/14 (speed_kmh=fast)' "$ERR" || fail "the failed case was run again"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/killed/sweep.csv" ||
  fail "sweep.csv after SIGKILL and --resume differs from the uninterrupted one"
checks=$((checks + 1))
[ "$(ls -A "$WORK/killed" | tr '\n' ' ')" = ".flexbond-manifest sweep.csv " ] ||
  fail "the journal is removed after resuming"

# ---- Interrupted (SIGINT): exit 130, the journal kept and named.
stopped "$WORK/int" INT
expect_status 130 "SIGINT in the middle"
expect_in "$ERR" "cases are done and kept in $WORK/int/$JOURNAL: run the same command with --resume" \
  "SIGINT names the journal"
run "${STUDY[@]}" -o "$WORK/int" --resume -q
expect_status 4 "resumed after SIGINT"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/int/sweep.csv" ||
  fail "sweep.csv after SIGINT and --resume differs from the uninterrupted one"

# ---- Journals that do not belong to the study.
stopped "$WORK/other" KILL
run sweep "$WORK/long.yaml" --set "speed_kmh=$SPEEDS,58" --no-figures -o "$WORK/other" --resume
expect_status 1 "another study's journal"
expect_in "$ERR" "$WORK/other/$JOURNAL: the journal of another study" "another study: message"
# The journal's second row (its line: after the comments and the header).
line=$(grep -n '^[0-9]' "$WORK/other/$JOURNAL" | sed -n 2p | cut -d: -f1)
sed -i "${line}s/^\([0-9]*\),\([A-Z_]*\),\([^,]*\),/\1,\2,999,/" "$WORK/other/$JOURNAL"
run "${STUDY[@]}" -o "$WORK/other" --resume
expect_status 2 "a row of another case"
expect_in "$ERR" "$WORK/other/$JOURNAL:$line: case " "a row of another case names its line"
expect_in "$ERR" "has speed_kmh=999" "a row of another case: message"

# The same study with a key spelled otherwise: other columns.
stopped "$WORK/spelled" KILL
run sweep "$WORK/long.yaml" --set "road.speed_kmh=$SPEEDS" --no-figures -o "$WORK/spelled" \
  --resume
expect_status 1 "the key spelled otherwise"
line=$(grep -n '^case,' "$WORK/spelled/$JOURNAL" | cut -d: -f1)
expect_in "$ERR" "$WORK/spelled/$JOURNAL:$line: the journal's columns are not this sweep's" \
  "the key spelled otherwise: message"

# Another flexbond's journal (its version in its comments, and its own
# fingerprint): refused, naming both versions.
sed -e '1s/study [0-9a-f]*,/study 0000000000000000,/' \
  -e 's/^# written by flexbond .*/# written by flexbond 0.0.1/' "$WORK/journal.copy" \
  >"$WORK/spelled/$JOURNAL"
run "${STUDY[@]}" -o "$WORK/spelled" --resume
expect_status 1 "another flexbond's journal"
expect_in "$ERR" "the journal of another study: it was written by flexbond 0.0.1, this is" \
  "another flexbond's journal: message"

# ---- A file the study reads changes after a partial run: the journal's
# cases were computed from the old file, so --resume refuses it (exit 1)
# and leaves it as it was, naming the file; once the file is back, it
# resumes. The damper-table example (its tables copied beside it) over
# 60 s, with the front axle's table swept too: shock_alt.csv, a copy of the front
# table, is named only by a --set value.
sed 's/^  t_end: 15 /  t_end: 60 /' "$REPO_ROOT/examples/apc6x6_shock_table.yaml" \
  >"$WORK/table.yaml"
cp "$REPO_ROOT/examples/shock_front.csv" "$REPO_ROOT/examples/shock_rear.csv" "$WORK/"
cp "$WORK/shock_front.csv" "$WORK/shock_alt.csv"
TABLES=(sweep "$WORK/table.yaml" --set suspensions.axles[0].damper_table.file=shock_front.csv,shock_alt.csv
  --set speed_kmh=6,18,30,42 --no-figures -j 1)
stopped "$WORK/table" KILL "${TABLES[@]}"
cp "$WORK/table/$JOURNAL" "$WORK/journal.copy"
for table in shock_front shock_alt; do
  # Every force of the table doubled (its F column).
  cp "$WORK/$table.csv" "$WORK/$table.orig"
  awk -F, 'BEGIN { OFS = "," } /^[-0-9.]/ { $2 = 2 * $2 } { print }' "$WORK/$table.orig" \
    >"$WORK/$table.csv"
  run "${TABLES[@]}" -o "$WORK/table" --resume
  expect_status 1 "$table.csv changed after a partial run"
  expect_in "$ERR" "$WORK/table/$JOURNAL: the journal of another study: $WORK/$table.csv has changed since the journal was written" \
    "$table.csv changed: message"
  checks=$((checks + 1))
  cmp -s "$WORK/table/$JOURNAL" "$WORK/journal.copy" ||
    fail "$table.csv changed: the refused journal was changed"
  mv "$WORK/$table.orig" "$WORK/$table.csv"
done
run "${TABLES[@]}" -o "$WORK/table" --resume -q
expect_status 0 "the tables restored: resumed"
checks=$((checks + 1))
[ "$(grep -c '^shock_' "$WORK/table/sweep.csv")" -eq 8 ] ||
  fail "the tables restored: 8 rows in sweep.csv: $(grep -c '^shock_' "$WORK/table/sweep.csv")"

# ---- The journal cannot be written (a file-size limit, SIGXFSZ ignored,
# so that a write fails with EFBIG as on a full disk): no case is started
# after that, and the message counts the rows the file holds, not the
# cases that ran.
rm -rf "$WORK/full"
(
  ulimit -f 4
  trap '' XFSZ
  exec "$FLEXBOND" "${STUDY[@]}" -o "$WORK/full" >"$OUT" 2>"$ERR"
)
status=$?
expect_status 5 "the journal cannot be written"
expect_in "$ERR" "$WORK/full/$JOURNAL: cannot write: File too large" "journal write: message"
# The complete rows: lines ended by '\n' but the comments and the header.
kept=$(($(wc -l <"$WORK/full/$JOURNAL") - $(grep -vc '^[0-9]' "$WORK/full/$JOURNAL")))
expect_in "$ERR" "; $kept of 14 cases are done and kept in" "journal write: the rows kept"
checks=$((checks + 1))
[ "$kept" -ge 1 ] && [ "$kept" -lt 13 ] || fail "journal write: $kept rows before the limit"
checks=$((checks + 1))
[ "$(grep -c ': case [0-9]*/14 ' "$ERR")" -eq $((kept + 1)) ] ||
  fail "journal write: cases were started after it failed"
run "${STUDY[@]}" -o "$WORK/full" --resume -q
expect_status 4 "resumed after the journal failed"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/full/sweep.csv" ||
  fail "sweep.csv after a failed journal write and --resume differs"

# ---- Two sweeps into one directory: the second is refused.
rm -rf "$WORK/two"
"$FLEXBOND" "${STUDY[@]}" -o "$WORK/two" -q 2>/dev/null &
first=$!
waited=0
while [ ! -s "$WORK/two/$JOURNAL" ] && [ "$waited" -lt 600 ]; do
  sleep 0.02
  waited=$((waited + 1))
done
run "${STUDY[@]}" -o "$WORK/two" --resume
expect_status 5 "a second sweep into the same directory"
expect_in "$ERR" "another flexbond command is writing into this directory" "second sweep: message"
wait "$first"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/two/sweep.csv" || fail "the first sweep was disturbed"

# ---- --resume with nothing to resume runs the whole study.
run "${STUDY[@]}" -o "$WORK/fresh" --resume -q
expect_status 4 "--resume without a journal"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/fresh/sweep.csv" || fail "--resume without a journal"

# ---- --mpi in a build without MPI (the MPI build has tests/mpi/).
if [ "${FLEXBOND_MPI_BUILD:-OFF}" != ON ]; then
  run sweep "$WORK/long.yaml" --set speed_kmh=10 --mpi -o "$WORK/mpi"
  expect_status 1 "--mpi without MPI"
  expect_in "$ERR" "this flexbond was built without MPI" "--mpi without MPI: message"
  expect_absent "$WORK/mpi" "--mpi without MPI"
fi

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
