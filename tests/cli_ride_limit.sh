#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond ride-limit (docs/ride-limit.md) on the paper's APC over its bump
# of two heights, System 1:
#   - each found speed is checked against flexbond sweep at the bracket's
#     two ends: the metric (the driver's largest |acceleration| from the
#     first wheel on the bump on, here against 1 g) is below the limit at
#     the reported speed and at or above it at speed_over, at most the
#     tolerance (0.1 km/h) higher; a sweep runs 15 s, ride-limit's runs
#     end 2 s after the last wheel leaves the bump, so the check holds as
#     long as the peak comes before that, which the agreement of the two
#     metrics to 1e-9 shows;
#   - -j 1 and -j 2 give the same ride_limit.csv, byte for byte;
#   - a study killed in the middle resumes with --resume, runs only what
#     its journal lacks and writes the same ride_limit.csv; a journal is
#     refused without --resume;
#   - a metric's limit that is never or already reached is said so;
#   - on a random course given by its r.m.s. the limit is bracketed, and
#     the driver's a_w is proportional to the r.m.s. (a linear vehicle);
#   - bad options exit 1 and write nothing (--mpi too, in a build
#     without MPI; tests/mpi/cli_ride_limit_mpi.sh runs it on ranks).
#
# usage: bash tests/cli_ride_limit.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_ride_limit
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

SCENARIO=$REPO_ROOT/examples/apc6x6.yaml
STUDY=(ride-limit "$SCENARIO" --vary road.bump.height=0.1,0.15 --metric abs_peak --limit 9.81
  --no-figures)

# ---- The reference, on one thread.
run "${STUDY[@]}" -j 1 -o "$WORK/j1"
expect_status 0 "the study"
expect_in "$ERR" "2 curves (2 found, 0 below, 0 above, 0 failed)" "its summary line"
expect_in "$WORK/j1/ride_limit.csv" \
  "road.bump.height [m],system,speed_kmh [km/h],status,abs_peak [m/s^2],speed_over_kmh [km/h],abs_peak_over [m/s^2],runs,error" \
  "the header"
checks=$((checks + 1))
[ "$(ls -A "$WORK/j1" | tr '\n' ' ')" = ".flexbond-manifest ride_limit.csv " ] ||
  fail "the journal is removed at the end: $(ls -A "$WORK/j1" | tr '\n' ' ')"

# ---- Two threads: the same file.
run "${STUDY[@]}" -j 2 -q -o "$WORK/j2"
expect_status 0 "the study on two threads"
checks=$((checks + 1))
cmp -s "$WORK/j1/ride_limit.csv" "$WORK/j2/ride_limit.csv" || fail "-j 1 and -j 2 differ"

# ---- Each found speed against flexbond sweep at the bracket's ends.
while IFS=, read -r height system speed status metric over metric_over runs error; do
  checks=$((checks + 1))
  [ "$status" = found ] && [ "$system" = rigid ] && [ "$runs" = 22 ] && [ -z "$error" ] ||
    fail "height $height: $status, $runs runs, '$error'"
  run sweep "$SCENARIO" --set "road.bump.height=$height" --set "speed_kmh=$speed,$over" \
    --no-figures -q -j 1 -o "$WORK/check_$height"
  expect_status 0 "sweep at height $height"
  values=$(awk -F, '
    NR == 1 { for (i = 1; i <= NF; ++i) { if ($i ~ /^driver_acc_peak/) p = i; if ($i ~ /^driver_acc_min/) q = i } next }
    p && q { printf "%.17g ", ($p > -$q ? $p : -$q) }' "$WORK/check_$height/sweep.csv")
  # shellcheck disable=SC2086 # two numbers, split on purpose
  set -- $values
  bracket_verdict 9.81 "${1:-nan}" "${2:-nan}" "$metric" "$metric_over" "$speed" "$over" \
    >"$WORK/awk.out"
  verdict=$?
  checks=$((checks + 1))
  [ "$verdict" -eq 0 ] || fail "height $height: $(cat "$WORK/awk.out")"
done < <(tail -n +2 "$WORK/j1/ride_limit.csv")

# ---- Killed in the middle, then resumed: the same file, fewer runs.
JOURNAL=ride_limit.partial.csv
# rows: the runs in the killed study's journal.
rows() {
  local n
  n=$(grep -c '^[0-9]' "$WORK/killed/$JOURNAL" 2>/dev/null) || n=0
  echo "$n"
}
# stop SIGNAL: starts the study into $WORK/killed, sends SIGNAL once its
# journal holds 5 runs, waits; sets $status.
stop() {
  rm -rf "$WORK/killed"
  "$FLEXBOND" "${STUDY[@]}" -j 1 -o "$WORK/killed" >"$OUT" 2>"$ERR" &
  local pid=$! waited=0
  while [ "$(rows)" -lt 5 ] && [ "$waited" -lt 1000 ]; do
    sleep 0.01
    waited=$((waited + 1))
  done
  kill -s "$1" "$pid"
  { wait "$pid"; } 2>/dev/null
  status=$?
}
# Ctrl-C: exit 130, the journal kept and said.
stop INT
expect_status 130 "interrupted"
expect_in "$ERR" "ride_limit.partial.csv: run the same command with --resume" "the journal said"
checks=$((checks + 1))
[ "$(rows)" -ge 5 ] || fail "the interrupted study's journal"
expect_absent "$WORK/killed/ride_limit.csv" "an interrupted study's CSV"
stop KILL
kept=$(rows)
checks=$((checks + 1))
[ "$kept" -ge 5 ] && [ "$kept" -lt 44 ] || fail "killed in the middle: $kept of 44 runs kept"
run "${STUDY[@]}" -j 1 -o "$WORK/killed"
expect_status 1 "a journal without --resume"
expect_in "$ERR" "run the same command with --resume" "the refusal's advice"
run "${STUDY[@]}" -j 1 --resume -o "$WORK/killed"
expect_status 0 "resumed"
expect_in "$ERR" "resuming: $kept runs are done" "the resumed runs said"
ran=$(grep -c 'km/h: abs_peak' "$ERR")
checks=$((checks + 1))
[ "$ran" -eq $((44 - kept)) ] || fail "the resumed study ran $ran runs, not $((44 - kept))"
checks=$((checks + 1))
cmp -s "$WORK/j1/ride_limit.csv" "$WORK/killed/ride_limit.csv" || fail "resumed CSV differs"
expect_absent "$WORK/killed/$JOURNAL" "the journal after the resumed study"

# ---- Never reached (above) and already reached (below), not numbers.
run ride-limit "$SCENARIO" --vary road.bump.height=0.02,0.3 --metric abs_peak --limit 9.81 \
  --speeds 30:40 --no-figures -q -o "$WORK/ends"
expect_status 0 "a study with both ends"
expect_in "$WORK/ends/ride_limit.csv" "0.02,rigid,,above," "a limit never reached"
expect_in "$WORK/ends/ride_limit.csv" "0.3,rigid,,below," "a limit reached at the lowest speed"

# ---- A random course by its r.m.s. (road.iso8608.rms): a_w r.m.s. of
# the driver over 40 m, 10 .. 50 km/h every 10 km/h to 1 km/h: 5 grid runs
# and 4 bisections (10 / 2^4 = 0.625 km/h), the limit bracketed.
ROUGH=$REPO_ROOT/examples/apc6x6_rough_course.yaml
run ride-limit "$ROUGH" --vary road.iso8608.rms=0.03,0.05 --metric a_w_rms --limit 1.5 \
  --course-length 40 --speeds 10:50 --coarse-step 10 --tolerance 1 --no-figures -q \
  -o "$WORK/rough"
expect_status 0 "a random course by its r.m.s."
awk -F, 'NR > 1 && !($4 == "found" && $8 == 9 && $6 - $3 <= 1 && $6 > $3 &&
  $5 < 1.5 && $7 >= 1.5) { print; bad = 1 } END { exit bad }' "$WORK/rough/ride_limit.csv" \
  >"$WORK/awk.out"
verdict=$?
checks=$((checks + 1))
[ "$verdict" -eq 0 ] || fail "the random course's rows: $(cat "$WORK/awk.out")"
# The vehicle is linear and starts at rest on flat ground: on the same
# road (one seed) its a_w is proportional to the r.m.s. asked for, so 50
# mm gives 5/3 of 30 mm's at one speed, to the solver's tolerance (rtol
# 1e-4 in the example; measured 2.3e-6): the r.m.s. reaches the road's
# level linearly.
run sweep "$ROUGH" --set road.iso8608.rms=0.03,0.05 --set speed_kmh=30 --no-figures -q \
  --plain-header -o "$WORK/rough_sweep"
expect_status 0 "the course at two r.m.s."
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "ride_a_w_rms") c = i; next }
  { a[NR - 1] = $c }
  END { if (!c) { print "no ride_a_w_rms column"; exit 1 }
        r = a[2] / a[1] / (5 / 3) - 1; if (r < 0) r = -r; if (!(r < 1e-4)) { print r; exit 1 } }' \
  "$WORK/rough_sweep/sweep.csv" >"$WORK/awk.out"
verdict=$?
checks=$((checks + 1))
[ "$verdict" -eq 0 ] || fail "a_w not proportional to the r.m.s.: $(cat "$WORK/awk.out")"

# ---- Bad options: exit 1, nothing written.
bad() {
  local what=$1 phrase=$2
  shift 2
  rm -rf "$WORK/bad"
  run ride-limit "$SCENARIO" "$@" -o "$WORK/bad"
  expect_status 1 "$what"
  expect_in "$ERR" "$phrase" "$what: the message"
  expect_absent "$WORK/bad" "$what: the output directory"
}
bad "no metric" "missing --metric" --vary road.bump.height=0.1
bad "an unknown metric" "--metric power: no such metric (the metrics: absorbed_power" \
  --vary road.bump.height=0.1 --metric power
bad "no standard limit" "--metric a_w_rms has no standard limit" \
  --vary road.bump.height=0.1 --metric a_w_rms
bad "the speed varied" "the search sets road.speed_kmh itself" \
  --vary speed_kmh=10,20 --metric abs_peak --limit 5
bad "an unknown output" "--output nope: the scenario has no such output" \
  --vary road.bump.height=0.1 --metric abs_peak --limit 5 --output nope
bad "an unknown key" "--vary road.bump.hieght" \
  --vary road.bump.hieght=0.1 --metric abs_peak --limit 5
bad "bad speeds" "--speeds needs LO:HI" \
  --vary road.bump.height=0.1 --metric abs_peak --limit 5 --speeds 40:20
bad "a hexadecimal value" "is not a finite number in decimal digits" \
  --vary road.bump.height=0x1 --metric abs_peak --limit 5
bad "no values" "--vary needs KEY=V1,V2" --vary road.bump.height= --metric abs_peak --limit 5
# A value the scenario refuses: exit 2 before any run, located in the file.
rm -rf "$WORK/bad"
run ride-limit "$SCENARIO" --vary road.bump.height=0.1,-0.1 --metric abs_peak --limit 5 \
  -o "$WORK/bad"
expect_status 2 "a value the scenario refuses"
expect_in "$ERR" "--vary road.bump.height=-0.1: $(at "$SCENARIO" "height: 0.10" "0.10") road.bump.height: must be >= 0 m (got -0.1)" \
  "a value the scenario refuses: the message"
expect_absent "$WORK/bad" "a value the scenario refuses: the output directory"
bad "a seat metric of a force" "--metric nrmm_peak is of a vertical acceleration in m/s^2; output tire_force_LF is in N" \
  --vary road.bump.height=0.1 --metric nrmm_peak --output tire_force_LF
bad "no settling time" "--settle needs a number of seconds > 0 (got '0')" \
  --vary road.bump.height=0.1 --metric nrmm_peak --settle 0
# --mpi in a build without MPI (the MPI build has tests/mpi/).
if [ "${FLEXBOND_MPI_BUILD:-OFF}" != ON ]; then
  bad "--mpi without MPI" "this flexbond was built without MPI" \
    --vary road.bump.height=0.1 --metric abs_peak --limit 5 --mpi
fi
run ride-limit "$SCENARIO" --vary road.bump.height=0.1 --metric abs_peak --limit 5
expect_status 1 "no output directory"
expect_in "$ERR" "missing output directory (-o DIR)" "no output directory: the message"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
