#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Strict loading of model and scenario files through the real flexbond
# command (docs/errors.md, "Text, NUL and number checks"): control
# characters in names, units and other one-line text, NUL escapes, integers
# beyond 2^53, hexadecimal numbers in files and on the command line, and
# graph errors and empty documents located at their cause. For every case:
# the exit status, the FILE:LINE:COL: KEY of the cause on stderr, and no
# output directory created; for the gnuplot injection, that its command
# did not run.
#
# usage: bash tests/cli_load_strict.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_load_strict
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

EX=$REPO_ROOT/examples
IN=$WORK/in
mkdir -p "$IN" || exit 2
# Fixtures are named relative to IN, so messages quote them as given.
cd "$IN" || exit 2
PWNED=$WORK/pwned

# at FILE TEXT VALUE: "FILE:LINE:COL:" with LINE the first line of FILE
# holding TEXT and COL the 1-based column of VALUE in that line (through
# the environment: awk -v would read the backslashes of "m\n" as escapes).
at() {
  AT_TEXT=$2 AT_VALUE=$3 awk -v file="$1" '
    index($0, ENVIRON["AT_TEXT"]) {
      printf "%s:%d:%d:", file, NR, index($0, ENVIRON["AT_VALUE"])
      found = 1
      exit
    }
    END { if (!found) printf "NOT-FOUND(%s in %s)", ENVIRON["AT_TEXT"], file }' "$1"
}

# derive NEW FROM SED-ARGS...: NEW is FROM edited by sed; it must differ.
derive() {
  local new=$1 from=$2
  shift 2
  sed "$@" "$from" >"$new"
  checks=$((checks + 1))
  ! cmp -s "$new" "$from" || fail "fixture $new: sed $* changed nothing in $from"
}

# refused STATUS WHAT TEXT... -- ARGS...: flexbond ARGS exits STATUS with
# every TEXT on stderr, creates no output directory $WORK/out and runs no
# injected command.
refused() {
  local want=$1 what=$2
  shift 2
  local texts=()
  while [ "$1" != -- ]; do
    texts+=("$1")
    shift
  done
  shift
  run "$@"
  expect_status "$want" "$what"
  local t
  for t in "${texts[@]}"; do
    expect_in "$ERR" "$t" "$what"
  done
  expect_absent "$WORK/out" "$what"
  expect_absent "$PWNED" "$what"
  rm -rf "$WORK/out" "$PWNED"
}

cp "$EX/quarter_car.yaml" m_ok.yaml
cp "$EX/apc6x6.yaml" s_ok.yaml
run sim m_ok.yaml -o "$WORK/ok" --plot
expect_status 0 "fixture m_ok.yaml"
run mesh s_ok.yaml
expect_status 0 "fixture s_ok.yaml"

# ---- Control characters in one-line text. A line break in a probe's unit
# went into the gnuplot script as a line of its own: '!' runs a shell
# command there.
derive m_unit_nl.yaml m_ok.yaml \
  -e "s|unit: m}|unit: \"m\\\\n!touch $PWNED\"}|"
refused 2 "unit with a line break (double-quoted), sim --plot" \
  "$(at m_unit_nl.yaml 'name: x_body' 'm\n!') probes[0].unit: has a line break" -- \
  sim m_unit_nl.yaml -o "$WORK/out" --plot
# The same as a literal block scalar, in the probe's name and its unit.
derive m_unit_block.yaml m_ok.yaml \
  -e "s|^  - {name: x_body, flow: b_body, integrate: true, unit: m}.*|  - name: x_body\n    flow: b_body\n    unit: \|\n      m\n      !touch $PWNED|"
refused 2 "unit with a line break (literal block), sim --plot" \
  "$(at m_unit_block.yaml '      m' '') probes[0].unit: has a line break" -- \
  sim m_unit_block.yaml -o "$WORK/out" --plot
derive m_name_block.yaml m_ok.yaml \
  -e "s|^  - {name: x_body, flow: b_body, integrate: true, unit: m}.*|  - name: \|\n      x\n      !touch $PWNED\n    flow: b_body|"
refused 2 "probe name with a line break (literal block), sim --plot" \
  "$(at m_name_block.yaml '      x' '') probes[0].name: has a line break" -- \
  sim m_name_block.yaml -o "$WORK/out" --plot
# A tab, an escape and DEL in a unit, a carriage return in a table's file name.
derive m_unit_tab.yaml m_ok.yaml -e 's|unit: m/s^2}|unit: "m\\t/s^2"}|'
refused 2 "unit with a tab" \
  "$(at m_unit_tab.yaml 'name: a_body' 'm\t') probes[1].unit: has a tab" -- \
  sim m_unit_tab.yaml -o "$WORK/out"
derive m_unit_esc.yaml m_ok.yaml -e 's|unit: m/s^2}|unit: "m\\e[31m"}|'
refused 2 "unit with an escape character" \
  "$(at m_unit_esc.yaml 'name: a_body' 'm\e') probes[1].unit: has an escape" -- \
  sim m_unit_esc.yaml -o "$WORK/out"
derive m_unit_del.yaml m_ok.yaml -e 's|unit: m/s^2}|unit: "m\\x7f"}|'
refused 2 "unit with DEL" \
  "$(at m_unit_del.yaml 'name: a_body' 'm\x7f') probes[1].unit: has a delete character" -- \
  sim m_unit_del.yaml -o "$WORK/out"
# A key with a line break (a parameter's name, in the DOT and JSON files).
derive m_key_nl.yaml m_ok.yaml -e 's|^  ms: 250 |  "ms\\nx": 250 |'
refused 2 "parameter key with a line break" \
  "$(at m_key_nl.yaml '"ms' 'ms\n') parameters: a key has a line break" -- \
  sim m_key_nl.yaml -o "$WORK/out"
# The scenario's title (in report.md, summary.json and the figures).
derive s_name_nl.yaml s_ok.yaml -e "s|^scenario: apc6x6|scenario: \"apc\\\\n!touch $PWNED\"|"
refused 2 "scenario name with a line break" \
  "$(at s_name_nl.yaml 'scenario: ' 'apc') scenario: has a line break" -- \
  run s_name_nl.yaml -o "$WORK/out"
derive s_initial_nl.yaml s_ok.yaml -e 's|^  initial: zero |  initial: "zero\\n" |'
refused 2 "scenario choice with a line break" \
  "$(at s_initial_nl.yaml 'initial: ' 'zero') simulation.initial: has a line break" -- \
  run s_initial_nl.yaml -o "$WORK/out"

# ---- NUL escapes: the text was cut there, "250\0junk" read as 250.
derive m_nul.yaml m_ok.yaml -e 's|^  ms: 250 |  ms: "250\\0junk" |'
refused 2 "NUL in a number" \
  "$(at m_nul.yaml 'ms: "' '250') parameters.ms: the value has a NUL" -- \
  sim m_nul.yaml -o "$WORK/out"
derive m_nul_name.yaml m_ok.yaml -e 's|{name: Cs, type: R, r: cs}|{name: "Cs\\0x", type: R, r: cs}|'
refused 2 "NUL in a name" \
  "$(at m_nul_name.yaml 'name: "Cs' 'Cs\0') elements[3].name: the value has a NUL" -- \
  sim m_nul_name.yaml -o "$WORK/out"
derive s_nul.yaml s_ok.yaml -e '0,/spring_k: 145300 /s//spring_k: "145300\\0junk" /'
refused 2 "NUL in a scenario number" \
  "$(at s_nul.yaml 'spring_k: "' '145300') suspensions.axles[0].spring_k: the value has a NUL" -- \
  run s_nul.yaml -o "$WORK/out"

# ---- Integers beyond 2^53 are not all doubles: 2^53 + 1 read as 2^53.
derive m_big.yaml m_ok.yaml -e 's|^  ms: 250 |  ms: 9007199254740993 |'
refused 2 "integer beyond 2^53" \
  "$(at m_big.yaml 'ms: 9' '9') parameters.ms: the integer 9007199254740993 is beyond 2^53" -- \
  sim m_big.yaml -o "$WORK/out"
derive s_big.yaml s_ok.yaml -e '0,/spring_k: 145300 /s//spring_k: -12345678901234567890 /'
refused 2 "scenario integer beyond 2^53" \
  "$(at s_big.yaml 'spring_k: -' '-') suspensions.axles[0].spring_k: the integer -12345678901234567890 is beyond 2^53" -- \
  run s_big.yaml -o "$WORK/out"
# 2^53 itself, and larger numbers with a point or an exponent, still load.
derive m_2p53.yaml m_ok.yaml -e 's|^  kt: 160000 |  kt: 9007199254740992 |' \
  -e 's|^  ks: 16000 |  ks: 9007199254740993.0 |' -e 's|^  cs: 1000 |  cs: 1e20 |'
run causality m_2p53.yaml
expect_status 0 "2^53, a decimal with a point and one with an exponent load"

# ---- Hexadecimal numbers: refused in files as on the command line.
derive m_hex.yaml m_ok.yaml -e 's|^  ms: 250 |  ms: 0xfa |'
refused 2 "hexadecimal in a model" \
  "$(at m_hex.yaml 'ms: 0x' '0x') parameters.ms: '0xfa' is not a decimal number" -- \
  sim m_hex.yaml -o "$WORK/out"
derive s_hex.yaml s_ok.yaml -e 's|^  speed_kmh: 10 |  speed_kmh: 0x1p3 |'
refused 2 "hexadecimal in a scenario" \
  "$(at s_hex.yaml 'speed_kmh: 0x' '0x') road.speed_kmh: '0x1p3' is not a decimal number" -- \
  run s_hex.yaml -o "$WORK/out"
# (inf, nan and 1e999 were refused before, as strtod reports them.)
for opt in --t-end=0x10 --rtol=0x1p-10 --sample-rate=0x400; do
  name=${opt%%=*} value=${opt#*=}
  refused 1 "sim $name $value" "flexbond sim: option '$name' needs a finite number > 0" \
    "(got '$value')" -- sim m_ok.yaml -o "$WORK/out" "$name" "$value"
done

# ---- Graph errors found after loading name the element or bond in the
# file (fb_err.origin, fb_model_blame), in every command that finds them.
cat >g_port.yaml <<'EOF'
model: unconnected
elements:
  - {name: F, type: Se, value: 1}
  - {name: T, type: TF, ratio: 2}
bonds:
  - [F, T.1]
EOF
cat >g_conflict.yaml <<'EOF'
model: conflict
elements:
  - {name: F1, type: Sf, value: 1}
  - {name: F2, type: Sf, value: 2}
  - {name: J, type: 1}
bonds:
  - [F1, J]
  - [F2, J]
EOF
cat >g_composite.yaml <<'EOF'
model: composite_direction
elements:
  - {name: E1, type: Se, value: 1}
  - {name: E2, type: Se, value: 2}
  - {name: H, type: composite, parts: [1, 1]}
  - {name: M, type: I, dim: 2, m: 1}
bonds:
  - [E1, H.1]
  - [H.2, E2]
  - [H.whole, M]
EOF
cat >g_instance.yaml <<'EOF'
model: instance_conflict
subsystems:
  driven:
    ports:
      - {name: a, at: j}
    elements:
      - {name: j, type: 1}
      - {name: S, type: Sf, value: 1}
    bonds:
      - [S, j]
elements:
  - {name: F, type: Sf, value: 1}
  - {name: body, type: 1}
  - {name: p, type: driven}
bonds:
  - [F, body]
  - [body, p.a]
EOF
# Found while the block diagram is built, after the causality: a field
# whose ports get mixed causality.
cat >g_rmixed.yaml <<'EOF'
model: r_mixed
elements:
  - {name: E, type: Se, value: 1}
  - {name: F, type: Sf, value: 1}
  - name: R
    type: R
    ports: 2
    matrix: [[1, 0], [0, 1]]
bonds:
  - [E, R.1]
  - [F, R.2]
EOF
for cmd in sim diagram eig; do
  tail=()
  [ "$cmd" = sim ] && tail=(-o "$WORK/out")
  refused 3 "$cmd: a field with mixed causality" \
    "$(at g_rmixed.yaml 'name: R' 'n') elements[2]: R 'R' has mixed causality" -- \
    "$cmd" g_rmixed.yaml "${tail[@]}"
done
for cmd in causality sim diagram eig; do
  tail=()
  [ "$cmd" = sim ] && tail=(-o "$WORK/out")
  refused 2 "$cmd: unconnected port" \
    "$(at g_port.yaml 'name: T' '{') elements[1]: TF 'T': port 2 is not connected" -- \
    "$cmd" g_port.yaml "${tail[@]}"
  refused 3 "$cmd: causal conflict" \
    "$(at g_conflict.yaml '[F2, J]' '[') bonds[1]: causal conflict at Sf 'F2'" -- \
    "$cmd" g_conflict.yaml "${tail[@]}"
  refused 2 "$cmd: composite power direction" \
    "$(at g_composite.yaml '[H.2, E2]' '[') bonds[1]: composite 'H': part bond 'H.2->E2'" -- \
    "$cmd" g_composite.yaml "${tail[@]}"
  refused 3 "$cmd: causal conflict inside a subsystem instance" \
    "$(at g_instance.yaml '[S, j]' '[') subsystems.driven.bonds[0]: causal conflict at Sf 'p.S'" \
    "(in instance 'p' at $(at g_instance.yaml 'name: p,' '{' | sed 's/:$//'))" -- \
    "$cmd" g_instance.yaml "${tail[@]}"
done

# ---- A document with no content ('---' alone) is an empty file.
printf -- '---\n' >m_dashes.yaml
refused 2 "model of '---' alone" \
  "flexbond: m_dashes.yaml:1:1: the file is empty (no YAML document)" -- \
  sim m_dashes.yaml -o "$WORK/out"
printf -- '--- # nothing\n...\n' >s_dashes.yaml
refused 2 "scenario of '---' alone" \
  "flexbond: s_dashes.yaml:1:1: the file is empty (no YAML document)" -- \
  run s_dashes.yaml -o "$WORK/out"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
