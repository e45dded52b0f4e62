#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Strings from the inputs reach the generated documents escaped for their
# language (docs/outputs.md), through the real commands, with the
# characters the loaders accept in names, units and paths: a probe named
# like a spreadsheet formula and a unit with a comma, quotes and markup
# give a probes.csv that Python's csv module reads into the right columns,
# the formula guarded by a '; the model's diagram passes `dot -Tsvg` with
# as many nodes as the example's; a scenario in a directory whose name
# holds < > & | * [ ] ( ) a comma and a quote, run into an output
# directory with a comma and a quote, writes a summary.json that Python's
# json reads and a report.md with no raw <, & or link syntax from the
# path; export's model.json is JSON; the mesh's .vtu is XML; a sweep value
# with a quote comes back exactly from sweep.csv, in the right columns.
#
# usage: bash tests/cli_escape.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_escape
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# check_python DESCRIPTION ARGS... < SCRIPT: the script exits 0.
check_python() {
  local what=$1
  shift
  checks=$((checks + 1))
  python3 - "$@" || fail "$what"
}

# ---- A model with a formula for a probe name and markup in a unit.
QC=$REPO_ROOT/examples/quarter_car.yaml
PROBE='=cmd|x!A0'
UNIT='m,"s" <b>&amp; *y* [l](u)'
python3 - "$QC" "$WORK/qc.yaml" "$PROBE" "$UNIT" <<'EOF'
import json, sys
src, dst, probe, unit = sys.argv[1:5]
text = open(src).read()
# JSON strings are YAML double-quoted scalars.
text = text.replace("{name: tire_force,", "{name: %s," % json.dumps(probe))
text = text.replace("integrate: true, unit: m}", "integrate: true, unit: %s}" % json.dumps(unit))
open(dst, "w").write(text)
EOF
run sim "$WORK/qc.yaml" -o "$WORK/sim" -q
expect_status 0 "sim of the model with a hostile probe name and unit"
check_python "probes.csv: header in 6 columns, the formula guarded, the unit intact" \
  "$WORK/sim/probes.csv" "$PROBE" "$UNIT" <<'EOF'
import csv, sys
path, probe, unit = sys.argv[1:4]
rows = list(csv.reader(open(path, newline="", encoding="utf-8")))
header = rows[0]
assert len(header) == 6, header
assert header[1] == "x_body [%s]" % unit, header[1]
assert header[4] == "'%s [N]" % probe, header[4]
assert all(len(r) == 6 for r in rows[1:]), "a data row is not 6 fields"
EOF
run diagram "$WORK/qc.yaml" -o "$WORK/qc.dot"
expect_status 0 "diagram of the model with a hostile probe name"
run diagram "$QC" -o "$WORK/plain.dot"
expect_status 0 "diagram of the example"
checks=$((checks + 1))
if dot -Tsvg "$WORK/qc.dot" >"$WORK/qc.svg" 2>"$WORK/dot.err" && [ ! -s "$WORK/dot.err" ] &&
  dot -Tsvg "$WORK/plain.dot" >"$WORK/plain.svg"; then
  [ "$(grep -c '<g id="node' "$WORK/qc.svg")" -eq "$(grep -c '<g id="node' "$WORK/plain.svg")" ] ||
    fail "the diagram's node count changed"
else
  fail "dot -Tsvg refuses the diagram: $(head -c 300 "$WORK/dot.err")"
fi

# ---- A scenario in a hostile directory, run into a hostile directory.
DIR='in d<i>&a|b*c,"q"[x](y)'
mkdir -p "$WORK/$DIR"
SCEN=$WORK/$DIR/apc.yaml
cp "$REPO_ROOT/examples/apc6x6.yaml" "$SCEN"
OUTDIR=$WORK/out,\"q\"
run run "$SCEN" --system rigid --no-figures -q -o "$OUTDIR"
expect_status 0 "run of a scenario in a directory with markup in its name"
check_python "summary.json is JSON" "$OUTDIR/summary.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1], encoding="utf-8"))
assert d["scenario"] == "apc6x6", d["scenario"]
EOF
check_python "report.md: the path escaped, nothing raw from it" "$OUTDIR/report.md" "$SCEN" <<'EOF'
import sys
path, scen = sys.argv[1:3]
text = open(path, encoding="utf-8").read()
assert "<" not in text and ">" not in text, "raw < or > in report.md"
assert "&a" not in text.replace("&amp;", ""), "raw & in report.md"
want = scen.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
want = "".join("\\" + c if c in "\\`*_[]#|~" else c for c in want)
row = "| file | %s |" % want
assert row in text, [l for l in text.splitlines() if l.startswith("| file")]
EOF
run export "$SCEN" --system rigid -o "$OUTDIR/export"
expect_status 0 "export of the scenario in the hostile directory"
check_python "model.json is JSON" "$OUTDIR/export/model.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1], encoding="utf-8"))
assert d["scenario"] == "apc6x6" and d["variables"], d["scenario"]
EOF
run mesh "$SCEN" --export "$OUTDIR/hull.vtu"
expect_status 0 "mesh export into the hostile directory"
check_python "the .vtu is XML" "$OUTDIR/hull.vtu" <<'EOF'
import sys, xml.dom.minidom
doc = xml.dom.minidom.parse(sys.argv[1])
names = [a.getAttribute("Name") for a in doc.getElementsByTagName("DataArray")]
assert "node_id" in names, names
EOF

# ---- A sweep value with a quote: its case fails, its row keeps it.
BAD='1"0'
run sweep "$SCEN" --set "speed_kmh=10,$BAD" --system rigid --no-figures -q -o "$OUTDIR/sweep"
expect_status 4 "sweep with a value that is not a number"
check_python "sweep.csv: every row in the header's columns, the value intact" \
  "$OUTDIR/sweep/sweep.csv" "$BAD" <<'EOF'
import csv, sys
path, bad = sys.argv[1:3]
rows = list(csv.reader(open(path, newline="", encoding="utf-8")))
assert len(rows) == 3, rows
assert all(len(r) == len(rows[0]) for r in rows), [len(r) for r in rows]
assert [r[0] for r in rows[1:]] == ["10", bad], [r[0] for r in rows]
assert rows[2][-1].startswith("--set speed_kmh=" + bad), rows[2][-1]
EOF

# ---- Every message is one line, whatever text it quotes: a line break in an option's value,
# a scenario's name or a directory is written \n (fb_err_escape), in errors and status lines.
NL='a
b'
run sweep "$SCEN" --system rigid --set speed_kmh=5,10 --plot "$NL" -o "$OUTDIR/nl"
expect_status 1 "sweep --plot with a line break"
expect_in "$ERR" "--plot a\nb: no such metric" "sweep --plot: the line break escaped"
checks=$((checks + 1))
[ "$(wc -l < "$ERR")" -eq 2 ] || fail "sweep --plot with a line break: not one line and the hint"
run "$NL"
expect_status 1 "an unknown command with a line break"
expect_in "$ERR" "unknown command 'a\nb'" "unknown command: the line break escaped"
mkdir -p "$WORK/nl" && cp "$SCEN" "$WORK/nl/$NL.yaml"
run run "$WORK/nl/$NL.yaml" --system rigid --no-figures -o "$WORK/nl/$NL"
expect_status 0 "run of a scenario whose name has a line break"
checks=$((checks + 1))
! grep -q '^b' "$ERR" || fail "run: a status line broken by the scenario's name"
expect_in "$ERR" "a\nb" "run: the name escaped in the status lines"

# ---- A data file named by mistake (a password file as a damper table): the message names the
# file, line and column, never the file's text; only the terminal sees the one field that
# failed, and sweep.csv (an output file) none of it.
mkdir -p "$WORK/secret"
cp "$REPO_ROOT/examples/apc6x6_shock_table.yaml" "$REPO_ROOT"/examples/shock_*.csv "$WORK/secret/"
printf 'root:$6$SECRETHASH:19000:0:99999:7:::\ndaemon:*:19000\n' > "$WORK/secret/shadow"
printf 'v,F\n0,0\n1,SECRETFIELD\n' > "$WORK/secret/field.csv"
T=suspensions.axles[0].damper_table.file
run sweep "$WORK/secret/apc6x6_shock_table.yaml" --system rigid --no-figures -q \
  --set "$T=shock_front.csv,shadow,field.csv" -o "$WORK/secret/s"
expect_status 4 "sweep with a password file as a damper table"
checks=$((checks + 1))
! grep -q SECRET "$WORK/secret/s/sweep.csv" || fail "sweep.csv quotes a data file's text"
checks=$((checks + 1))
! grep -q SECRETHASH "$ERR" || fail "stderr quotes more of a data file than the field that failed"
expect_in "$WORK/secret/s/sweep.csv" "shadow:1: no column 'v' among the header's 1 field" \
  "sweep.csv: the header's failure located"
expect_in "$WORK/secret/s/sweep.csv" "field.csv:3: column 'F': not a number" \
  "sweep.csv: the field's failure located"
sed 's/shock_front\.csv/field.csv/' "$WORK/secret/apc6x6_shock_table.yaml" > "$WORK/secret/field.yaml"
run run "$WORK/secret/field.yaml" --system rigid --no-figures -o "$WORK/secret/r"
expect_status 2 "run with a bad field in a damper table"
expect_in "$ERR" "field.csv:3: column 'F': not a number (read: 'SECRETFIELD')" \
  "run: the terminal sees the field that failed"

# ---- The same for a mesh deck: its text reaches the terminal as the one field that failed,
# never a message that goes into sweep.csv.
(cd "$WORK/secret" && "$FLEXBOND" mesh "$REPO_ROOT/examples/apc6x6.yaml" --export hull.inp) \
  >/dev/null 2>&1
sed '0,/^1, /s/^1, [^,]*,/1, SECRETNODE,/' "$WORK/secret/hull.inp" >"$WORK/secret/bad.inp"
sed -e '/^    density: 1 /d' -e '/^    generator:/,/nose_rung_divisions/c\    deck: hull.inp' \
  "$REPO_ROOT/examples/apc6x6.yaml" >"$WORK/secret/deck.yaml"
run sweep "$WORK/secret/deck.yaml" --system flexible --no-figures -q \
  --set "hull.mesh.deck=hull.inp,bad.inp" -o "$WORK/secret/sd"
expect_status 4 "sweep with a mesh deck holding text where a number goes"
checks=$((checks + 1))
! grep -q SECRET "$WORK/secret/sd/sweep.csv" || fail "sweep.csv quotes a mesh deck's text"
expect_in "$WORK/secret/sd/sweep.csv" "bad.inp:" "sweep.csv: the deck's failure located"
sed 's/deck: hull.inp/deck: bad.inp/' "$WORK/secret/deck.yaml" >"$WORK/secret/bad_deck.yaml"
run mesh "$WORK/secret/bad_deck.yaml"
expect_status 2 "mesh of a deck holding text where a number goes"
expect_in "$ERR" "(read: 'SECRETNODE')" "the terminal sees the deck's field that failed"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
