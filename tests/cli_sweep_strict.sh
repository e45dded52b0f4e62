#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond sweep refuses, through the real command, what it once took:
# numbers of a --set spec that are not plain decimals (hexadecimal, inf,
# nan, beyond a double), in ranges and in lists; a control character in a
# --set key or value (C0, DEL, C1), refused at parse time, before any
# case runs; a study of more cases than the bound (docs/sweep.md,
# "Limits"), refused with the counts that make it; and a journal name
# that is a symbolic link or not a regular file. Each refusal checks the
# exit status, the message, and that DIR was not created (or, when it
# existed, not changed). The journal names every file it hashed on one
# line whatever its path: a scenario in a directory whose name has a line
# break is written percent-encoded, resumes to the same sweep.csv as an
# ordinary path, and a change to it is named; an ordinary path is written
# as it is.
#
# usage: bash tests/cli_sweep_strict.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_sweep_strict
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml
JOURNAL=sweep.partial.csv

# guarded ARGS...: run under a time limit, so that a study the code
# under test would run at length fails fast instead; sets $status.
guarded() {
  timeout 120 "$FLEXBOND" "$@" >"$OUT" 2>"$ERR"
  status=$?
}

# listing DIR: what DIR holds, names and contents, to tell it unchanged.
listing() {
  (cd "$1" && ls -lA --time-style=+ && find . -maxdepth 1 -type f -exec cat {} +) | md5sum
}

# refused DESCRIPTION STATUS MESSAGE ARGS...: sweep ARGS -o DIR exits
# STATUS with MESSAGE on stderr, first with DIR absent (not created), then
# with DIR holding an earlier result (not changed).
refused() {
  local what=$1 code=$2 message=$3
  shift 3
  local dir=$WORK/refused
  rm -rf "$dir"
  guarded sweep "$@" -o "$dir" -q --no-figures
  expect_status "$code" "$what"
  expect_in "$ERR" "$message" "$what: message"
  expect_absent "$dir" "$what"
  mkdir -p "$dir" && echo "an earlier result" >"$dir/sweep.csv"
  local before
  before=$(listing "$dir")
  guarded sweep "$@" -o "$dir" -q --no-figures
  expect_status "$code" "$what (DIR existed)"
  expect_in "$ERR" "$message" "$what (DIR existed): message"
  checks=$((checks + 1))
  [ "$(listing "$dir")" = "$before" ] || fail "$what: DIR was changed: $(ls -A "$dir")"
}

# ---- Numbers of a spec: plain decimals only, as the data files and the
# other options read them (fb_parse_decimal).
NOT_DECIMAL="is not a finite number in decimal digits"
# SPEC|the number refused
for case in 0x10:1:0x11\|0x10 10:0x1:12\|0x1 0x1p3:1:10\|0x1p3 10:1:inf\|inf nan:1:12\|nan \
  -inf:1:0\|-inf 10:1:1e999\|1e999; do
  spec=${case%|*}
  refused "range $spec" 1 "--set speed_kmh=$spec: '${case#*|}' $NOT_DECIMAL" "$APC" \
    --set "speed_kmh=$spec"
done
for item in 0x10 0X1A 0x1p3 inf -inf +Infinity nan 'nan(1)' .inf -.Inf .NaN 1e999; do
  refused "list value $item" 1 "--set speed_kmh=10,$item: '$item' $NOT_DECIMAL" "$APC" \
    --set "speed_kmh=10,$item"
done
# Decimals in every form still run, and words and expressions still go
# to the scenario reader (a word it refuses fails its case, exit 4).
guarded sweep "$APC" --set speed_kmh=1e1:5e0:+2e1 -o "$WORK/decimal" -q --no-figures
expect_status 0 "a range in exponent form"
checks=$((checks + 1))
[ "$(cut -d, -f1 "$WORK/decimal/sweep.csv" | tr '\n' ' ')" = "speed_kmh [km/h] 10 15 20 " ] ||
  fail "1e1:5e0:+2e1 gives 10 15 20: $(cut -d, -f1 "$WORK/decimal/sweep.csv" | tr '\n' ' ')"
guarded sweep "$APC" --set speed_kmh=12.5,fast -o "$WORK/word" -q --no-figures
expect_status 4 "a word in a list is the reader's to refuse"
expect_in "$WORK/word/sweep.csv" "unknown name 'fast'" "the word's case failed"

# ---- Control characters in a --set key or value: refused before any
# case runs, the option named with them escaped, on one line.
# control PART WHAT SHOWN ARG: --set ARG is refused for WHAT in its PART,
# the option shown as SHOWN.
control() {
  refused "control character in the $1: $3" 1 "flexbond sweep: --set $3: the $1 has $2 at byte" \
    "$APC" --set "$4"
  checks=$((checks + 1))
  [ "$(wc -l <"$ERR")" -eq 2 ] || fail "$3: the message is not one line (+ the --help hint)"
}
control value "a line break (\\n, U+000A)" "speed_kmh=10\\n20" $'speed_kmh=10\n20'
control value "a carriage return (\\r, U+000D)" "speed_kmh=10\\r" $'speed_kmh=10\r'
control value "a tab (\\t, U+0009)" "speed_kmh=10,\\t20" $'speed_kmh=10,\t20'
control value "a control character (\\x01, U+0001)" "speed_kmh=1\\x010" $'speed_kmh=1\x010'
control value "a control character (\\x7f, U+007F)" "speed_kmh=10,2\\x7f" $'speed_kmh=10,2\x7f'
control value "a control character (\\u0085, U+0085)" "simulation.initial=zero,a\\u0085b" \
  $'simulation.initial=zero,a\xc2\x85b'
control value "a control character (\\u009f, U+009F)" "speed_kmh=1:1:\\u009f" \
  $'speed_kmh=1:1:\xc2\x9f'
control key "a line break (\\n, U+000A)" "speed\\n_kmh=10" $'speed\n_kmh=10'
control key "a control character (\\x1b, U+001B)" "\\x1b[31mspeed_kmh=10" $'\x1b[31mspeed_kmh=10'
# Also in the --set=KEY=SPEC form, and in a later --set of several.
refused "control character, --set= form" 1 "--set speed_kmh=5\\n6: the value has a line break" \
  "$APC" --set road.bump.height=0.1 $'--set=speed_kmh=5\n6'

# ---- The bound on the number of cases: their product, refused with the
# counts before anything is allocated or run.
refused "1e8 cases" 1 "the --set options give 100000000 cases (speed_kmh: 10000 values x \
angle_deg: 10000 values), more than the 100000 a study may have" "$APC" \
  --set speed_kmh=1:1:10000 --set angle_deg=1:1:10000
refused "110000 cases of three keys" 1 "the --set options give 110000 cases (speed_kmh: 100 \
values x angle_deg: 100 values x road.bump.height: 11 values), more than the 100000" "$APC" \
  --set speed_kmh=1:1:100 --set angle_deg=1:1:100 --set road.bump.height=0.1:0.01:0.2
sixteen=()
for k in a b c d e f g h i j k l m n o p; do sixteen+=(--set "$k=1:1:10000"); done
refused "16 keys of 10000 values (1e64 cases)" 1 "the --set options give 1e+64 cases (a: \
10000 values x b: 10000 values" "$APC" "${sixteen[@]}"
# 100000 cases are within the bound: the next check (an unknown key) speaks.
refused "100000 cases" 1 "--set no_such_key: " "$APC" --set no_such_key=1:1:1000 \
  --set speed_kmh=1:1:100

# ---- The journal's name: not followed through a link, a regular file.
planted() {
  local what=$1 message=$2
  shift 2
  local before
  before=$(listing "$WORK/planted")
  guarded sweep "$APC" --set speed_kmh=10 -o "$WORK/planted" -q --no-figures "$@"
  expect_status 5 "$what"
  expect_in "$ERR" "$WORK/planted/$JOURNAL: cannot open: $message" "$what: message"
  checks=$((checks + 1))
  [ "$(listing "$WORK/planted")" = "$before" ] || fail "$what: DIR was changed"
}
mkdir -p "$WORK/planted"
ln -s "$WORK/victim" "$WORK/planted/$JOURNAL"
planted "a link to a missing file" "it is a symbolic link, which the journal is not written"
expect_absent "$WORK/victim" "a link to a missing file: its target"
planted "a link to a missing file, --resume" "it is a symbolic link" --resume
expect_absent "$WORK/victim" "a link to a missing file, --resume: its target"
: >"$WORK/victim"
planted "a link to an empty file, --resume" "it is a symbolic link" --resume
checks=$((checks + 1))
[ ! -s "$WORK/victim" ] || fail "the empty file behind the link was written"
rm "$WORK/planted/$JOURNAL"
mkfifo "$WORK/planted/$JOURNAL"
planted "a FIFO" "not a regular file" --resume
rm "$WORK/planted/$JOURNAL"
mkdir "$WORK/planted/$JOURNAL"
planted "a directory" "Is a directory"

# ---- The journal's file lines. A 60 s run (a case of about 0.1 s), so
# that the study can be killed in the middle; no case fails, so sweep.csv
# holds no path.
sed 's/^  t_end: 15 /  t_end: 60 /' "$APC" >"$WORK/long.yaml"
grep -q '^  t_end: 60 ' "$WORK/long.yaml" || {
  echo "$NAME: cannot lengthen the example's run" >&2
  exit 2
}
ODD="$WORK/new"$'\n'"line%41"
mkdir "$ODD" && cp "$WORK/long.yaml" "$ODD/long.yaml"
SPEEDS=6,10,14,18,22,26,30,34,38,42,46,50,54

# rows DIR: the number of case rows in DIR's journal.
rows() {
  local n
  n=$(grep -c '^[0-9]' "$1/$JOURNAL" 2>/dev/null) || n=0
  echo "$n"
}

# killed SCENARIO DIR: the study of SCENARIO into DIR, killed once its
# journal holds 2 rows.
killed() {
  rm -rf "$2"
  "$FLEXBOND" sweep "$1" --set "speed_kmh=$SPEEDS" --no-figures -j 1 -q -o "$2" \
    >"$OUT" 2>"$ERR" &
  local pid=$! waited=0
  while [ "$(rows "$2")" -lt 2 ] && [ "$waited" -lt 1500 ]; do
    sleep 0.02
    waited=$((waited + 1))
  done
  kill -s KILL "$pid"
  wait "$pid" 2>/dev/null
}

guarded sweep "$WORK/long.yaml" --set "speed_kmh=$SPEEDS" --no-figures -q -o "$WORK/ref"
expect_status 0 "the study, never stopped"

# An ordinary path is written as it is.
killed "$WORK/long.yaml" "$WORK/plain"
checks=$((checks + 1))
[ "$(grep '^# input ' "$WORK/plain/$JOURNAL" | cut -d' ' -f4-)" = "$WORK/long.yaml" ] ||
  fail "an ordinary path is written byte for byte: $(grep '^# input ' "$WORK/plain/$JOURNAL")"

# A line break and a '%' in a directory's name: one line, percent-encoded.
killed "$ODD/long.yaml" "$WORK/odd"
checks=$((checks + 1))
[ "$(grep '^# input ' "$WORK/odd/$JOURNAL" | cut -d' ' -f4-)" = "$WORK/new%0Aline%2541/long.yaml" ] ||
  fail "an odd path is percent-encoded: $(grep -a '^# input ' "$WORK/odd/$JOURNAL")"
checks=$((checks + 1))
if [ ! -s "$WORK/odd/$JOURNAL" ] || grep -qav '^# \|^case,\|^[0-9]' "$WORK/odd/$JOURNAL"; then
  fail "every line of the journal is a comment, the header or a row"
fi
guarded sweep "$ODD/long.yaml" --set "speed_kmh=$SPEEDS" --no-figures -q -o "$WORK/odd" --resume
expect_status 0 "resumed from the journal of an odd path"
checks=$((checks + 1))
cmp -s "$WORK/ref/sweep.csv" "$WORK/odd/sweep.csv" ||
  fail "sweep.csv resumed at an odd path differs from the one never stopped"

# The file changed since: named, as the journal writes it (one line).
killed "$ODD/long.yaml" "$WORK/odd2"
echo "# changed" >>"$ODD/long.yaml"
guarded sweep "$ODD/long.yaml" --set "speed_kmh=$SPEEDS" --no-figures -q -o "$WORK/odd2" --resume
expect_status 1 "resumed after the odd path's file changed"
expect_in "$ERR" "the journal of another study: $WORK/new%0Aline%2541/long.yaml has changed" \
  "the changed file at an odd path is named"
checks=$((checks + 1))
[ "$(wc -l <"$ERR")" -eq 2 ] || fail "the changed file's message is one line"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
