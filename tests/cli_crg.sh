#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The `crg` road (docs/roads.md, "OpenCRG surfaces") through the CLI:
#   - examples/apc6x6_crg.yaml (its own surface: the paper's type II bump
#     straight across the road, sampled every 0.05 m) against the same
#     vehicle on the analytic bump at angle 0 meeting it at the same time;
#   - a malformed surface is refused at road.crg.file with the surface's
#     file and line;
#   - the ASAM sample files (../shared/data/opencrg beside the repository;
#     skipped, exit 77, when absent): an ASCII sample runs; belgian_block.crg
#     (binary) is refused at its data's first byte, its copy being short of
#     the bytes its grid needs (tests/test_crg.c says why).
#
# usage: bash tests/cli_crg.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_crg
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/apc6x6.yaml "$REPO_ROOT"/examples/apc6x6_crg.yaml \
  "$REPO_ROOT"/examples/apc6x6_crg.crg . || exit 2

# worst COLUMN A.csv B.csv: max |a - b| over the rows, over the range of B's column.
worst() {
  paste -d, "$2" "$3" | awk -F, -v col="$1" '
    NR == 1 { n = NF / 2; for (i = 1; i <= n; i++) if (index($i, col) == 1) c = i; next }
    { d = $c - $(c + n); if (d < 0) d = -d; if (d > m) m = d
      if (NR == 2 || $(c + n) < lo) lo = $(c + n); if (NR == 2 || $(c + n) > hi) hi = $(c + n) }
    END { printf "%.3g\n", m / (hi - lo) }'
}

# ---- The example against the analytic bump (angle 0: both tracks alike).
run run apc6x6_crg.yaml -o crg --system rigid
expect_status 0 "apc6x6_crg.yaml runs"
sed -e 's/angle_deg: 45 /angle_deg: 0  /' apc6x6.yaml >bump0.yaml
run run bump0.yaml -o bump0 --system rigid
expect_status 0 "the bump at angle 0 runs"
# The surface is the bump sampled every 0.05 m and interpolated by PCHIP:
# the displacements and the driver's acceleration agree within 1e-3 of
# their range (measured: 1e-4, 7e-5, 2.5e-4), while the surface placed one
# sample (0.05 m) late misses by 2.5e-2, 1.9e-2 and 9e-3.
for col in spring_defl_RF tire_defl_RM driver_acc; do
  w=$(worst "$col" crg/system1.csv bump0/system1.csv)
  checks=$((checks + 1))
  awk -v w="$w" 'BEGIN { exit !(w < 1e-3) }' || fail "$col: the OpenCRG bump misses the analytic one by $w of its range"
done
expect_in crg/report.md "the vehicle over the OpenCRG surface ./apc6x6\\_crg.crg" \
  "the report names the surface, escaped"

# ---- A malformed surface: its file and line, under the scenario's key.
sed -e 's/^REFERENCE_LINE_INCREMENT *= 0.05/REFERENCE_LINE_INCREMENT = 5 cm/' apc6x6_crg.crg >bad.crg
sed -e 's/file: apc6x6_crg.crg /file: bad.crg        /' apc6x6_crg.yaml >bad.yaml
run run bad.yaml -o bad --system rigid
expect_status 2 "a malformed surface is refused"
expect_in "$ERR" "road.crg.file: ./bad.crg:10: REFERENCE_LINE_INCREMENT: not a number: '5 cm'" \
  "the surface's line named"
expect_absent bad "nothing written for a refused scenario"

# ---- The ASAM samples, outside the repository.
DATA=$REPO_ROOT/../shared/data/opencrg
if [ ! -d "$DATA" ]; then
  echo "$NAME: SKIPPED the sample-file runs: $DATA is absent"
  [ "$failures" -eq 0 ] || { echo "$NAME: $failures of $checks checks failed" >&2; exit 1; }
  exit 77
fi
sed -e "s|file: apc6x6_crg.crg |file: $DATA/handmade_straight.crg|" \
  -e 's/front_start: -11.888888889/front_start: 0/' apc6x6_crg.yaml >straight.yaml
run run straight.yaml -o straight --system rigid
expect_status 0 "handmade_straight.crg runs"
sed -e "s|file: apc6x6_crg.crg |file: $DATA/belgian_block.crg|" apc6x6_crg.yaml >belgian.yaml
run run belgian.yaml -o belgian --system rigid
if [ "$status" -eq 0 ]; then
  echo "$NAME: belgian_block.crg is an intact copy: it ran"
else
  expect_status 2 "the short copy of belgian_block.crg is refused"
  expect_in "$ERR" "belgian_block.crg: byte 9338: the binary road data (KRBI) is 1369435 bytes" \
    "its data's first byte and size named"
fi

if [ "$failures" -ne 0 ]; then
  echo "$NAME: $failures of $checks checks failed" >&2
  exit 1
fi
echo "$NAME: $checks checks passed"
