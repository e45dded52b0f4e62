#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# report.md speaks of what the scenario has (docs/report.md,
# "Conclusions"): a truck with only a cargo mount (examples/truck4x4.yaml
# without its driver and engine) on an ISO 8608 random road is reported
# "on the ISO 8608 class C road", its title, window, animation and
# conclusions included, and nothing in it speaks of a driver, an engine or
# a bump; on a measured profile the road is named by its file, escaped for
# Markdown. The Assumptions, the modes, the figures and the values of a
# truck on walking-beam bogies with an anti-roll bar and of a quarter car
# say what those vehicles have, none of the paper's vehicle.
#
# usage: bash tests/cli_report_words.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_report_words
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/truck4x4.yaml "$REPO_ROOT"/examples/*.csv . || exit 2

# The truck without its driver and engine (and the driver's output), its
# comments dropped (a report quotes no comment, but this test must not
# pass by one), on a random road.
python3 - truck4x4.yaml cargo.yaml <<'EOF' || fail "fixture cargo.yaml"
import re
import sys
t = open(sys.argv[1]).read()
for line in (r"  - \{name: driver.*\n", r"  - \{name: engine.*\n", r"  - \{signal: acc, of: driver\}.*\n"):
    t, n = re.subn("^" + line, "", t, flags=re.M)
    assert n == 1, line
road = re.search(r"^road:\n(?:  .*\n)+", t, flags=re.M).group(0)
t = t.replace(road, "road:\n  speed_kmh: 30\n  iso8608:\n    class: C\n    seed: 2026\n"
              "    fade_in: 10\n    front_start: -5\n")
t = re.sub(r" *#.*", "", t)
t = re.sub(r"^scenario: .*", "scenario: cargo", t, flags=re.M)
t = re.sub(r"^description: .*", "description: a 4x4 truck with a cargo box", t, flags=re.M)
assert not re.search("driver|engine|bump", t, re.I), "the fixture still names them"
open(sys.argv[2], "w").write(t)
EOF

run run cargo.yaml -o "$WORK/cargo" -q --animate
expect_status 0 "run of the cargo truck on a random road"
R=$WORK/cargo/report.md
expect_in "$R" "# cargo: rigid and flexible hull on the ISO 8608 class C road" "the title"
expect_in "$R" "| road window | the vehicle on the ISO 8608 class C road, from " "the road window"
expect_in "$R" "![System 2 (flexible hull) on the ISO 8608 class C road](animation_system2.gif)" \
  "the animation"
expect_in "$R" "On the ISO 8608 class C road, System 2 departs from System 1 by up to " \
  "the conclusions"
expect_in "$R" "cargo" "the mount by its name"
for word in driver engine bump; do
  checks=$((checks + 1))
  ! grep -qi "$word" "$R" || fail "report.md of the cargo truck on a random road says '$word':
$(grep -i -m 3 "$word" "$R")"
done

# A measured profile, named by its file: the underscore and the asterisk
# escaped.
awk 'BEGIN { print "s,z"; for (s = -20; s <= 200; s += 0.5) printf "%g,%g\n", s, (s > 10 && s < 11) ? 0.03 : 0 }' \
  >"my_road*.csv"
sed -e '/^  iso8608:/,$d' cargo.yaml >profile.yaml
printf '  profile:\n    file: "my_road*.csv"\n    front_start: -5\n' >>profile.yaml
sed -n '/^simulation:/,$p' cargo.yaml >>profile.yaml
run run profile.yaml -o "$WORK/profile" -q --system rigid --no-figures
expect_status 0 "run on a measured profile"
head -n 1 "$WORK/profile/report.md" >"$WORK/title"
expect_in "$WORK/title" "# cargo: the vehicle over the profile " "the profile's title"
expect_in "$WORK/title" "my\\_road\\*.csv" "the profile's title: its file's name, escaped"

# not_in FILE TEXT DESCRIPTION: FILE does not contain TEXT (fixed string).
not_in() {
  checks=$((checks + 1))
  ! grep -qF -- "$2" "$1" || fail "$3: '$2' in $(basename "$1"):
$(grep -F -m 3 -- "$2" "$1")"
}

# The 6x6 truck on walking-beam bogies with a front anti-roll bar: the
# springs and shock absorbers of the bogies' corners (LM, RM, LR, RR) are
# not used, so the Assumptions list only the front ones and a line per
# bogie and bar; the paper's figure numbers and windows are not said of it.
cp "$REPO_ROOT"/examples/truck6x6_bogie.yaml . || exit 2
run run truck6x6_bogie.yaml -o "$WORK/bogie" -q
expect_status 0 "run of the bogie truck"
R=$WORK/bogie/report.md
expect_in "$R" "- Shock absorbers: LF, RF: linear, 9000 N s/m." "only the corners with their own dampers"
expect_in "$R" "- Springs: LF, RF: linear, 90000 N/m." "only the corners with their own springs"
expect_in "$R" "  - left: LM at a = 0.65 m ahead of the pivot, LR at b = 0.65 m behind it; the beam 120 kg, 25 kg m^2 in pitch about the pivot; the pivot's spring 320000 N/m, its damper 24000 N s/m." \
  "the left bogie"
expect_in "$R" "  - right: RM at a = 0.65 m ahead of the pivot, RR at b = 0.65 m behind it;" "the right bogie"
expect_in "$R" "front (LF, RF): 60000 N/m." "the anti-roll bar"
expect_in "$R" "Each figure shows the whole run." "no output has a window"
expect_in "$R" "| road.bump.angle\\_deg | 30 | deg |" "the bump's angle as the file wrote it"
expect_in "$R" "The reference vehicle's suspension modes moved by less than 0.1 %" \
  "the mesh's effect on the modes, the reference vehicle's"
for text in "Figs. 12" "Fig. 5" "Fig. 6" "The paper's mesh" "unilateral, unilateral"; do
  not_in "$R" "$text" "the bogie truck's report"
done
# System 2's modes of a bogie's beam carry the bogie's labels, as System
# 1's do; the beam's pitch, which no spring at the pivot resists and whose
# wheels' tire forces cancel at the pivot (a = b, equal wheels), is at
# f = sqrt(k_t (a^2 + b^2) / (J + m_w (a^2 + b^2))) / (2 pi) in both
# systems (the values from the report's table; 4-digit table, so 5e-5 Hz).
python3 - "$R" <<'EOF2' || fail "System 2's bogie modes"
import math, re, sys
t = open(sys.argv[1]).read()
values = dict(re.findall(r"^\| ([a-z_.\\A-Z]+) \| ([^|]+) \|", t, re.M))
v = lambda k: float(values[k.replace("_", "\\_")])
a = v("corners.LM.x") - v("bogies.left.pivot_x")
b = v("bogies.left.pivot_x") - v("corners.LR.x")
assert abs(a - b) < 1e-12, (a, b)
kt, mw = v("corners.LM.wheel.tire_k"), v("corners.LM.wheel.mass")
f = math.sqrt(kt * (a * a + b * b) / (v("bogies.left.beam_inertia") + mw * (a * a + b * b))) / (2 * math.pi)
s2 = t[t.index("### System 2"):t.index("## Model")]
rows = re.findall(r"^\| \d+ \| ([0-9.]+) \| ([^|]+) \|", s2, re.M)
for corner in ("LM", "RM", "LR", "RR"):
    assert not any(d.startswith("wheel hop " + corner + " ") for _, d in rows), (corner, rows)
for side in ("left", "right"):
    pitch = [float(fr) for fr, d in rows if d.startswith("bogie pitch " + side + " ")]
    assert len(pitch) == 1 and abs(pitch[0] - f) < 5e-5, (side, pitch, f)
    assert any(d.startswith("bogie bounce " + side + " ") for _, d in rows), (side, rows)
print("bogie pitch: %.4f Hz closed form" % f)
EOF2
checks=$((checks + 1))

# A rigid quarter car with one load point and no torsion output: its
# outputs' numbered figures are its own, one of them with a window.
python3 - "$REPO_ROOT"/examples/quarter_car_stops.yaml quarter.yaml <<'EOF2' || fail "fixture quarter.yaml"
import re, sys
t = open(sys.argv[1]).read()
t, n = re.subn(r"\{signal: spring_defl, of: F, figure: 2\}",
               "{signal: spring_defl, of: F, figure: 2, window: [0.5, 1.25]}", t)
assert n == 1
t, n = re.subn(r"\{signal: tire_force, of: F, figure: 4\}",
               "{signal: tire_force, of: F, figure: 4, window: [5, 6]}", t)
assert n == 1
open(sys.argv[2], "w").write(t)
EOF2
run run quarter.yaml -o "$WORK/quarter" -q
expect_status 0 "run of the quarter car"
R=$WORK/quarter/report.md
expect_in "$R" "the 30000 N act at the 1 load point and" "one load point"
expect_in "$R" "- Outputs: the scenario's list (docs/vehicle-outputs.md), compressions positive." \
  "no torsion angle among the outputs"
expect_in "$R" "A figure shows the whole run, except where its output has a window (\`window\`): Fig. 2, from 0.5 to 1.25 s. Fig. 4 shows the whole run: its window, 5 to 6 s, lies outside it." \
  "the figures' windows"
expect_in "$R" "![Multibond graph, System 1 (rigid hull)](fig05_bond_graph_system1.png)" \
  "the diagram's caption without the paper's number"
expect_in "$R" "Only System 1 (rigid hull) ran, so nothing is compared (the scenario has no finite-element hull for System 2)." \
  "no System 2 to run"
for text in "torsion" "Figs. 12" "1 load points" "--system both"; do
  not_in "$R" "$text" "the quarter car's report"
done

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
