#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The flexbond command on model files: the shipped examples run and write
# what the README says; bad models exit non-zero with `file:line:` and the
# key in the message, and write nothing.
#
# usage: bash tests/cli_model.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_model
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# ---- The quarter car example: CSV header with units, 5 s at 1 kHz,
# solver statistics, a PNG figure.
run sim "$REPO_ROOT/examples/quarter_car.yaml" -o "$WORK/qc" --plot -q
expect_status 0 "sim quarter_car"
checks=$((checks + 1))
head -n 1 "$WORK/qc/probes.csv" | grep -qx \
  't \[s\],x_body \[m\],a_body \[m/s^2\],deflection \[m\],tire_force \[N\],damper_power \[W\]' ||
  fail "probes.csv header: $(head -n 1 "$WORK/qc/probes.csv")"
checks=$((checks + 1))
[ "$(wc -l <"$WORK/qc/probes.csv")" -eq 5002 ] || fail "probes.csv has 5001 samples + header"
checks=$((checks + 1))
tail -n 1 "$WORK/qc/probes.csv" | grep -q '^5,' || fail "last sample at t = 5 s"
expect_in "$WORK/qc/stats.json" '"steps":' "stats.json"
checks=$((checks + 1))
[ "$(head -c 4 "$WORK/qc/probes.png" | od -An -tx1 | tr -d ' ')" = "89504e47" ] ||
  fail "probes.png is a PNG"
checks=$((checks + 1))
[ -z "$(ls -A "$WORK/qc" | grep -v -x -e probes.csv -e stats.json -e probes.png -e .flexbond-manifest)" ] ||
  fail "no temporary files left in the output directory"

run diagram "$REPO_ROOT/examples/two_dof_fields.yaml" -o "$WORK/d.dot"
expect_status 0 "diagram two_dof_fields"
expect_in "$WORK/d.dot" "digraph" "diagram writes DOT"
run eig "$REPO_ROOT/examples/two_dof_fields.yaml"
expect_status 0 "eig two_dof_fields"
# The APC's hull on six springs is statically indeterminate: three zero eigenvalues (as
# flexbond modes counts them), which dgeev returns as round-off (1e-15, with a spurious
# imaginary part): counted and left out, the table holding only the 22 others.
run eig "$REPO_ROOT/examples/apc6x6.yaml"
expect_status 0 "eig apc6x6"
expect_in "$OUT" "3 zero eigenvalues (|lambda| <= " "eig counts the zero eigenvalues"
expect_in "$OUT" "25 states, 14 real eigenvalues, 4 complex pairs" "eig counts the rest"
grep -Eq '^ +[0-9]+ +-?[0-9.]+e-1[0-9]' "$OUT" && fail "eig lists round-off as an eigenvalue"
[ "$(grep -Ec '^ +[0-9]+ ' "$OUT")" = 18 ] || fail "eig: 18 table rows (14 real, 4 pairs)"
run causality "$REPO_ROOT/examples/quarter_car.yaml"
expect_status 0 "causality quarter_car"
expect_in "$OUT" "stroke at Ms" "causality lists strokes"

# ---- A spring drawn with its bond pointing away from it: the model runs
# (it is legal), with a warning at the bond's line, for every command
# that reads a model file, and none for the shipped examples.
printf '%s\n' 'model: backwards' 'elements:' '  - {name: F, type: Se, value: 1}' \
  '  - {name: J, type: 1}' '  - {name: M, type: I, m: 1}' '  - {name: K, type: C, k: 100}' \
  'bonds: [[F, J], [J, M], [K, J]]' 'simulation: {t_end: 0.1}' >"$WORK/backwards.yaml"
for cmd in sim causality eig diagram; do
  case $cmd in
  sim) run sim "$WORK/backwards.yaml" -o "$WORK/backwards" -q ;;
  diagram) run diagram "$WORK/backwards.yaml" -o "$WORK/backwards.dot" ;;
  *) run "$cmd" "$WORK/backwards.yaml" ;;
  esac
  expect_status 0 "$cmd of a model with a bond out of a C"
  expect_in "$ERR" "flexbond: warning: $WORK/backwards.yaml:7:25: bonds[2]: bond 'K->J' points out of C 'K'" \
    "$cmd warns at the bond"
done
# What the warning says: the same motion (the bonds' flows), the state,
# the efforts and the powers negated, against the usual drawing.
printf '%s\n' 'model: drawn' 'elements:' '  - {name: F, type: Se, value: 1}' \
  '  - {name: J, type: 1}' '  - {name: M, type: I, m: 1}' '  - {name: K, type: C, k: 100}' \
  '  - {name: D, type: R, r: 2}' \
  'bonds: [[F, J], {name: bm, from: J, to: M}, [J, K], {name: bd, from: J, to: D}]' \
  'probes: [{state: M}, {effort: bm}, {flow: bm}, {effort: bd}, {flow: bd}, {power: bd}]' \
  'simulation: {t_end: 0.5, sample_rate: 100}' >"$WORK/drawn.yaml"
sed -e 's/from: J, to: M/from: M, to: J/' -e 's/from: J, to: D/from: D, to: J/' \
  "$WORK/drawn.yaml" >"$WORK/reversed.yaml"
run sim "$WORK/drawn.yaml" -o "$WORK/drawn" -q
expect_status 0 "sim drawn the usual way"
run sim "$WORK/reversed.yaml" -o "$WORK/reversed" -q
expect_status 0 "sim with the I and R bonds reversed"
checks=$((checks + 1))
# Columns: t, p, e_bm, f_bm, e_bd, f_bd, P_bd; flows equal, the rest negated,
# to the CSV's 10 significant digits (the two runs take the same steps).
paste -d, "$WORK/drawn/probes.csv" "$WORK/reversed/probes.csv" | awk -F, 'NR > 1 {
    for (k = 2; k <= 7; ++k) {
      s = (k == 4 || k == 6) ? 1 : -1
      if ($k - s * $(k + 7) > 1e-9 * (1 + ($k < 0 ? -$k : $k)) ||
          s * $(k + 7) - $k > 1e-9 * (1 + ($k < 0 ? -$k : $k))) bad = 1
    }
  } END { exit bad }' || fail "a reversed bond changes the motion or not only the signs"
# A nonlinear law reversed changes the motion, as its warning says: the
# table damper's bond drawn out of it swaps its compression and rebound
# branches, and the body moves otherwise (by more than a tenth of its
# travel).
sed 's/  - {name: b_damper, from: defl, to: Cs}/  - {name: b_damper, from: Cs, to: defl}/' \
  "$REPO_ROOT/examples/quarter_car_table.yaml" >"$WORK/qct_reversed.yaml"
cp "$REPO_ROOT/examples/damper_fv.csv" "$WORK/"
run sim "$REPO_ROOT/examples/quarter_car_table.yaml" -o "$WORK/qct" -q
expect_status 0 "sim quarter_car_table"
run sim "$WORK/qct_reversed.yaml" -o "$WORK/qct_reversed" -q
expect_status 0 "sim quarter_car_table with the damper's bond reversed"
expect_in "$ERR" "compression and extension swap, and the motion differs" "warning of a reversed table"
checks=$((checks + 1))
paste -d, "$WORK/qct/probes.csv" "$WORK/qct_reversed/probes.csv" | awk -F, -v n="$(head -1 "$WORK/qct/probes.csv" | awk -F, '{print NF}')" '
  NR > 1 { d = $2 - $(2 + n); if (d < 0) d = -d; if (d > worst) worst = d
           a = $2 < 0 ? -$2 : $2; if (a > range) range = a }
  END { exit !(worst > 0.1 * range) }' || fail "a reversed table damper leaves the motion as it was"
for model in quarter_car quarter_car_table two_dof_fields; do
  run causality "$REPO_ROOT/examples/$model.yaml"
  checks=$((checks + 1))
  grep -q warning "$ERR" && fail "$model.yaml: no warning expected, got $(cat "$ERR")"
done

# ---- Bad models: status, `file:line:` and phrase; no output written.
good='model: m
elements:
  - {name: F, type: Se, value: 1}
  - {name: J, type: 1}
  - {name: m, type: I, m: 2}
bonds:
  - [F, J]
  - [J, m]
simulation: {t_end: 1}'

# bad_model NAME STATUS PHRASE LINE: writes $WORK/NAME.yaml from stdin,
# runs sim and diagram on it, checks the status and the message.
bad_model() {
  local file=$WORK/$1.yaml
  cat >"$file"
  run sim "$file" -o "$WORK/out_$1"
  expect_status "$2" "$1: sim"
  expect_in "$ERR" "$file:$4:" "$1: sim message has file:line"
  expect_in "$ERR" "$3" "$1: sim message"
  expect_absent "$WORK/out_$1" "$1: sim output"
  run diagram "$file" -o "$WORK/$1.dot"
  expect_status "$2" "$1: diagram"
  expect_absent "$WORK/$1.dot" "$1: diagram output"
}

# libfyaml notices the unclosed mapping at the next line.
bad_model syntax 2 "missing comma in flow mapping" 4 <<'EOF2'
model: m
elements:
  - {name: F, type: Se, value: 1
bonds: []
EOF2
bad_model unknown_type 2 "unknown element type 'Q'" 3 <<'EOF2'
model: m
elements:
  - {name: F, type: Q}
EOF2
bad_model missing_param 2 "ms" 3 <<'EOF2'
model: m
elements:
  - {name: m, type: I, m: ms}
EOF2
bad_model negative_mass 2 "m" 3 <<'EOF2'
model: m
elements:
  - {name: m, type: I, m: -250}
EOF2
bad_model dimension 2 "dimension" 6 <<'EOF2'
model: m
elements:
  - {name: J, type: 1, dim: 2}
  - {name: m, type: I, m: 1}
bonds:
  - [J, m]
EOF2
bad_model nan_value 2 "elements[0].m" 3 <<'EOF2'
model: m
elements:
  - {name: m, type: I, m: .nan}
EOF2

# Derivative causality: exit 3, the element and bond named, nothing written.
cat >"$WORK/deriv.yaml" <<'EOF2'
model: m
elements:
  - {name: F, type: Se, value: 1}
  - {name: J, type: 1}
  - {name: m, type: I, m: 2}
  - {name: m2, type: I, m: 1}
bonds:
  - [F, J]
  - [J, m]
  - {name: b_m2, from: J, to: m2}
EOF2
run sim "$WORK/deriv.yaml" -o "$WORK/out_deriv"
expect_status 3 "derivative causality"
expect_in "$ERR" "I 'm2' is in derivative causality on bond 'b_m2'" "derivative causality"
expect_absent "$WORK/out_deriv" "derivative causality output"

# The good model itself runs.
printf '%s\n' "$good" >"$WORK/good.yaml"
run sim "$WORK/good.yaml" -o "$WORK/out_good" -q
expect_status 0 "good model"

# ---- An output file that is not a plain file (io/out.c): a symbolic link
# is followed (its file replaced, the link kept); a FIFO or a device gets
# the complete output written into it and stays what it was; a directory
# or a link to nothing is refused (exit 5) with nothing written.
DOT=$REPO_ROOT/examples/two_dof_fields.yaml
run diagram "$DOT" -o "$WORK/ref.dot"
expect_status 0 "diagram into a plain file"
echo old >"$WORK/linked.dot"
ln -s linked.dot "$WORK/link.dot"
run diagram "$DOT" -o "$WORK/link.dot"
expect_status 0 "diagram into a symbolic link"
checks=$((checks + 1))
[ -L "$WORK/link.dot" ] && cmp -s "$WORK/linked.dot" "$WORK/ref.dot" ||
  fail "diagram into a symbolic link: the link is kept and its file replaced"
mkfifo "$WORK/fifo.dot"
# A regression would replace the FIFO and leave its reader waiting: time it out.
timeout 10 cat "$WORK/fifo.dot" >"$WORK/from_fifo.dot" &
reader=$!
run diagram "$DOT" -o "$WORK/fifo.dot"
expect_status 0 "diagram into a FIFO"
wait "$reader"
checks=$((checks + 1))
[ -p "$WORK/fifo.dot" ] && cmp -s "$WORK/from_fifo.dot" "$WORK/ref.dot" ||
  fail "diagram into a FIFO: the reader gets the whole output and the FIFO stays one"
# A device of our own (mknod needs root): a null and a full one.
if mknod "$WORK/null" c 1 3 2>/dev/null && mknod "$WORK/full" c 1 7 2>/dev/null; then
  run diagram "$DOT" -o "$WORK/null"
  expect_status 0 "diagram into a null device"
  checks=$((checks + 1))
  [ -c "$WORK/null" ] || fail "diagram into a null device: still a device"
  run diagram "$DOT" -o "$WORK/full"
  expect_status 5 "diagram into a full device"
  expect_in "$ERR" "full: write failed: No space left on device" "diagram into a full device"
  checks=$((checks + 1))
  [ -c "$WORK/full" ] || fail "diagram into a full device: still a device"
fi
# A link to the standard output (as /dev/stdout is; a link of our own, so
# that a regression replaces it, not /dev/stdout) into a file the shell
# appends to: the earlier line stays, then the output.
ln -s /proc/self/fd/1 "$WORK/stdout_link"
echo earlier >"$WORK/appended.dot"
"$FLEXBOND" diagram "$DOT" -o "$WORK/stdout_link" >>"$WORK/appended.dot" 2>"$ERR"
status=$?
expect_status 0 "diagram into the standard output appended to a file"
checks=$((checks + 1))
[ -L "$WORK/stdout_link" ] && { echo earlier; cat "$WORK/ref.dot"; } | cmp -s - "$WORK/appended.dot" ||
  fail "diagram into the standard output appended to a file: the link stays, the file holds" \
    "its line, then the output"
mkdir "$WORK/dir.dot"
run diagram "$DOT" -o "$WORK/dir.dot"
expect_status 5 "diagram into a directory"
expect_in "$ERR" "dir.dot: cannot create file: Is a directory" "diagram into a directory"
ln -s no/such/place.dot "$WORK/dangling.dot"
run diagram "$DOT" -o "$WORK/dangling.dot"
expect_status 5 "diagram into a link to nothing"
expect_in "$ERR" "dangling.dot: cannot create file: a symbolic link to nothing" \
  "diagram into a link to nothing"
checks=$((checks + 1))
[ -z "$(find "$WORK" -name '*.tmp.*')" ] || fail "no temporary file is left behind"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
