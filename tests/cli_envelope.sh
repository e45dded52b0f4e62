#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Tire enveloping through the real flexbond command (docs/tire-envelope.md):
# the paper's 6x6 with `wheel.envelope: point` written out runs to the same
# bytes as without it; with cams or the overlap (and the tire's radius) it
# runs, at the top level and per axle; bad values are refused at
# FILE:LINE:COL: KEY, an implausible radius warned about there.
#
# usage: bash tests/cli_envelope.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_envelope
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT/examples/apc6x6.yaml" apc.yaml || exit 2

# at FILE TEXT: "FILE:LINE:COL:" with LINE the first line of FILE holding
# TEXT and COL the column of TEXT's value (after "KEY: ").
at() {
  AT_TEXT=$2 awk -v file="$1" '
    index($0, ENVIRON["AT_TEXT"]) {
      t = ENVIRON["AT_TEXT"]
      printf "%s:%d:%d:", file, NR, index($0, t) + index(t, ": ") + 1
      found = 1
      exit
    }
    END { if (!found) printf "NOT-FOUND(%s in %s)", ENVIRON["AT_TEXT"], file }' "$1"
}

# keyat FILE TEXT: as at, the column of TEXT itself (an error about a
# whole section or item).
keyat() {
  AT_TEXT=$2 awk -v file="$1" '
    index($0, ENVIRON["AT_TEXT"]) {
      printf "%s:%d:%d:", file, NR, index($0, ENVIRON["AT_TEXT"])
      found = 1
      exit
    }
    END { if (!found) printf "NOT-FOUND(%s in %s)", ENVIRON["AT_TEXT"], file }' "$1"
}

# derive NEW SED-SCRIPT: NEW is apc.yaml edited; it must differ.
derive() {
  sed "$2" apc.yaml >"$1"
  checks=$((checks + 1))
  ! cmp -s "$1" apc.yaml || fail "fixture $1: sed $2 changed nothing"
}

WHEEL='s/^  tire_c: 140000 .*/&\n'

# Point contact written out: the same run, byte for byte.
derive point.yaml "${WHEEL}  envelope: point/"
run run apc.yaml -o "$WORK/plain" --system rigid --no-figures -q
expect_status 0 "the paper's 6x6"
run run point.yaml -o "$WORK/point" --system rigid --no-figures -q
expect_status 0 "envelope: point"
checks=$((checks + 1))
cmp -s "$WORK/plain/system1.csv" "$WORK/point/system1.csv" ||
  fail "envelope: point changed the run"

# The cams for every tire, and the overlap on the front axle only.
derive cams.yaml "${WHEEL}  radius: 0.55\n  envelope: cams/"
run run cams.yaml -o "$WORK/cams" --system rigid --no-figures -q
expect_status 0 "envelope: cams"
sed 's/^      spring_k: 145300 .*/&\n      wheel: {envelope: overlap, overlap: {deflection: 0.03}}/' \
  cams.yaml >axle.yaml
run run axle.yaml -o "$WORK/axle" --system rigid --no-figures -q
expect_status 0 "the front axle's overlap"
checks=$((checks + 1))
! cmp -s "$WORK/cams/system1.csv" "$WORK/plain/system1.csv" || fail "the cams changed nothing"
checks=$((checks + 1))
! cmp -s "$WORK/axle/system1.csv" "$WORK/cams/system1.csv" ||
  fail "the front axle's overlap changed nothing"

# refused FILE WHERE TEXT: run refuses FILE with the error at WHERE.
refused() {
  run run "$1" -o "$WORK/bad" --system rigid --no-figures -q
  expect_status 2 "$1"
  expect_in "$ERR" "flexbond: $2 $3" "$1: the error at its key"
  expect_absent "$WORK/bad" "$1"
}

# No radius: refused at the first corner's item, which has no key of it.
derive norad.yaml "${WHEEL}  envelope: cams/"
refused norad.yaml "$(keyat norad.yaml 'name: F ')" \
  "suspensions.axles[0].wheel.radius: a \`cams\` envelope needs the tire's free radius"

derive order.yaml "${WHEEL}  radius: 0.55\n  envelope: cams\n  cams: {order: 0.5}/"
refused order.yaml "$(at order.yaml 'order: 0.5' | sed 's/:$//'):" \
  "wheel.cams.order: must be in [1, 10] (got 0.5)"

derive foreign.yaml "${WHEEL}  radius: 0.55\n  envelope: cams\n  overlap: {deflection: 0.01}/"
refused foreign.yaml "$(keyat foreign.yaml 'overlap: {')" \
  "wheel.overlap: no corner's envelope is overlap (wheel.envelope chooses the envelopes)"

sed 's/^      spring_k: 145300 .*/&\n      wheel: {envelope: overlap, overlap: {deflection: 0.7}}/' \
  cams.yaml >deep.yaml
refused deep.yaml "$(at deep.yaml 'deflection: 0.7')" \
  "suspensions.axles[0].wheel.overlap.deflection: must be in (0, the tire's radius 0.55 m) (got 0.7 m)"

# An implausible radius: a warning at its key, refused under --strict.
derive big.yaml "${WHEEL}  radius: 1.5\n  envelope: overlap/"
run run big.yaml -o "$WORK/big" --system rigid --no-figures -q --strict
expect_status 2 "a 1.5 m tire under --strict"
expect_in "$ERR" "flexbond: $(at big.yaml 'radius: 1.5') wheel.radius: 1.5 m is implausible" \
  "the radius's warning at its key"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
