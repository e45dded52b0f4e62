#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Regression against a released state: `flexbond run` on the APC example
# (both systems, 15 s at 1 kHz) reproduces, sample by sample, the
# system1.csv and system2.csv that commit 5b32e25 wrote
# (tests/data/apc6x6_5b32e25/README.md). Every output column must be within
# 1e-4 of that column's range in the reference (1e-12 absolute for a
# constant column: System 1's torsion), with the same header, row count
# and time column; tests/tools/result_compare.c does the comparison and
# says why 1e-4: the integration's own error, measured against a converged
# run, with a margin, and below what a 1 % change of a tire's stiffness
# shows. First the comparator is checked on its own: it accepts the
# reference against itself and rejects copies changed by little more than
# the tolerance.
#
# usage: bash tests/cli_regression.sh PATH/TO/flexbond REPO_ROOT
# with FLEXBOND_RESULT_COMPARE the result_compare executable (CTest sets
# it; by hand, e.g. FLEXBOND_RESULT_COMPARE=build/result_compare).
set -u
NAME=cli_regression
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

COMPARE=${FLEXBOND_RESULT_COMPARE:-}
if [ -z "$COMPARE" ] || [ ! -x "$COMPARE" ]; then
  echo "$NAME: FLEXBOND_RESULT_COMPARE ('$COMPARE') is not the result_compare executable" >&2
  exit 2
fi
REF=$REPO_ROOT/tests/data/apc6x6_5b32e25

# compare OLD NEW: runs the comparator, output in $OUT and $ERR, sets $status.
compare() {
  "$COMPARE" "$1" "$2" >"$OUT" 2>"$ERR"
  status=$?
}

# perturb SRC DST LINE FIELD OP X: DST is SRC with field FIELD (1 = t) of
# line LINE (1 = the header) multiplied by X (OP "mul") or plus X (OP
# "add"), printed as %.17g.
perturb() {
  awk -F, -v OFS=, -v line="$3" -v field="$4" -v op="$5" -v x="$6" \
    'NR == line { $field = sprintf("%.17g", op == "mul" ? $field * x : $field + x) } { print }' \
    "$1" >"$2"
}

# range FILE FIELD: max - min of field FIELD over the data rows, %.17g.
range() {
  awk -F, -v f="$2" 'NR == 2 { lo = hi = $f } NR > 2 { if ($f < lo) lo = $f; if ($f > hi) hi = $f }
    END { printf "%.17g\n", hi - lo }' "$1"
}

# ---- The comparator checks itself.
for s in 1 2; do
  compare "$REF/system$s.csv" "$REF/system$s.csv"
  expect_status 0 "reference system$s.csv against itself"
  expect_in "$OUT" "0.000e+00 x range" "reference system$s.csv against itself: zero differences"
done

# One value of System 1's LF tire force changed by 1e-3 relative (about
# 8e-4 of the column's range): rejected, the message naming the column,
# row, time and both values. Line 5001 is sample 5000, t = 4.999 s, where
# the tire carries its static load.
P=$WORK/perturbed1.csv
perturb "$REF/system1.csv" "$P" 5001 2 mul 1.001
# The comparator prints values as %.17g, as awk does here.
old=$(awk -F, 'NR == 5001 { printf "%.17g", $2 }' "$REF/system1.csv")
new=$(awk -F, 'NR == 5001 { printf "%.17g", $2 }' "$P")
checks=$((checks + 1))
[ "$old" != "$new" ] || fail "perturbed copy: value unchanged ($old)"
compare "$REF/system1.csv" "$P"
expect_status 1 "perturbed tire_force_LF (1e-3 relative)"
expect_in "$ERR" "column 'tire_force_LF': 1 of 15001 samples differ" "perturbed: column named"
expect_in "$ERR" "worst at row 5000 (line 5001), t = 4.999 s" "perturbed: row and time named"
expect_in "$ERR" "old $old, new $new," "perturbed: both values shown"
expect_in "$OUT" "tire_power_LR" "perturbed: every column still listed"

# Either side of the tolerance at one sample of System 2's driver
# acceleration: 0.9e-4 of the column's range added passes, 1.1e-4 fails.
R=$(range "$REF/system2.csv" 5)
for frac in 0.9e-4 1.1e-4; do
  P=$WORK/driver_acc_$frac.csv
  perturb "$REF/system2.csv" "$P" 9001 5 add "$(awk -v r="$R" -v f="$frac" 'BEGIN { printf "%.17g", r * f }')"
  compare "$REF/system2.csv" "$P"
  if [ "$frac" = 0.9e-4 ]; then
    expect_status 0 "driver_acc plus 0.9e-4 x range at one sample"
  else
    expect_status 1 "driver_acc plus 1.1e-4 x range at one sample"
    expect_in "$ERR" "column 'driver_acc': 1 of 15001 samples differ" "driver_acc: column named"
    expect_in "$ERR" "worst at row 9000 (line 9001), t = 8.999 s" "driver_acc: row and time"
  fi
done

# System 1's torsion is exactly 0 (range 0): 1e-12 absolute is allowed,
# 1e-11 is not.
for v in 1e-12 1e-11; do
  P=$WORK/torsion_$v.csv
  awk -F, -v OFS=, -v v="$v" 'NR == 7001 { $4 = v } { print }' "$REF/system1.csv" >"$P"
  compare "$REF/system1.csv" "$P"
  if [ "$v" = 1e-12 ]; then
    expect_status 0 "System 1 torsion 1e-12 at one sample"
  else
    expect_status 1 "System 1 torsion 1e-11 at one sample"
    expect_in "$ERR" "column 'torsion': 1 of 15001 samples differ by more than 1e-12 (absolute" \
      "torsion: absolute tolerance named"
  fi
done

# A different time column, row count or header is refused whatever the values.
P=$WORK/time.csv
awk -F, -v OFS=, 'NR == 3 { $1 = "0.0010000001" } { print }' "$REF/system1.csv" >"$P"
compare "$REF/system1.csv" "$P"
expect_status 1 "changed sample time"
expect_in "$ERR" "column 't' (time), row 2 (line 3)" "changed sample time: row named"
head -n -1 "$REF/system1.csv" >"$WORK/short.csv"
compare "$REF/system1.csv" "$WORK/short.csv"
expect_status 1 "one row fewer"
expect_in "$ERR" "15001 rows in" "one row fewer"
sed '1s/torsion/twist/' "$REF/system1.csv" >"$WORK/header.csv"
compare "$REF/system1.csv" "$WORK/header.csv"
expect_status 1 "renamed column"
expect_in "$ERR" "header differs" "renamed column"
printf 't,x\n0,1\n0.001,oops\n' >"$WORK/bad.csv"
compare "$WORK/bad.csv" "$WORK/bad.csv"
expect_status 2 "unparsable value"
expect_in "$ERR" "bad.csv:3: field 2 ('x') is not a number" "unparsable value"

# ---- The current build against the reference, as it runs anywhere: no
# BLAS kernel or thread count pinned, the solver's own step selection (the
# reference's had no stability limit detection), beta from whichever
# eigen-solver the hull's size calls for. Its System 2 had the hull in
# nodal coordinates, the reference formulation beside the default modal
# one (a reduced model of the same hull, compared with it in
# tests/test_system2_sim.c), which the run here asks for.
# --plain-header: the reference's header, names only (the paper's CSV).
run run "$REPO_ROOT/examples/apc6x6.yaml" -o "$WORK/out" --no-figures -q \
  --hull-coordinates nodal --plain-header
expect_status 0 "run apc6x6, both systems"
for s in 1 2; do
  compare "$REF/system$s.csv" "$WORK/out/system$s.csv"
  checks=$((checks + 1))
  if [ "$status" -ne 0 ]; then
    echo "$NAME: FAIL: system$s.csv differs from the 5b32e25 reference (exit $status):" >&2
    cat "$OUT" "$ERR" >&2
    failures=$((failures + 1))
  else
    echo "$NAME: system$s.csv matches the 5b32e25 reference:" >&2
    cat "$OUT" >&2
  fi
done

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
