#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond run's hull stresses (docs/stresses.md "Over a run"): on the APC
# shortened to 3 s (a 0.5 m bump met at 1 s), System 2's stress_peaks.csv
# (one row per element, parsed), stress_peak.vtu (well-formed, its cell
# data the CSV's), stress_peak.png, report.md's hot-spot table (the CSV's
# ten highest peaks, in order) and the animation's frames with the von
# Mises stress per element, each frame's at most the CSV's peak (von Mises
# is a norm of the stress components, which are linear between samples,
# so between two samples it is at most the larger of theirs). A hull with
# sections names each element's. --no-stress writes none of it; System 1
# alone writes none and says why once.
#
# usage: bash tests/cli_stress.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_stress
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

SHORT=$WORK/apc_short.yaml
sed -e 's/^  t_end: 15 /  t_end: 3.0 /' -e 's/first_contact: 5.0/first_contact: 1.0/' \
  -e 's/length: 3.70 /length: 0.5 /' "$REPO_ROOT/examples/apc6x6.yaml" >"$SHORT"

run run "$SHORT" -o "$WORK/both" -q --animate --animate-fps 10
expect_status 0 "run --animate"
for f in stress_peaks.csv stress_peak.vtu stress_peak.png; do
  checks=$((checks + 1))
  [ -s "$WORK/both/$f" ] || fail "$f missing or empty"
done
expect_in "$WORK/both/report.md" "## Hull stresses" "report.md's hot spots"
expect_in "$WORK/both/report.md" "](stress_peak.png)" "report.md's peak picture"
if command -v xmllint >/dev/null; then
  for f in stress_peak.vtu animation_system2_0000.vtu; do
    checks=$((checks + 1))
    xmllint --noout "$WORK/both/$f" 2>"$ERR" || fail "$f is not well-formed XML"
  done
fi

checks=$((checks + 1))
python3 - "$WORK/both" <<'PY' || fail "the stress files"
import csv, glob, json, sys
import xml.etree.ElementTree as ET
out = sys.argv[1]
problems = []
def want(cond, what):
    if not cond:
        problems.append(what)
rows = list(csv.DictReader(open(out + "/stress_peaks.csv", newline="")))
want(rows and list(rows[0]) == ["element_id", "x [m]", "y [m]", "z [m]", "von_mises_peak [Pa]",
                                "time [s]", "surface", "range [Pa]", "range_surface"],
     "CSV header %s" % (list(rows[0]) if rows else None))
t0 = json.load(open(out + "/summary.json"))["system2"]["bump_window"][0]
for r in rows:
    want(float(r["von_mises_peak [Pa]"]) > 0, "element %s: peak not positive" % r["element_id"])
    want(t0 - 1e-9 <= float(r["time [s]"]) <= 3.0 + 1e-9,
         "element %s: time %s outside [%g, 3]" % (r["element_id"], r["time [s]"], t0))
    want(r["surface"] in ("top", "bottom") and r["range_surface"] in ("top", "bottom"),
         "element %s: surfaces %s, %s" % (r["element_id"], r["surface"], r["range_surface"]))
    want(float(r["range [Pa]"]) >= 0, "element %s: negative range" % r["element_id"])
def cells(path):
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    arrays = {a.get("Name"): [float(v) for v in a.text.split()]
              for a in piece.find("CellData")}
    return int(piece.get("NumberOfCells")), arrays
n, arrays = cells(out + "/stress_peak.vtu")
want(n == len(rows), "VTU has %d cells, CSV %d rows" % (n, len(rows)))
for name, col in (("element_id", "element_id"), ("von_mises_peak", "von_mises_peak [Pa]"),
                  ("time_of_peak", "time [s]"), ("stress_range", "range [Pa]")):
    vals = arrays.get(name)
    want(vals is not None and len(vals) == n and
         all(abs(v - float(r[col])) <= 1e-9 * max(1.0, abs(v)) for v, r in zip(vals, rows)),
         "VTU cell array %s differs from the CSV" % name)
# Every frame's von Mises below the peak (both printed to 10 digits).
peak = [float(r["von_mises_peak [Pa]"]) for r in rows]
frames = sorted(glob.glob(out + "/animation_system2_*.vtu"))
want(len(frames) > 5, "%d System 2 frames" % len(frames))
worst = 0.0
for f in frames:
    _, a = cells(f)
    vm = a.get("von_mises")
    want(vm is not None and len(vm) >= len(rows), "%s: no von_mises per element" % f)
    if vm:
        worst = max([worst] + [v / p - 1 for v, p in zip(vm, peak)])
want(worst <= 2e-9, "a frame's von Mises exceeds the peak by %.3g of it" % worst)
for f in glob.glob(out + "/animation_system1_*.vtu")[:1]:
    want("von_mises" not in cells(f)[1], "System 1's frames have a von Mises stress")
# The report's hot spots: the CSV's ten highest peaks, in order, in MPa.
order = sorted(range(len(rows)), key=lambda i: (-peak[i], i))[:10]
report = open(out + "/report.md").read().split("## Hull stresses", 1)[-1]
table = [l for l in report.splitlines() if l.startswith("| ") and l[2].isdigit()]
want(len(table) == 10, "%d hot-spot rows" % len(table))
for line, i in zip(table, order):
    cols = [c.strip() for c in line.strip("|").split("|")]
    want(cols[0] == rows[i]["element_id"], "hot spot %s, expected element %s" %
         (cols[0], rows[i]["element_id"]))
    want(abs(float(cols[2]) - peak[i] / 1e6) <= 5e-4 * peak[i] / 1e6,
         "hot spot %s: %s MPa against the CSV's %g Pa" % (cols[0], cols[2], peak[i]))
if problems:
    print("\n".join(problems[:10]), file=sys.stderr)
    sys.exit(1)
PY

# A hull with sections: each element's in the CSV and the report.
run run "$REPO_ROOT/examples/ifv6x6_turret.yaml" -o "$WORK/ifv" -q --no-figures --system flexible
expect_status 0 "run of a hull with sections"
checks=$((checks + 1))
python3 - "$WORK/ifv/stress_peaks.csv" <<'PY' || fail "the sections in the CSV"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
sections = {r["section"] for r in rows}
sys.exit(0 if rows and {"ROOF", "FLOOR"} <= sections else 1)
PY
expect_in "$WORK/ifv/report.md" "| element | section | centroid x, y, z [m] |" \
  "the hot spots' section column"

# --no-stress: none of it.
run run "$SHORT" -o "$WORK/nostress" -q --no-figures --system flexible --no-stress --animate \
  --animate-fps 5
expect_status 0 "run --no-stress"
expect_absent "$WORK/nostress/stress_peaks.csv" "--no-stress"
expect_absent "$WORK/nostress/stress_peak.vtu" "--no-stress"
checks=$((checks + 1))
! grep -q "## Hull stresses" "$WORK/nostress/report.md" || fail "--no-stress: hot spots"
checks=$((checks + 1))
! grep -q 'Name="von_mises"' "$WORK/nostress/animation_system2_0000.vtu" ||
  fail "--no-stress: von Mises in the frames"
expect_in "$WORK/nostress/report.md" "No hull stresses: the run had \`--no-stress\`." \
  "--no-stress: the report says why"

# System 1 alone: no stress files, said once.
run run "$SHORT" -o "$WORK/rigid" --no-figures --system rigid
expect_status 0 "run --system rigid"
expect_absent "$WORK/rigid/stress_peaks.csv" "System 1"
checks=$((checks + 1))
[ "$(grep -c "no hull stresses" "$ERR")" = 1 ] || fail "System 1: the note, once"
expect_in "$WORK/rigid/report.md" "No hull stresses: they are System 2's, and only System 1 (rigid hull) ran." \
  "System 1: the report says why"
run run "$SHORT" -o "$WORK/rigid_q" -q --no-figures --system rigid
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "System 1 with -q: says nothing"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
