#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond sweep: twelve speeds of System 1 give twelve rows, speeds 5 to
# 60 in order, each with the header's metrics, and the rows of two speeds
# equal what `flexbond run --system rigid` reports in summary.json for a
# copy of the scenario at that speed (independent path: the file edited
# by sed, not by an override); one thread and two give the same numbers;
# a two-key grid has the product of the counts as rows, in grid order; a
# case whose bump no longer fits in the run is marked in the error column
# while the others run, with exit 4 and one final message on stderr, also
# under -q; a categorical first key and System 2 run; usage errors exit 1
# and write nothing; a directory that cannot be made exits 5.
#
# usage: bash tests/cli_sweep.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_sweep
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml
OUTPUTS="tire_force_LF spring_defl_RF torsion driver_acc shock_power_LM tire_defl_RM tire_power_LR"
# sweep.csv's metric columns with their units (a count or ratio has none).
UNITS=(N m rad m/s^2 W m W)
METRICS=""
i=0
for o in $OUTPUTS; do
  u=${UNITS[$i]}
  METRICS="$METRICS,${o}_peak [$u],${o}_min [$u],${o}_rms [$u]"
  i=$((i + 1))
done
METRICS="$METRICS,min_tire_force [N],contact_loss_intervals,ride_a_w_rms [m/s^2],ride_mtvv [m/s^2]"
METRICS="$METRICS,ride_vdv [m/s^1.75],ride_crest_factor,ride_jerk_peak [m/s^3],ride_jerk_rms [m/s^3]"
METRICS="$METRICS,solver_steps"

# check_python DESCRIPTION ARGS... < SCRIPT: the script exits 0.
check_python() {
  local what=$1
  shift
  checks=$((checks + 1))
  python3 - "$@" || fail "$what"
}

# ---- Twelve speeds of System 1.
# -j 2 explicitly: the -j 1 comparison below must face a threaded run
# whatever the machine.
run sweep "$APC" --set speed_kmh=5:5:60 -j 2 -o "$WORK/speeds"
expect_status 0 "sweep of 12 speeds"
expect_in "$ERR" "flexbond sweep: case 3/12 (speed_kmh=15): ok" "progress line of case 3"
checks=$((checks + 1))
[ "$(ls -A "$WORK/speeds" | tr '\n' ' ')" = ".flexbond-manifest sweep.csv sweep.png " ] ||
  fail "sweep writes sweep.csv and sweep.png, and removes its journal: $(ls -A "$WORK/speeds")"
checks=$((checks + 1))
[ "$(head -1 "$WORK/speeds/sweep.csv")" = "speed_kmh [km/h]$METRICS,error" ] ||
  fail "sweep.csv header: $(head -1 "$WORK/speeds/sweep.csv")"
check_python "12 rows, speeds 5..60, every metric present" "$WORK/speeds/sweep.csv" <<'EOF'
import csv, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
assert [r["speed_kmh"] for r in rows] == [str(v) for v in range(5, 65, 5)], rows
for r in rows:
    assert r["error"] == "", r["error"]
    for k, v in r.items():
        if k != "error":
            float(v)
    # System 1's hull is rigid: no torsion. The crossing takes 1000+ steps.
    assert float(r["torsion_peak"]) == 0 and float(r["solver_steps"]) > 1000
    assert float(r["tire_force_LF_min"]) <= float(r["tire_force_LF_rms"]) <= float(r["tire_force_LF_peak"])
    assert float(r["min_tire_force"]) <= float(r["tire_force_LF_min"])
EOF

# Two of the cases against flexbond run on an edited copy of the file:
# sweep.csv holds every bit of each double, summary.json 10 significant
# digits; printed the way summary.json prints them (%.10g, which Python's
# % formats the same way, correctly rounded), they must read back equal.
for speed in 10 35; do
  sed "s/^  speed_kmh: 10 /  speed_kmh: $speed /" "$APC" >"$WORK/apc_$speed.yaml"
  run run "$WORK/apc_$speed.yaml" --system rigid --no-figures -q -o "$WORK/run_$speed"
  expect_status 0 "run at $speed km/h"
  check_python "sweep row at $speed km/h equals run's summary.json" \
    "$WORK/speeds/sweep.csv" "$WORK/run_$speed/summary.json" "$speed" <<'EOF'
import csv, json, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = {r["speed_kmh"]: r for r in map(by_name, csv.DictReader(open(sys.argv[1])))}
s1 = json.load(open(sys.argv[2]))["system1"]
row = rows[sys.argv[3]]
problems = []
for name, o in s1["outputs"].items():
    for stat in ["peak", "min", "rms"]:
        if float("%.10g" % float(row[name + "_" + stat])) != o[stat]:
            problems.append("%s_%s: sweep %s, run %r" % (name, stat, row[name + "_" + stat], o[stat]))
if int(row["solver_steps"]) != s1["solver"]["steps"]:
    problems.append("steps %s vs %s" % (row["solver_steps"], s1["solver"]["steps"]))
# The contact-loss intervals of the whole run that end after the first bump
# entry; the smallest reaction over that span is at most the LF one.
t0 = s1["bump_window"][0]
want = sum(1 for t in s1["tire_contact"]["contact_loss_intervals"] if t["to"] >= t0)
if int(row["contact_loss_intervals"]) != want:
    problems.append("contact-loss intervals %s vs %d" % (row["contact_loss_intervals"], want))
for name in ["a_w_rms", "mtvv", "vdv", "crest_factor", "jerk_peak", "jerk_rms"]:
    if float("%.10g" % float(row["ride_" + name])) != s1["ride"][name]:
        problems.append("ride %s: sweep %s, run %r" % (name, row["ride_" + name], s1["ride"][name]))
assert not problems, problems
EOF
done

# One thread: the same file, byte for byte, quietly.
run sweep "$APC" --set speed_kmh=5:5:60 -o "$WORK/speeds_j1" -j 1 -q --no-figures
expect_status 0 "sweep -j 1"
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "-q prints nothing"
checks=$((checks + 1))
cmp -s "$WORK/speeds/sweep.csv" "$WORK/speeds_j1/sweep.csv" ||
  fail "-j 1 and -j 2 write different sweep.csv files"
# Every number reads back as itself: 17 significant digits at most, and
# fewer where they suffice (the speeds' 5 stays 5).
check_python "shortest exact numbers" "$WORK/speeds/sweep.csv" <<'EOF'
import csv, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
digits = [len(v.lstrip("-").replace(".", "").split("e")[0].lstrip("0"))
          for r in rows for k, v in r.items() if k != "error" and v not in ("", "0")]
assert max(digits) <= 17 and min(digits) < 15, (max(digits), min(digits))
assert any(len(r["tire_force_LF_peak"]) > 12 for r in rows)
EOF

# ---- A two-key grid: 3 x 3 rows, the first key varying slowest.
run sweep "$APC" --set speed_kmh=10,20,30 --set suspensions.axles[0].damper_c=20000:5000:30000 \
  -o "$WORK/grid" --no-figures -q -j 2
expect_status 0 "two-key grid"
checks=$((checks + 1))
[ "$(ls "$WORK/grid")" = "sweep.csv" ] || fail "--no-figures writes only sweep.csv"
check_python "grid rows in order" "$WORK/grid/sweep.csv" <<'EOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
assert rows[0][:2] == ["speed_kmh [km/h]", "suspensions.axles[0].damper_c [N s/m]"], rows[0]
want = [[s, d] for s in ["10", "20", "30"] for d in ["20000", "25000", "30000"]]
assert [r[:2] for r in rows[1:]] == want, [r[:2] for r in rows[1:]]
# Stiffer front dampers (LF and RF) change the LF tire force: the cases differ.
assert len({r[2] for r in rows[1:4]}) == 3
EOF

# ---- --plain-header: the metrics' names only; --plot: the panels of
# sweep.png, by OUTPUT[:STAT] or by a column's name; a metric that does not
# exist, or too many, is a usage error before anything runs.
run sweep "$APC" --set speed_kmh=10,20 -o "$WORK/plots" --plain-header \
  --plot tire_force_LF:min --plot torsion:rms --plot min_tire_force --plot tire_defl_RM_peak -q
expect_status 0 "sweep with --plot and --plain-header"
checks=$((checks + 1))
[ "$(head -1 "$WORK/plots/sweep.csv")" = "speed_kmh$(echo "$METRICS" | sed 's/ \[[^]]*\]//g'),error" ] ||
  fail "sweep --plain-header: header $(head -1 "$WORK/plots/sweep.csv")"
checks=$((checks + 1))
[ "$(head -c 4 "$WORK/plots/sweep.png" | od -An -tx1 | tr -d ' ')" = "89504e47" ] ||
  fail "sweep --plot draws sweep.png"
for bad in torsion:max tire_force_LX ride; do
  run sweep "$APC" --set speed_kmh=10,20 -o "$WORK/badplot" --plot "$bad"
  expect_status 1 "sweep --plot $bad"
  expect_in "$ERR" "--plot $bad: no such metric; give OUTPUT[:peak|min|rms]" "sweep --plot $bad"
done
many=()
for k in $(seq 17); do many+=(--plot torsion); done
run sweep "$APC" --set speed_kmh=10,20 -o "$WORK/badplot" "${many[@]}"
expect_status 1 "sweep with 17 --plot"
expect_in "$ERR" "17 --plot options; sweep.png takes at most 16 panels" "sweep with 17 --plot"
checks=$((checks + 1))
[ ! -e "$WORK/badplot" ] || fail "a refused --plot writes nothing"

# ---- A failing case: at 2 km/h the last wheel leaves the bump at
# 5 + 8.7 m / (2/3.6 m/s) = 20.66 s, after t_end = 15 s.
run sweep "$APC" --set speed_kmh=2,10 -o "$WORK/fail" --no-figures
expect_status 4 "a failing case exits 4"
expect_in "$ERR" "case 1/2 (speed_kmh=2): failed: --set speed_kmh=2: " "failure on stderr"
expect_in "$ERR" "case 2/2 (speed_kmh=10): ok" "the other case runs"
check_python "failed row marked, metrics empty" "$WORK/fail/sweep.csv" <<'EOF'
import csv, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
assert len(rows) == 2
bad, good = rows
assert bad["error"].startswith("--set speed_kmh=2: ") and "the run ends at 15 s, before the last wheel" in bad["error"], bad["error"]
assert "20.66" in bad["error"]
assert all(v == "" for k, v in bad.items() if k not in ("speed_kmh", "error"))
assert good["error"] == "" and float(good["tire_force_LF_peak"]) > 0
EOF
expect_in "$ERR" "flexbond: 1 of 2 cases failed (each has its message in the error column of $WORK/fail/sweep.csv); the first, case 1 (speed_kmh=2): --set speed_kmh=2: " \
  "failed cases: the final message"
# A value the reader refuses fails its case the same way. -q silences the
# progress, not the failure: one message on stderr (docs/errors.md).
run sweep "$APC" --set speed_kmh=fast -o "$WORK/word" --no-figures -q
expect_status 4 "a bad value fails its case"
want="^flexbond: 1 of 1 case failed (.*); the first, case 1 (speed_kmh=fast): "
want="$want--set speed_kmh=fast: $APC:152:14: road.speed_kmh: expression 'fast'"
checks=$((checks + 1))
[ "$(wc -l <"$ERR")" -eq 1 ] && grep -q "$want" "$ERR" ||
  fail "-q with a failed case: one message on stderr"
expect_in "$WORK/word/sweep.csv" "--set speed_kmh=fast: $APC:" "reader's message with --set prefix"
expect_in "$WORK/word/sweep.csv" "road.speed_kmh: expression 'fast'" "reader's message"

# ---- A categorical first key (words), and System 2 (a reduced hull over
# a shortened run: the last wheel leaves the bump at 8.132 s).
run sweep "$APC" --set simulation.initial=zero,static --set speed_kmh=10,20 -o "$WORK/words" -q
expect_status 0 "categorical first key"
checks=$((checks + 1))
[ -s "$WORK/words/sweep.png" ] && [ "$(wc -l <"$WORK/words/sweep.csv")" -eq 5 ] ||
  fail "categorical sweep writes a figure and 4 rows"
run sweep "$APC" --system flexible --set hull.fe.modes=20 --set simulation.t_end=9 \
  -o "$WORK/flex" -q --no-figures
expect_status 0 "System 2"
check_python "System 2 row" "$WORK/flex/sweep.csv" <<'EOF'
import csv, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
# The flexible hull twists: torsion is not zero, unlike System 1's.
assert len(rows) == 1 and rows[0]["error"] == "" and float(rows[0]["torsion_peak"]) > 0, rows
EOF

# ---- A key the file leaves out (wheel.tire_contact, bilateral by
# default), by its bare name: over a 0.3 m bump at 30 km/h a bilateral
# tire pulls the wheel down, a unilateral one never does.
run sweep "$APC" --set tire_contact=bilateral,unilateral --set road.bump.height=0.3 \
  --set speed_kmh=30 -o "$WORK/contact" -q --no-figures
expect_status 0 "a key the file leaves out"
check_python "a key the file leaves out" "$WORK/contact/sweep.csv" <<'EOF'
import csv, sys
# Columns by name, without the units of the header ("torsion_peak [rad]").
by_name = lambda r: {k.split(" [")[0]: v for k, v in r.items()}
rows = list(map(by_name, csv.DictReader(open(sys.argv[1]))))
assert [r["tire_contact"] for r in rows] == ["bilateral", "unilateral"], rows
assert float(rows[0]["min_tire_force"]) < 0 and float(rows[1]["min_tire_force"]) == 0, rows
EOF

# ---- Usage errors: exit 1, nothing written.
usage() {
  local what=$1 text=$2
  shift 2
  run sweep "$@"
  expect_status 1 "$what"
  expect_in "$ERR" "$text" "$what: message"
  expect_absent "$WORK/usage" "$what"
}
usage "ambiguous key" "key 'mass' is ambiguous: it occurs 4 times (hull.mass, mounts[0].mass, mounts[1].mass, wheel.mass)" \
  "$APC" --set mass=1:1:2 -o "$WORK/usage"
usage "absent key" "no key 'sped_kmh' in the scenario (did you mean 'road.speed_kmh'?)" \
  "$APC" --set sped_kmh=1 -o "$WORK/usage"
usage "bad path" "road: has no key 'speed' (its keys: speed_kmh, bump, iso8608, profile, crg)" \
  "$APC" --set road.speed=1 -o "$WORK/usage"
usage "bad path, close key" "simulation: has no key 'max_stpes' (did you mean 'max_steps'?" \
  "$APC" --set simulation.max_stpes=1 -o "$WORK/usage"
usage "item beyond the list" "suspensions.axles: has no item [3] (it has 3)" \
  "$APC" --set suspensions.axles[3].spring_k=1 -o "$WORK/usage"
usage "not a value" "road.bump: is a mapping" "$APC" --set road.bump=1 -o "$WORK/usage"
usage "same value twice" "--set speed_kmh and --set road.speed_kmh both set road.speed_kmh" \
  "$APC" --set speed_kmh=1 --set road.speed_kmh=2 -o "$WORK/usage"
usage "zero step" "step 0 does not lead from 1 to 3" "$APC" --set speed_kmh=1:0:3 -o "$WORK/usage"
usage "wrong direction" "step 1 does not lead from 3 to 1" "$APC" --set speed_kmh=3:1:1 -o "$WORK/usage"
usage "too many values" "more than 10000 values" "$APC" --set speed_kmh=1:1:10001 -o "$WORK/usage"
usage "not a number" "'x' is not a finite number" "$APC" --set speed_kmh=1:x:3 -o "$WORK/usage"
usage "empty list item" "empty value in the list" "$APC" --set speed_kmh=1,,3 -o "$WORK/usage"
usage "no spec" "--set needs KEY=SPEC" "$APC" --set speed_kmh -o "$WORK/usage"
usage "no --set" "give at least one --set" "$APC" -o "$WORK/usage"
usage "no -o" "missing output directory" "$APC" --set speed_kmh=10
usage "bad -j" "option '-j' needs an integer in 1..1024" "$APC" --set speed_kmh=10 -j 0 -o "$WORK/usage"
usage "bad --system" "--system" "$APC" --set speed_kmh=10 --system both -o "$WORK/usage"
usage "no scenario" "missing SCENARIO file" --set speed_kmh=10 -o "$WORK/usage"
# The stop is included to step/1e9: (0.3 - 0.1) / 0.1 is 1.9999999999999998
# in doubles, and 0.1 + 2 x 0.1 is 0.30000000000000004, printed as 0.3.
run sweep "$APC" --set road.bump.height=0.1:0.1:0.3 -o "$WORK/tol" -q --no-figures
expect_status 0 "0.1:0.1:0.3"
checks=$((checks + 1))
[ "$(cut -d, -f1 "$WORK/tol/sweep.csv" | tr '\n' ' ')" = "road.bump.height [m] 0.1 0.2 0.3 " ] ||
  fail "0.1:0.1:0.3 gives 0.1 0.2 0.3: $(cut -d, -f1 "$WORK/tol/sweep.csv" | tr '\n' ' ')"

# ---- Input and I/O errors.
run sweep "$WORK/missing.yaml" --set speed_kmh=10 -o "$WORK/usage"
expect_status 5 "missing scenario"
expect_absent "$WORK/usage" "missing scenario"
touch "$WORK/plain_file"
run sweep "$APC" --set speed_kmh=10 -o "$WORK/plain_file/out" -q
expect_status 5 "unwritable output directory"

run sweep --help
expect_status 0 "sweep --help"
expect_in "$OUT" "--set KEY=SPEC" "help text"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
