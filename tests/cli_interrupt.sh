#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Nothing half-written: a run interrupted by SIGINT (or SIGTERM) in the
# middle of its simulation, a run whose solver fails and a run that fills
# the disk exit with their documented codes (130, 4, 5), say so, and leave the output directory's
# previous contents exactly as they were, with no staging directory left
# behind; a successful run replaces the files it writes and keeps the
# others.
#
# usage: bash tests/cli_interrupt.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_interrupt
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# previous DIR: a directory holding an earlier result and a user's file.
previous() {
  rm -rf "$1"
  mkdir -p "$1"
  echo "earlier result" >"$1/system2.csv"
  echo "earlier result" >"$1/probes.csv"
  echo "the user's notes" >"$1/notes.txt"
}

# expect_unchanged DIR DESCRIPTION: exactly the files of previous, intact.
expect_unchanged() {
  checks=$((checks + 1))
  [ "$(ls -A "$1" | tr '\n' ' ')" = "notes.txt probes.csv system2.csv " ] ||
    fail "$2: $1 now holds: $(ls -A "$1" | tr '\n' ' ')"
  checks=$((checks + 1))
  [ "$(cat "$1/system2.csv" "$1/probes.csv" "$1/notes.txt")" = \
    "$(printf 'earlier result\nearlier result\nthe user'"'"'s notes')" ] ||
    fail "$2: a previous file was changed"
}

# interrupt SIGNAL: starts System 1 on the ISO road example lengthened to
# 3000 s (minutes of simulation) into $WORK/int, waits until its
# simulation has started, then sends SIGNAL; sets $status.
interrupt() {
  previous "$WORK/int"
  sed 's/^  t_end: 15 .*/  t_end: 3000/' "$REPO_ROOT/examples/apc6x6_iso_road.yaml" \
    >"$WORK/long.yaml"
  "$FLEXBOND" run "$WORK/long.yaml" -o "$WORK/int" --system rigid >"$OUT" 2>"$ERR" &
  local pid=$! waited=0
  while ! grep -q "simulating System 1" "$ERR" && [ "$waited" -lt 600 ]; do
    sleep 0.1
    waited=$((waited + 1))
  done
  sleep 0.5
  kill -s "$1" "$pid"
  wait "$pid"
  status=$?
}

for sig in INT TERM; do
  interrupt "$sig"
  expect_status 130 "SIG$sig during the simulation"
  expect_in "$ERR" "the simulation was interrupted" "SIG$sig message"
  expect_in "$ERR" "nothing was written: $WORK/int holds what it held before" \
    "SIG$sig says the previous results stand"
  expect_unchanged "$WORK/int" "SIG$sig"
done

# A solver failure (the step budget of the quarter car's model exhausted).
sed 's/^  t_end: 5$/  t_end: 5\n  max_steps: 30/' "$REPO_ROOT/examples/quarter_car.yaml" \
  >"$WORK/too_few_steps.yaml"
previous "$WORK/fail"
run sim "$WORK/too_few_steps.yaml" -o "$WORK/fail"
expect_status 4 "solver failure"
expect_in "$ERR" "CV_TOO_MUCH_WORK" "solver failure names the CVODE flag"
expect_in "$ERR" "raise max_steps" "solver failure gives a hint"
expect_in "$ERR" "nothing was written" "solver failure says the previous results stand"
expect_unchanged "$WORK/fail" "solver failure"

# A full disk: System 1's outputs into a 64 KiB tmpfs (where this test may
# mount one, as root in CI), and into any directory under a 64 KiB file-size
# limit with SIGXFSZ ignored, so that a write fails with EFBIG as it would
# with ENOSPC. Both must end in exit 5 with the reason and the previous
# results intact. The reason is an extended regular expression: under the
# file-size limit it is flexbond's own write (EFBIG) or a child's, which
# starts with every signal's default action and is killed by SIGXFSZ,
# whichever of the figures drawn at once fails first.
disk_full() { # DIR DESCRIPTION REASON [ulimit]
  previous "$1"
  if [ "${4:-}" = ulimit ]; then
    (
      ulimit -f 64
      trap '' XFSZ
      exec "$FLEXBOND" run "$REPO_ROOT/examples/apc6x6.yaml" --system rigid -o "$1" -q
    ) >"$OUT" 2>"$ERR"
    status=$?
  else
    run run "$REPO_ROOT/examples/apc6x6.yaml" --system rigid -o "$1" -q
  fi
  expect_status 5 "$2"
  checks=$((checks + 1))
  grep -qE -- "$3" "$ERR" || fail "$2 gives the reason: /$3/ not in stderr"
  expect_in "$ERR" "nothing was written: $1 holds what it held before" \
    "$2 says the previous results stand"
  expect_unchanged "$1" "$2"
  checks=$((checks + 1))
  [ -z "$(find "$1" -name '*.tmp*' -o -name '.flexbond*')" ] || fail "$2: a temporary file was left behind"
}
disk_full "$WORK/fsize" "file-size limit" "File too large|File size limit exceeded" ulimit

# Every command with an output directory says the same when a write fails on its way (through
# cli_outdir_close): the reason, that nothing was written, and what DIR holds. A 1 KiB file-size
# limit stops each at its first file.
APC=$REPO_ROOT/examples/apc6x6.yaml
QC=$REPO_ROOT/examples/quarter_car.yaml
for cmd in "sim $QC" "freq $APC --system rigid --no-figures" "modes $APC --system flexible" \
           "export $APC --system rigid" "model $APC --system rigid" \
           "mesh $APC --export-matrices" "sweep $APC --system rigid --set speed_kmh=5,10"; do
  name=${cmd%% *}
  dir=$WORK/fsize_$name
  previous "$dir"
  case $name in
    mesh) out_opt=(--export-matrices "$dir"); cmd=${cmd% --export-matrices} ;;
    *) out_opt=(-o "$dir") ;;
  esac
  (
    ulimit -f 1
    trap '' XFSZ
    # shellcheck disable=SC2086
    exec "$FLEXBOND" $cmd "${out_opt[@]}"
  ) >"$OUT" 2>"$ERR"
  status=$?
  checks=$((checks + 1))
  [ "$status" -ne 0 ] || fail "$name under a 1 KiB file-size limit: exit 0"
  expect_in "$ERR" "nothing was written: $dir holds what it held before" \
    "$name under a file-size limit says the previous results stand"
  expect_unchanged "$dir" "$name under a file-size limit"
done
mkdir -p "$WORK/small"
if mount -t tmpfs -o size=64k tmpfs "$WORK/small" 2>/dev/null; then
  disk_full "$WORK/small/out" "full disk" "No space left on device"
  umount "$WORK/small"
else
  echo "$NAME: SKIP the full tmpfs (mount not permitted); the file-size limit stands in" >&2
fi

# A successful run replaces probes.csv, adds stats.json, keeps the rest,
# and leaves no staging directory.
previous "$WORK/ok"
run sim "$REPO_ROOT/examples/quarter_car.yaml" -o "$WORK/ok" -q
expect_status 0 "successful run"
checks=$((checks + 1))
[ "$(ls -A "$WORK/ok" | tr '\n' ' ')" = ".flexbond-manifest notes.txt probes.csv stats.json system2.csv " ] ||
  fail "successful run: $(ls -A "$WORK/ok" | tr '\n' ' ')"
checks=$((checks + 1))
[ "$(head -c 1 "$WORK/ok/probes.csv")" = "t" ] || fail "successful run: probes.csv not replaced"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
