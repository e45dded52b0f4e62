#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Basic checks of the flexbond command that need no model: help, version,
# usage errors (exit 1), and a missing model file (exit 5 or 2, path in the
# message, no output created). Exit codes are documented in src/cli/main.c.
#
# usage: bash tests/cli_basic.sh PATH/TO/flexbond REPO_ROOT
set -u

NAME=cli_basic
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# ---- Help and version go to stdout with status 0.
for flag in --help -h; do
  run "$flag"
  expect_status 0 "flexbond $flag"
  expect_in "$OUT" "usage: flexbond" "flexbond $flag"
  for cmd in sim diagram causality eig run modes; do
    expect_in "$OUT" "$cmd" "flexbond $flag lists $cmd"
  done
done

run --version
expect_status 0 "flexbond --version"
checks=$((checks + 1))
[ "$(cat "$OUT")" = "flexbond 0.1.0" ] || fail "--version prints 'flexbond 0.1.0'"

for cmd in sim diagram causality eig run modes; do
  run "$cmd" --help
  expect_status 0 "flexbond $cmd --help"
  expect_in "$OUT" "usage: flexbond $cmd" "flexbond $cmd --help"
done

# ---- Usage errors: status 1 and a message naming the problem.
run
expect_status 1 "flexbond without arguments"
expect_in "$ERR" "usage: flexbond" "flexbond without arguments"

run frobnicate
expect_status 1 "unknown command"
expect_in "$ERR" "unknown command 'frobnicate'" "unknown command"

run --frobnicate
expect_status 1 "unknown top-level option"
expect_in "$ERR" "--frobnicate" "unknown top-level option"

run sim "$WORK/m.yaml" -o "$WORK/out" --bogus
expect_status 1 "unknown sim option"
expect_in "$ERR" "unknown option '--bogus'" "unknown sim option"

run sim "$WORK/m.yaml" -o
expect_status 1 "-o without a value"
expect_in "$ERR" "'-o' needs a value" "-o without a value"

run sim "$WORK/m.yaml"
expect_status 1 "sim without -o"
expect_in "$ERR" "-o DIR" "sim without -o"

run sim -o "$WORK/out"
expect_status 1 "sim without a model"
expect_in "$ERR" "missing MODEL" "sim without a model"

run sim "$WORK/a.yaml" "$WORK/b.yaml" -o "$WORK/out"
expect_status 1 "sim with two models"
expect_in "$ERR" "unexpected argument" "sim with two models"

run causality
expect_status 1 "causality without a model"

run eig --quiet "$WORK/m.yaml"
expect_status 1 "eig does not take --quiet"

run diagram --help=yes
expect_status 1 "flag given a value"

# Numeric options must be finite numbers > 0, and the message names them.
for bad in "--t-end 0" "--t-end -1" "--rtol abc" "--rtol 1e-3x" "--rtol inf" \
  "--sample-rate nan" "--sample-rate 1e999" "--t-end="; do
  set -- $bad
  name=${1%%=*}
  run sim "$WORK/m.yaml" -o "$WORK/out" "$@"
  expect_status 1 "sim $bad"
  expect_in "$ERR" "option '$name' needs a finite number > 0" "sim $bad"
done
expect_absent "$WORK/out" "usage errors"

# ---- A model file that does not exist: an I/O (5) or input (2) error
# naming the path, and nothing written.
missing=$WORK/no_such_model.yaml
run sim "$missing" -o "$WORK/out/run1" --t-end 1
checks=$((checks + 1))
[ "$status" -eq 5 ] || [ "$status" -eq 2 ] || fail "sim missing model: exit status $status"
expect_in "$ERR" "flexbond: " "sim missing model"
expect_in "$ERR" "$missing" "sim missing model"
expect_absent "$WORK/out" "sim missing model"

run diagram "$missing" -o "$WORK/d.dot"
checks=$((checks + 1))
[ "$status" -eq 5 ] || [ "$status" -eq 2 ] || fail "diagram missing model: exit status $status"
expect_in "$ERR" "$missing" "diagram missing model"
expect_absent "$WORK/d.dot" "diagram missing model"

for cmd in causality eig; do
  run "$cmd" "$missing"
  checks=$((checks + 1))
  [ "$status" -eq 5 ] || [ "$status" -eq 2 ] || fail "$cmd missing model: exit status $status"
  expect_in "$ERR" "$missing" "$cmd missing model"
done

# Only the files above were ever made in the scratch directory.
checks=$((checks + 1))
leftover=$(cd "$WORK" && ls -A | grep -vx -e stdout -e stderr)
[ -z "$leftover" ] || fail "stray files in scratch directory: $leftover"

echo "cli_basic: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
