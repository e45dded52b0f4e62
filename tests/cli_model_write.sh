#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond model: a vehicle scenario written as a model file. The file
# and its matrices appear together and nothing else; `flexbond sim` on it
# gives the outputs `flexbond run` gives (the same digits in the CSV); bad
# options and scenarios whose parts cannot be written exit non-zero and
# write nothing.
#
# usage: bash tests/cli_model_write.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_model_write
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml

run model "$APC" -o "$WORK/m"
expect_status 0 "model apc6x6"
expect_in "$ERR" "apc6x6 (rigid hull): 3 files" "summary line"
checks=$((checks + 1))
[ "$(ls -A "$WORK/m" | sort | tr '\n' ' ')" = \
  ".flexbond-manifest apc6x6.hull.to_attach.mtx apc6x6.hull.to_load.mtx apc6x6.yaml " ] ||
  fail "the model, its two matrices and the manifest: $(ls -A "$WORK/m")"
expect_in "$WORK/m/apc6x6.yaml" "  - {name: susp_RF, type: susp_LF}" \
  "equal corners share one definition"
expect_in "$WORK/m/apc6x6.yaml" "matrix: {mtx: apc6x6.hull.to_attach.mtx}" "large MTF to a file"
# The transformer is dense: the array format keeps it dense on reading.
expect_in "$WORK/m/apc6x6.hull.to_attach.mtx" "%%MatrixMarket matrix array real general" \
  "Matrix Market header"

# The model simulates as the scenario does: the seven outputs of
# system1.csv are probes.csv's first seven, digit for digit.
run sim "$WORK/m/apc6x6.yaml" -o "$WORK/s" -q
expect_status 0 "sim of the written model"
run run "$APC" -o "$WORK/r" --system rigid -q
expect_status 0 "run of the scenario"
checks=$((checks + 1))
if ! cmp -s <(tail -n +2 "$WORK/r/system1.csv") <(tail -n +2 "$WORK/s/probes.csv" | cut -d, -f1-8); then
  fail "probes.csv differs from system1.csv"
fi

# Unilateral contact and a static start are in the language now.
run model "$REPO_ROOT/examples/apc6x6_liftoff.yaml" -o "$WORK/l" -q
expect_status 0 "model apc6x6_liftoff"
expect_in "$WORK/l/apc6x6_liftoff.yaml" "type: contact" "tire contact element"
expect_in "$WORK/l/apc6x6_liftoff.yaml" "initial: static" "static initial state"

# Usage errors and a scenario that does not load: nothing written.
run model "$APC" --system wobbly -o "$WORK/u1"
expect_status 1 "unknown --system"
expect_absent "$WORK/u1" "unknown --system"
run model "$APC"
expect_status 1 "missing -o"
expect_in "$ERR" "missing output directory" "missing -o message"
sed 's/^scenario: apc6x6/scenario: "apc-6x6"/' "$APC" >"$WORK/dash.yaml"
run model "$WORK/dash.yaml" -o "$WORK/d"
expect_status 2 "scenario name that is no name"
expect_absent "$WORK/d" "refused scenario"
run model --help
expect_status 0 "--help"
expect_in "$OUT" "usage: flexbond model SCENARIO.yaml" "usage text"

checks=$((checks + 1))
[ -z "$(find "$WORK" -name '*.tmp*')" ] || fail "no temporary file is left behind"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
