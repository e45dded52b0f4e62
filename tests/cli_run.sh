#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond run and flexbond modes on vehicle scenarios: the APC example
# with System 1 writes exactly the documented files (CSV header, 15 s at
# 1 kHz, valid summary.json agreeing with the CSV, PNGs, report.md); both
# systems on a shortened APC write both CSVs, a comparison in summary.json
# that the CSVs reproduce and a report whose tables and image links are
# complete; bad options and bad scenarios exit non-zero and write nothing;
# a failure while writing takes back what was written.
#
# usage: bash tests/cli_run.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_run
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml
HEADER='t [s],tire_force_LF [N],spring_defl_RF [m],torsion [rad],driver_acc [m/s^2],shock_power_LM [W],tire_defl_RM [m],tire_power_LR [W]'
FIGURES=(fig08_tire_force_LF.png fig09_spring_defl_RF.png fig10_torsion.png
  fig11_driver_acc.png fig12_shock_power_LM.png fig13_tire_defl_RM.png fig14_tire_power_LR.png)
# Each system's multibond graph and block diagram (the paper's Figs. 5, 6).
DIAGRAMS1=(fig05_bond_graph_system1.png fig06_block_diagram_system1.png)
DIAGRAMS2=(fig05_bond_graph_system2.png fig06_block_diagram_system2.png)
# The frequency response of every output but the powers (flexbond freq's figures).
BODES=(bode_tire_force_LF.png bode_spring_defl_RF.png bode_torsion.png bode_driver_acc.png
  bode_tire_defl_RM.png)
EXPECTED_FILES=$(printf '%s\n' .flexbond-manifest "${FIGURES[@]}" "${DIAGRAMS1[@]}" "${BODES[@]}" report.md \
  summary.json system1.csv | sort)

# expect_files DIR DESCRIPTION: DIR holds exactly the files of a run.
expect_files() {
  checks=$((checks + 1))
  [ "$(ls -A "$1" | sort)" = "$EXPECTED_FILES" ] || fail "$2: files $(ls -A "$1" | tr '\n' ' ')"
}

# check_summary DIR INITIAL PAYLOAD: summary.json is valid JSON with every
# documented key, the bump window of the data sheet, and statistics that a
# second computation from system1.csv reproduces.
check_summary() {
  checks=$((checks + 1))
  python3 -m json.tool "$1/summary.json" >/dev/null || fail "summary.json is not valid JSON"
  checks=$((checks + 1))
  python3 - "$1" "$2" "$3" <<'EOF' || fail "summary.json contents ($1)"
import csv, json, math, sys
out, initial, payload = sys.argv[1:4]
d = json.load(open(out + "/summary.json"))
names = ["tire_force_LF", "spring_defl_RF", "torsion", "driver_acc",
         "shock_power_LM", "tire_defl_RM", "tire_power_LR"]
units = ["N", "m", "rad", "m/s^2", "W", "m", "W"]
problems = []
def want(cond, what):
    if not cond:
        problems.append(what)
want(d["scenario"] == "apc6x6", "scenario name")
want(d["initial"] == initial and d["payload"] == payload, "settings")
for key in ["static", "peak", "min", "rms", "peak_time", "min_time", "bump_window"]:
    want(key in d["definitions"], "definition of " + key)
s1 = d["system1"]
want(list(s1["outputs"]) == names, "output names and order")
for key in ["steps", "rhs_evals", "newton_setups", "factorizations", "newton_iters",
            "err_test_fails", "wall_seconds"]:
    want(isinstance(s1["solver"].get(key), (int, float)), "solver." + key)
want(s1["solver"]["steps"] > 0, "solver steps > 0")
# Tire contact: the paper's crossing keeps every tire in compression; the
# LF minimum over the run is at most the CSV's (which is the same force).
tc = s1["tire_contact"]
want(list(tc["min_force"]) == ["LF", "RF", "LM", "RM", "LR", "RR"], "tire_contact tires")
want(tc["contact_loss_intervals"] == [], "no tensile interval on the paper's crossing")
want("tire_contact" in d["definitions"], "definition of tire_contact")
# Data sheet: the LF wheel meets the bump at 5 s; the RR wheel, 2.9 m
# behind and 2.1 m to the right at 45 degrees, leaves it after a further
# (2.9 + 2.1 + 3.7) m at 10/3.6 m/s: 8.132 s. Printed with 10 digits.
t0, t1 = s1["bump_window"]
want(abs(t0 - 5.0) < 1e-9 and abs(t1 - (5.0 + 8.7 * 3.6 / 10)) < 1e-9, "bump window %s" % [t0, t1])
# Ride metrics of the driver over [first bump entry, end of the run]
# (values: test_ride.c). Relations that hold for any record: the crest
# factor is at least 1 and MTVV, a maximum of 1 s r.m.s. values, is at
# least the r.m.s. of some 1 s stretch, so positive with a_w.
ride = s1["ride"]
want(ride["window"][0] == t0, "ride window starts at the bump entry")
want(ride["a_w_rms"] > 0 and ride["vdv"] > 0 and ride["mtvv"] > 0, "ride metrics positive")
want(ride["crest_factor"] >= 1.0, "crest factor >= 1")
# The military measures (values: test_ride_military.c): the absorbed power
# is a mean square, the peak of the 30 Hz low-passed |a| is positive, S_ed
# is m_z D_z, the VDV ratio is VDV / 8.5 and the crest flag follows the
# crest factor; summary.json prints 10 significant digits, so the relations
# hold to 1e-9.
want(ride["absorbed_power"] > 0 and ride["nrmm_peak"] > 0, "absorbed power and NRMM peak")
want(ride["dz"] >= 0 and abs(ride["se"] - 0.032 * ride["dz"]) <= 1e-9 * ride["se"],
     "S_ed = m_z D_z")
want(abs(ride["vdv_ratio"] - ride["vdv"] / 8.5) <= 1e-9 * ride["vdv_ratio"], "VDV ratio")
want(ride["crest_over_9"] == (1 if ride["crest_factor"] > 9 else 0), "crest-factor flag")
want("ride" in d["definitions"], "definition of ride")
rows = [[float(v) for v in r] for r in list(csv.reader(open(out + "/system1.csv")))[1:]]
for j, name in enumerate(names, start=1):
    o = s1["outputs"][name]
    want(o["unit"] == units[j - 1], name + " unit")
    before = [r[j] for r in rows if r[0] < t0]
    after = [(r[j], r[0]) for r in rows if r[0] >= t0]
    bump = [r[j] for r in rows if t0 <= r[0] <= t1]
    peak = max(after, key=lambda p: p[0])
    low = min(after, key=lambda p: p[0])
    rms = math.sqrt(sum(v * v for v in bump) / len(bump))
    # The CSV and the JSON both print %.10g of the same doubles: the
    # extremes agree to 10 digits, the RMS (summed here from the rounded
    # CSV values) to about 1e-9 relative; 1e-8 leaves room (and 1e-300
    # only guards an exact zero).
    for key, ref in [("static", before[-1]), ("peak", peak[0]), ("min", low[0]), ("rms", rms)]:
        want(abs(o[key] - ref) <= 1e-8 * max(1e-300, abs(ref)), "%s %s: %r vs %r" % (name, key, o[key], ref))
    want(o["peak_time"] == peak[1] and o["min_time"] == low[1], name + " extreme times")
# System 1's hull is rigid: the torsion angle is identically zero (paper, Fig. 10a).
want(all(r[3] == 0 for r in rows), "torsion identically 0")
if problems:
    print("\n".join(problems), file=sys.stderr)
    sys.exit(1)
EOF
}

# ---- The APC example, System 1, the paper's protocol (all states zero).
run run "$APC" -o "$WORK/apc" -q --system rigid
expect_status 0 "run apc6x6"
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "run -q prints nothing on stderr"
expect_files "$WORK/apc" "run apc6x6"
checks=$((checks + 1))
[ "$(head -n 1 "$WORK/apc/system1.csv")" = "$HEADER" ] ||
  fail "system1.csv header: $(head -n 1 "$WORK/apc/system1.csv")"
checks=$((checks + 1))
[ "$(wc -l <"$WORK/apc/system1.csv")" -eq 15002 ] || fail "system1.csv has 15001 samples + header"
checks=$((checks + 1))
tail -n 1 "$WORK/apc/system1.csv" | grep -q '^15,' || fail "last sample at t = 15 s"
# Gravity switched on with every state zero: the driver starts in free
# fall, a = -g = -9.81 m/s^2 (data sheet), and the tires carry nothing yet.
checks=$((checks + 1))
[ "$(sed -n 2p "$WORK/apc/system1.csv")" = "0,0,0,0,-9.81,0,0,0" ] ||
  fail "first row: $(sed -n 2p "$WORK/apc/system1.csv")"
check_summary "$WORK/apc" zero weight-only
for f in "${FIGURES[@]}" "${DIAGRAMS1[@]}" "${BODES[@]}"; do
  checks=$((checks + 1))
  [ "$(head -c 8 "$WORK/apc/$f" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
    fail "$f is a PNG"
done

# Without -q: a progress line and a summary line on stderr.
# stderr is not a terminal here: no "\r" progress.
run run "$APC" -o "$WORK/apc_loud" --system rigid
expect_status 0 "run apc6x6 without -q"
expect_in "$ERR" "simulating System 1 (rigid hull)" "progress line"
expect_in "$ERR" "wrote 17 files -> $WORK/apc_loud" "summary line"
checks=$((checks + 1))
! grep -q $'\r' "$ERR" || fail "no progress line when stderr is not a terminal"

# Overrides: static equilibrium start and the lumped payload. At rest the
# driver does not accelerate: |a| below 1e-6 m/s^2 (the static solver
# balances forces to 1e-10 of the weight), against 9.81 from the zero
# start.
run run "$APC" -o "$WORK/apc_static" -q --initial static --payload lumped --system rigid
expect_status 0 "run --initial static --payload lumped"
expect_files "$WORK/apc_static" "run --initial static"
check_summary "$WORK/apc_static" static lumped
checks=$((checks + 1))
awk -F, 'NR == 2 { exit !($5 < 1e-6 && $5 > -1e-6) }' "$WORK/apc_static/system1.csv" ||
  fail "static start: driver acceleration at t = 0 is $(sed -n 2p "$WORK/apc_static/system1.csv")"

# ---- Both systems (the default) on the APC shortened to 3 s with a 0.5 m
# bump met at 1 s, so that System 2's full-order run takes seconds.
SHORT=$WORK/apc_short.yaml
sed -e 's/^  t_end: 15 /  t_end: 3.0 /' -e 's/first_contact: 5.0/first_contact: 1.0/' \
  -e 's/length: 3.70 /length: 0.5 /' "$APC" >"$SHORT"
# The modes pictured by kind (tests/cli_mode_pictures.sh): pitch 1, driver
# 2, engine 3, roll 4, bounce 5, first wheel hop 6, first elastic 8; the
# run lists the ten modes within its modal basis's band, one of them
# elastic.
MODE_PICTURES=(mode_01.png mode_02.png mode_03.png mode_04.png mode_05.png mode_06.png
  mode_08.png)
run run "$SHORT" -o "$WORK/both" -q
expect_status 0 "run, both systems"
checks=$((checks + 1))
[ "$(ls -A "$WORK/both" | sort)" = "$(printf '%s\n' "${FIGURES[@]}" "${MODE_PICTURES[@]}" \
  "${DIAGRAMS1[@]}" "${DIAGRAMS2[@]}" "${BODES[@]}" .flexbond-manifest report.md summary.json system1.csv system2.csv system2_converged.csv \
  stress_peak.png stress_peak.vtu stress_peaks.csv | sort)" ] ||
  fail "both systems: files $(ls -A "$WORK/both" | tr '\n' ' ')"
checks=$((checks + 1))
[ "$(head -n 1 "$WORK/both/system2.csv")" = "$HEADER" ] ||
  fail "system2.csv header: $(head -n 1 "$WORK/both/system2.csv")"
# Same sample times, row for row: 3 s at 1 kHz.
checks=$((checks + 1))
[ "$(cut -d, -f1 "$WORK/both/system1.csv" | md5sum)" = \
  "$(cut -d, -f1 "$WORK/both/system2.csv" | md5sum)" ] &&
  [ "$(wc -l <"$WORK/both/system2.csv")" -eq 3002 ] ||
  fail "system1.csv and system2.csv have the same 3001 sample times"

# summary.json: both systems, and a comparison that a second computation
# from the two CSVs reproduces.
checks=$((checks + 1))
python3 - "$WORK/both" <<'PY' || fail "summary.json comparison"
import csv, json, math, sys
out = sys.argv[1]
d = json.load(open(out + "/summary.json"))
names = ["tire_force_LF", "spring_defl_RF", "torsion", "driver_acc",
         "shock_power_LM", "tire_defl_RM", "tire_power_LR"]
problems = []
def want(cond, what):
    if not cond:
        problems.append(what)
def close(a, b, scale):
    # Both files print %.10g of the same doubles: values agree to ~1e-10
    # of their magnitude; a difference of two values to ~1e-10 of theirs.
    return a is not None and abs(a - b) <= 1e-8 * max(1.0, scale)
want(d["system1"]["label"] == "System 1 (rigid hull)", "system1 label")
want(d["system2"]["label"] == "System 2 (flexible hull)", "system2 label")
b = d["system2"]["hull_basis"]
want(b["coordinates"] == "modal" and b["modes"] == "auto", "system2's basis: modal, auto")
want(b["dofs"] == 1296 and b["coordinates_count"] == b["kept_modes"] + b["static_vectors"]
     and b["coordinates_count"] < b["dofs"], "system2's basis size %r" % b)
want(b["cutoff_hz"] == b["excitation_hz"] and b["cutoff_hz"] > b["first_elastic_hz"],
     "system2's band: the excitation's")
want(b["kept_modes"] == 6 and b["rigid_modes"] == 6 and b["ritz_blocks"] >= 2
     and 0 <= b["block_change"] <= 1e-3, "system2's auto basis: rigid-body modes and Ritz blocks")
est = b["estimated_error"]
want(list(est["of_range"]) == names and all(0 <= e < 1 for e in est["of_range"].values()),
     "system2's estimated error per output")
want(list(d["comparison"]) == names, "comparison outputs")
rows = [[[float(v) for v in r] for r in list(csv.reader(open("%s/system%d.csv" % (out, i))))[1:]]
        for i in (1, 2)]
t0, t1 = d["system1"]["bump_window"]
# Data sheet timing with first_contact 1 s and L = 0.5 m: RR leaves at
# 1 + (2.9 + 2.1 + 0.5) m / (10/3.6 m/s) = 2.98 s.
want(abs(t0 - 1.0) < 1e-9 and abs(t1 - 2.98) < 1e-9, "bump window %s" % [t0, t1])
for j, name in enumerate(names, start=1):
    c = d["comparison"][name]
    s1, s2 = d["system1"]["outputs"][name], d["system2"]["outputs"][name]
    want(c["peak_system1"] == s1["peak"] and c["peak_system2"] == s2["peak"], name + " peaks")
    want(c["rms_system1"] == s1["rms"] and c["rms_system2"] == s2["rms"], name + " rms")
    pairs = [(a[0], a[j], b[j]) for a, b in zip(*rows) if a[0] >= t0]
    diff, at = max((abs(v2 - v1), t) for t, v1, v2 in pairs)
    at = min(t for t, v1, v2 in pairs if abs(v2 - v1) == diff)
    scale = max(abs(v) for t, v1, v2 in pairs for v in (v1, v2))
    want(close(c["max_abs_diff"], diff, scale), "%s max_abs_diff %r vs %r" % (name, c["max_abs_diff"], diff))
    rng = max(v1 for t, v1, v2 in pairs) - min(v1 for t, v1, v2 in pairs)
    want(close(c["range_system1"], rng, scale), name + " range_system1")
    if rng > 0:
        want(abs(c["max_abs_diff_rel"] - diff / rng) <= 1e-6 * diff / rng + 1e-12,
             "%s max_abs_diff_rel %r vs %r" % (name, c["max_abs_diff_rel"], diff / rng))
        want(abs(c["peak_change_rel"] - (s2["peak"] - s1["peak"]) / abs(s1["peak"])) < 1e-9,
             name + " peak_change_rel")
    if name != "torsion":
        want(c["max_abs_diff"] > 0, name + ": the flexible hull changes it")
        want(abs(c["max_abs_diff_time"] - at) < 1e-9 or diff < 1e-6 * scale, name + " time")
# The rigid hull does not twist (paper, Fig. 10a): no range to scale by.
c = d["comparison"]["torsion"]
want(all(r[3] == 0 for r in rows[0]), "System 1 torsion identically 0")
want(c["range_system1"] == 0 and c["max_abs_diff_rel"] is None, "torsion ratio null")
want(c["peak_system2"] > 0, "System 2 twists")
# The example's converged mesh (hull.mesh.converged_density: 3): System 2
# again on 11964 DOFs, its first elastic mode lower (the paper's mesh is
# 14 % stiff there, docs/hull-mesh.md), compared with System 1 alike.
cv = d["system2_converged"]
want(cv["label"] == "System 2 at density 3" and cv["mesh_density"] == 3, "converged run's label")
want(cv["hull_basis"]["dofs"] == 11964, "converged hull's DOFs %r" % cv["hull_basis"]["dofs"])
want(0.85 < cv["hull_basis"]["first_elastic_hz"] / b["first_elastic_hz"] < 0.92,
     "converged first elastic mode %r" % cv["hull_basis"]["first_elastic_hz"])
rows3 = [[float(v) for v in r] for r in list(csv.reader(open(out + "/system2_converged.csv")))[1:]]
want(len(rows3) == len(rows[0]), "system2_converged.csv has the runs' samples")
for j, name in enumerate(names, start=1):
    c3 = d["comparison_converged"][name]
    want(c3["peak_system2"] == cv["outputs"][name]["peak"], name + " converged peak")
    pairs = [(a[j], b3[j]) for a, b3 in zip(rows[0], rows3) if a[0] >= t0]
    diff = max(abs(v3 - v1) for v1, v3 in pairs)
    scale = max(abs(v) for p in pairs for v in p)
    want(close(c3["max_abs_diff"], diff, scale), "%s converged max_abs_diff %r vs %r"
         % (name, c3["max_abs_diff"], diff))
if problems:
    print("\n".join(problems), file=sys.stderr)
    sys.exit(1)
PY

# report.md: a comparison row per output, the full-order hull, every
# image link pointing to a written file, and one paragraph of conclusions
# that notes the rigid hull's zero torsion.
REPORT=$WORK/both/report.md
for q in "LF tire normal reaction | N" "RF suspension spring deformation | m" \
  "hull torsion angle | rad" "driver plus seat acceleration | m/s^2" \
  "LM shock absorber dissipated power | W" "RM tire deformation | m" \
  "LR tire dissipated power | W"; do
  checks=$((checks + 1))
  [ "$(sed -n '/^## Comparison/,/^## /p' "$REPORT" | grep -c "^| $q |.*|.*|.*|.*|.*|.*|.*|.*|$")" \
    -eq 1 ] || fail "report.md comparison row '$q'"
done
expect_in "$REPORT" "System 2's hull mesh: the built-in generator at density 1: " \
  "report.md names the hull's source"
# The paper's positions are from the hull's centre of mass, and so is
# everything the report gives (a deck's frame row below, a declared
# frame's tests/cli_frame.sh).
expect_in "$REPORT" "| frame | the file's positions are from the hull structure's centre of mass, and so are the positions below and the pictures |" \
  "report.md of a generated hull without a frame names its frame"
expect_in "$REPORT" "System 2's hull model: in modal coordinates, " "report.md hull model"
expect_in "$REPORT" "coordinates in place of 1296 nodal DOFs" "report.md hull basis size"
expect_in "$REPORT" "Its estimated error, the largest difference from the same run with the basis's next block" \
  "report.md basis error estimate"
expect_in "$REPORT" "## Assumptions" "report.md assumptions"
expect_in "$REPORT" "System 2 ran again on the hull refined to density 3" "report.md converged mesh"
expect_in "$REPORT" " At the converged mesh (density 3) System 2 departs from System 1 by up to " \
  "report.md conclusions: the converged mesh"
expect_in "$REPORT" "## Frequency response" "report.md frequency response"
expect_in "$REPORT" "Mesh convergence (an estimate, not computed in this run): at density 1 the hull's first ten elastic free-free frequencies are about 12 % to 21 % above" \
  "report.md mesh error"
expect_in "$REPORT" "## Tire contact" "report.md tire contact"
expect_in "$REPORT" "## Ride comfort (driver plus seat acceleration)" "report.md ride comfort"
expect_in "$REPORT" "| VDV | m/s^1.75 |" "report.md VDV row"
# The shortened 0.5 m bump is sharp: every tire pulls its wheel down once.
expect_in "$REPORT" "System 2 (flexible hull): 6 intervals where a tire's normal reaction is tensile" \
  "report.md contact verdict"
expect_in "$REPORT" "| 11 | " "report.md System 1 modes"
# System 2's in its basis: those within its band (12.63 Hz), ten.
expect_in "$REPORT" "| 10 | " "report.md System 2 modes"
checks=$((checks + 1))
links=$(grep -o '](\([^)]*\))' "$REPORT" | sed 's/^](//; s/)$//')
[ "$(printf '%s\n' "$links" | sort)" = \
  "$(printf '%s\n' "${FIGURES[@]}" "${MODE_PICTURES[@]}" "${DIAGRAMS1[@]}" "${DIAGRAMS2[@]}" \
    "${BODES[@]}" stress_peak.png | sort)" ] ||
  fail "report.md image links: $(echo $links)"
for f in $links; do
  checks=$((checks + 1))
  [ -s "$WORK/both/$f" ] || fail "report.md links $f, which is missing"
done
checks=$((checks + 1))
[ "$(sed -n '/^## Conclusions/,$p' "$REPORT" | tail -n +2 | grep -c .)" -eq 1 ] ||
  fail "report.md conclusions are one paragraph"
expect_in "$REPORT" "The rigid hull's torsion angle is identically zero; the flexible hull's" \
  "report.md conclusions: torsion"

# --no-figures and the reduced hull: no PNG, a report without images that
# says why, and the hull order in the report and the summary.
run run "$SHORT" -o "$WORK/both_nofig" -q --no-figures --hull-modes 12
expect_status 0 "run, both systems, --no-figures --hull-modes 12"
checks=$((checks + 1))
[ "$(cd "$WORK/both_nofig" && ls | tr '\n' ' ')" = "report.md stress_peak.vtu stress_peaks.csv summary.json system1.csv system2.csv system2_converged.csv " ] ||
  fail "both systems --no-figures: $(ls "$WORK/both_nofig")"
checks=$((checks + 1))
! grep -q '!\[' "$WORK/both_nofig/report.md" || fail "report.md without images"
expect_in "$WORK/both_nofig/report.md" "No figures: the run had \`--no-figures\`" \
  "report.md says why it has no figures"
expect_in "$WORK/both_nofig/report.md" "its 12 lowest free-free modes (6 rigid-body modes) and 10 residual-flexibility vectors" \
  "report.md reduced hull"
expect_in "$WORK/both_nofig/summary.json" '"modes": 12,' "summary.json reduced hull"

# A deck as another tool would write it, never exactly flat: the example's
# hull exported, every node moved at random by up to 1 mm in each
# coordinate (warps up to 2e-3 of an element's diagonal). Both systems run,
# and the hull keeps its six rigid-body modes (docs/hull-mesh.md, "Warped
# elements").
run mesh "$SHORT" --export "$WORK/flat.inp"
expect_status 0 "mesh --export flat.inp"
awk 'BEGIN { srand(7) } /^\*/ { nodes = ($0 ~ /^\*NODE/); print; next }
  nodes && NF >= 4 { split($0, f, ",")
    printf "%s, %.9f, %.9f, %.9f\n", f[1], f[2] + 0.002 * rand() - 0.001,
      f[3] + 0.002 * rand() - 0.001, f[4] + 0.002 * rand() - 0.001; next } { print }' \
  "$WORK/flat.inp" >"$WORK/perturbed.inp"
sed -e '/^    density: 1 /d' -e '/^    generator:/,/nose_rung_divisions/c\    deck: perturbed.inp' \
  "$SHORT" >"$WORK/apc_perturbed.yaml"
checks=$((checks + 1))
grep -q 'deck: perturbed.inp' "$WORK/apc_perturbed.yaml" || fail "perturbed scenario: no deck"
run run "$WORK/apc_perturbed.yaml" -o "$WORK/perturbed" -q --no-figures
expect_status 0 "run on a deck moved by up to 1 mm"
run modes "$WORK/apc_perturbed.yaml" --system flexible
expect_in "$OUT" "6 rigid-body modes, then" "modes on a deck moved by up to 1 mm"

# Plates of two thicknesses. A deck with a 20 mm floor and 8.5 mm walls
# (the example's deck with its sections rewritten): its mass is the
# one-thickness hull's plus the floor's extra steel, 7860 kg/m^3 x 11.5 mm
# x the floor's 2.10 m x 5.13611724282061 m (closed form), and both
# systems run on it. The generated truck's floor and side walls as
# hull.sections: both systems run, and `mesh` lists each section's mass.
python3 - "$WORK/flat.inp" "$WORK/two.inp" <<'EOF'
import sys
s = open(sys.argv[1]).read()
s = s[:s.index("*MATERIAL")]
s += "*MATERIAL, NAME=STEEL\n*ELASTIC\n200e9, 0.3\n*DENSITY\n7860\n"
s += "*SHELL SECTION, ELSET=FLOOR, MATERIAL=STEEL\n0.020\n"
for name in ["ROOF", "SIDES", "REAR_WALL", "GLACIS", "BULKHEADS"]:
    s += "*SHELL SECTION, ELSET=%s, MATERIAL=STEEL\n0.0085\n" % name
open(sys.argv[2], "w").write(s)
EOF
sed -e '/^  mass: 4041.72/d' -e '/^  Ixx: /d' -e '/^  Iyy: /d' -e 's/deck: perturbed.inp/deck: two.inp/' \
  "$WORK/apc_perturbed.yaml" >"$WORK/apc_two.yaml"
run mesh "$WORK/apc_two.yaml"
expect_status 0 "mesh of a two-thickness deck"
expect_in "$OUT" "FLOOR               51 elements" "two-thickness deck's floor section"
checks=$((checks + 1))
python3 - "$OUT" <<'EOF' || fail "two-thickness deck's mass"
import re, sys
mass = float(re.search(r"^mass ([0-9.e+]+) kg", open(sys.argv[1]).read(), re.M).group(1))
expect = 4041.72 + 7860 * (0.020 - 0.0085) * 2.10 * (2.47813311938948 + 2.65798412344113)
# 4041.72 is the one-thickness mesh's mass to 6e-6 (the fit); printed to 6 digits.
assert abs(mass - expect) < 1e-4 * expect, (mass, expect)
EOF
run run "$WORK/apc_two.yaml" -o "$WORK/two" -q --no-figures
expect_status 0 "both systems on a two-thickness deck"
expect_in "$WORK/two/report.md" "hull.mesh.deck" "report of the two-thickness deck"
expect_in "$WORK/two/report.md" "| frame | the deck's: its structure's centre of mass is at x, y, z = " \
  "report of a deck names the frame it moved to"

TRUCK=$REPO_ROOT/examples/truck4x4.yaml
sed 's/^  edges:  /  sections:\n    - {set: FLOOR, thickness: 0.020}\n    - {set: sides, thickness: 0.0085, nonstructural_mass: 10}\n  edges:  /' \
  "$TRUCK" >"$WORK/truck_sections.yaml"
cp "$REPO_ROOT"/examples/*.csv "$WORK/"
run mesh "$WORK/truck_sections.yaml"
expect_status 0 "mesh of the truck with sections"
expect_in "$OUT" "SIDES               64 elements,    18.72 m^2, 0.0085 m" "truck's side section"
expect_in "$OUT" "+ 10 kg/m^2: 1436.29 kg" "truck's side section mass"
run run "$WORK/truck_sections.yaml" -o "$WORK/truck_sections" -q --no-figures
expect_status 0 "both systems on the truck with sections"
expect_in "$WORK/truck_sections/report.md" \
  "Plates with a section of their own (the material above elsewhere): FLOOR (104 elements) 0.02 m" \
  "report.md lists the sections"
sed 's/{set: FLOOR, thickness: 0.020}/{set: FLOR, thickness: 0.020}/' "$WORK/truck_sections.yaml" \
  >"$WORK/truck_bad_set.yaml"
run run "$WORK/truck_bad_set.yaml" -o "$WORK/truck_bad_set" -q --no-figures
expect_status 2 "a section of a set the mesh lacks"
expect_in "$ERR" "truck_bad_set.yaml:26:" "bad set: file and line"
expect_in "$ERR" "hull.sections[0].set: the hull mesh has no element set 'FLOR'" "bad set: key"
checks=$((checks + 1))
[ ! -e "$WORK/truck_bad_set" ] || fail "a refused scenario left output"

# A deck whose attachment points are not nodes: the example's deck without
# its SUSP_* and mount node sets, the front axle and the driver moved 3 cm
# off the node lines, coupled to the floor's nodes within 0.3 m
# (hull.mesh.coupling, distributing). Both systems run; without the coupling
# the same file is refused at the point's key.
python3 - "$WORK/flat.inp" "$WORK/nosets.inp" <<'EOF'
import re, sys
out, skip = [], False
for line in open(sys.argv[1]).read().split("\n"):
    if line.startswith("*"):
        skip = bool(re.match(r"\*NSET, NSET=(SUSP_|DRIVER|ENGINE)", line))
    if not skip:
        out.append(line)
open(sys.argv[2], "w").write("\n".join(out))
EOF
sed -e 's/deck: perturbed.inp/deck: nosets.inp\n    coupling: {kind: distributing, radius: 0.3, surface: FLOOR}/' \
  -e 's/^      x: 1.90  .*/      x: 1.93/' -e 's/^    x: 2.10  .*/    x: 2.13/' \
  "$WORK/apc_perturbed.yaml" >"$WORK/apc_coupled.yaml"
checks=$((checks + 1))
[ "$(grep -c -e 'x: 1.93' -e 'x: 2.13' -e 'coupling:' "$WORK/apc_coupled.yaml")" = 3 ] ||
  fail "coupled scenario: edits missing"
run run "$WORK/apc_coupled.yaml" -o "$WORK/coupled" -q --no-figures
expect_status 0 "both systems with distributing couplings"
sed '/coupling: {kind: distributing/d' "$WORK/apc_coupled.yaml" >"$WORK/apc_uncoupled.yaml"
# A point whose node set is one node 3 cm away: with a kinematic coupling,
# a lever to that node; without one, refused at the point's key.
sed -e 's/deck: perturbed.inp/deck: flat.inp\n    coupling: {kind: kinematic, radius: 0.1, surface: FLOOR}/' \
  -e 's/^      x: 1.90  .*/      x: 1.93/' "$WORK/apc_perturbed.yaml" >"$WORK/apc_lever.yaml"
run mesh "$WORK/apc_lever.yaml"
expect_status 0 "a one-node set off its point, kinematic coupling"
sed '/coupling: {kind: kinematic/d' "$WORK/apc_lever.yaml" >"$WORK/apc_no_lever.yaml"
run mesh "$WORK/apc_no_lever.yaml"
expect_status 2 "a one-node set off its point, no coupling"
expect_in "$ERR" "suspensions.axles[0].x: " "off-node point: key"
expect_in "$ERR" "flat.inp: the scenario puts SUSP_LF at (1.93" "off-node point: set"
run run "$WORK/apc_uncoupled.yaml" -o "$WORK/uncoupled" -q --no-figures
expect_status 2 "points off the nodes without a coupling"
expect_in "$ERR" "the mesh has no node set SUSP_LF" "uncoupled: the missing set"

# A hull meshed by gmsh (tests/data/gmsh/box_hull.geo, MSH 4.1): a closed
# 5.0 x 2.1 x 1.6 m box of 8.5 mm plates, its physical groups FLOOR, ROOF,
# SIDES, ENDS, LOAD (four points embedded in the floor), FRONT_EDGE and
# REAR_EDGE. The suspension and mount points are no nodes and couple to the
# floor (distributing, 0.3 m). Its mass is 7860 kg/m^3 x 8.5 mm x the box's
# 43.72 m^2 (closed form); both systems run on it.
cp "$REPO_ROOT/tests/data/gmsh/box_hull.msh" "$WORK/"
sed -e '/^  mass: 4041.72/d' -e '/^  Ixx: /d' -e '/^  Iyy: /d' \
  -e 's/^    front_x: .*/    front_x: 2.5/' -e 's/^    rear_x: .*/    rear_x: -2.5/' \
  -e 's/deck: perturbed.inp/deck: box_hull.msh\n    coupling: {kind: distributing, radius: 0.3, surface: FLOOR}/' \
  -e '/^    grid:/,/^      y: /c\    - [-1.5, -0.5]\n    - [-1.5, 0.5]\n    - [1.5, -0.5]\n    - [1.5, 0.5]' \
  "$WORK/apc_perturbed.yaml" >"$WORK/apc_gmsh.yaml"
run mesh "$WORK/apc_gmsh.yaml"
expect_status 0 "mesh of a gmsh hull"
expect_in "$OUT" "hull mesh: 900 nodes, 0 S3 + 898 S4 elements" "gmsh hull's elements"
checks=$((checks + 1))
python3 - "$OUT" <<'EOF' || fail "gmsh hull's mass"
import re, sys
mass = float(re.search(r"^mass ([0-9.e+]+) kg", open(sys.argv[1]).read(), re.M).group(1))
expect = 7860 * 0.0085 * (2 * 5.0 * 2.1 + 2 * 5.0 * 1.6 + 2 * 2.1 * 1.6)
assert abs(mass - expect) < 1e-5 * expect, (mass, expect)  # printed to 6 digits
EOF
run modes "$WORK/apc_gmsh.yaml" --system flexible
expect_in "$OUT" "6 rigid-body modes, then" "gmsh hull's rigid-body modes"
run run "$WORK/apc_gmsh.yaml" -o "$WORK/gmsh" -q --no-figures --hull-modes 40
expect_status 0 "both systems on a gmsh hull with couplings"

# -v: the hull's basis and its one eigen-solve, and what each vehicle
# cost, counted where the work was done. A whole run with both systems,
# the report's modes, the basis's error estimate and the converged mesh
# assembles each of the two hulls once and solves each eigenproblem once:
# each hull's (the basis and the report's free-free modes), System 2's
# vehicle's (the report's modes and pictures) and System 1's linear one;
# the estimators share their hull and its modes; the meshes came with
# their scenarios. Five simulations: both systems, the converged mesh and
# the two estimators.
run run "$SHORT" -o "$WORK/verbose" -v --no-figures
expect_status 0 "run -v"
expect_in "$ERR" "System 2 (flexible hull): hull of 1296 DOFs in " "run -v: the hull's basis"
expect_in "$ERR" "eigen-solve block Lanczos on a CHOLMOD factor, " "run -v: the hull's eigen-solve"
expect_in "$ERR" "System 1 (rigid hull): work: set-up " "run -v: System 1's work"
checks=$((checks + 1))
python3 - "$ERR" <<'PY' || fail "run -v: the work of the whole run"
import re, sys
total = {}
for line in open(sys.argv[1]):
    m = re.search(r": work: set-up [0-9.e+-]+ s, (.*)$", line)
    if m:
        for count, what in re.findall(r"([a-z -]+?) ([0-9]+)(?: \([^)]*\))?(?:, |$)", m.group(1)):
            total[count.strip()] = total.get(count.strip(), 0) + int(what)
want = {"mesh generations": 0, "hull assemblies": 2, "factorisations": 2, "hull eigen-solves": 2,
        "vehicle eigen-solves": 1, "linear eigen-solves": 1, "simulations": 5}
bad = {k: (total.get(k), v) for k, v in want.items() if total.get(k) != v}
if bad:
    sys.exit("counts (got, want): %r" % bad)
PY
run run "$SHORT" -o "$WORK/verbose_nodal" -v --no-figures --system flexible \
  --hull-coordinates nodal
expect_status 0 "run -v --hull-coordinates nodal"
expect_in "$ERR" "hull of 1296 DOFs in nodal coordinates; eigen-solve block Lanczos on a CHOLMOD factor, 12 lowest modes," \
  "run -v: the nodal hull's frequencies"
run run "$SHORT" -o "$WORK/quiet_verbose" -q -v --no-figures --system rigid
expect_status 0 "run -q -v"
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "run -q -v: -q wins, stderr holds $(head -c 200 "$ERR")"

# Failures with both systems write nothing: System 2 asked of a scenario
# without a finite-element hull (exit 2), and report.md blocked after
# both runs (exit 5). Without --system such a scenario runs System 1.
# (Deletes hull.mesh and hull.fe: from "  mesh:" to the next top-level key.)
sed '/^  mesh:/,/^[a-z]/{/^[a-z]/!d;}' "$SHORT" >"$WORK/nofe.yaml"
run run "$WORK/nofe.yaml" -o "$WORK/out_nofe" --system both
expect_status 2 "run --system both without a finite-element hull"
expect_in "$ERR" "hull.fe: System 2 needs the hull's finite-element model" "run --system both without a finite-element hull"
expect_absent "$WORK/out_nofe" "run --system both without a finite-element hull"
run run "$WORK/nofe.yaml" -o "$WORK/nofe" --no-figures
expect_status 0 "run without a finite-element hull"
expect_in "$ERR" "only System 1 (rigid hull) ran" "default without a finite-element hull"
checks=$((checks + 1))
[ "$(cd "$WORK/nofe" && ls | tr '\n' ' ')" = "report.md summary.json system1.csv " ] ||
  fail "run without a finite-element hull: $(ls "$WORK/nofe")"
# A stress of the shell hull, which System 1 cannot give: without --system
# System 2 runs alone, and says so.
sed 's/^outputs:/outputs:\n  - {signal: hull_stress, element: 5, surface: top, stress: sx}/' \
  "$SHORT" >"$WORK/stress.yaml"
run run "$WORK/stress.yaml" -o "$WORK/stress" --no-figures
expect_status 0 "run with a stress output"
expect_in "$ERR" "include stresses of the shell hull, which System 1 (rigid hull) does not have, so only System 2 ran" \
  "default with a stress output"
checks=$((checks + 1))
[ -s "$WORK/stress/system2.csv" ] && [ ! -e "$WORK/stress/system1.csv" ] ||
  fail "run with a stress output: $(ls "$WORK/stress")"
mkdir -p "$WORK/both_blocked/report.md"
run run "$SHORT" -o "$WORK/both_blocked" -q --no-figures --hull-modes 12
expect_status 5 "both systems, report.md blocked"
checks=$((checks + 1))
[ "$(ls -A "$WORK/both_blocked")" = "report.md" ] ||
  fail "blocked run left: $(ls -A "$WORK/both_blocked" | tr '\n' ' ')"

# Progress: on a terminal, one "\r"-updated line per system up to 100 %;
# nothing with -q. script(1) provides the terminal.
if command -v script >/dev/null 2>&1; then
  script -qec "'$FLEXBOND' run '$SHORT' -o '$WORK/tty' --system rigid --no-figures" /dev/null \
    >"$WORK/tty.txt" 2>&1
  checks=$((checks + 1))
  grep -q $'\r'"flexbond run: apc6x6: simulating System 1 (rigid hull), t = 0..3 s: 100%" \
    "$WORK/tty.txt" || fail "progress line on a terminal: $(tr '\r' '|' <"$WORK/tty.txt" | head -c 300)"
  checks=$((checks + 1))
  n=$(tr -cd '\r' <"$WORK/tty.txt" | wc -c)
  # At most 101 redraws (0 .. 100 %) plus the terminal's CR of each line.
  [ "$n" -gt 10 ] && [ "$n" -le 110 ] || fail "progress redraws: $n"
  script -qec "'$FLEXBOND' run '$SHORT' -o '$WORK/tty_q' --system rigid --no-figures -q" \
    /dev/null >"$WORK/tty_q.txt" 2>&1
  checks=$((checks + 1))
  [ ! -s "$WORK/tty_q.txt" ] || fail "-q on a terminal prints nothing"
fi

# ---- Bad options.
for bad in "--system rubber" "--initial warm" "--payload heavy"; do
  set -- $bad
  run run "$APC" -o "$WORK/out_opt" "$@"
  expect_status 1 "run $bad"
  expect_in "$ERR" "option '$1' must be one of" "run $bad"
done
for bad in "--hull-modes -1" "--hull-modes 12x" "--hull-modes 100001" "--hull-modes 5" "--hull-modes 0"; do
  set -- $bad
  run run "$APC" -o "$WORK/out_opt" "$@"
  expect_status 1 "run $bad"
  expect_in "$ERR" "option '--hull-modes' needs auto, all (every mode) or an integer in 6..100000" "run $bad"
done
run run "$APC" -o "$WORK/out_opt" --system rigid --hull-modes 12
expect_status 1 "run --system rigid --hull-modes"
expect_in "$ERR" "not with --system rigid" "run --system rigid --hull-modes"
run run "$APC" -o "$WORK/out_opt" --hull-coordinates cartesian
expect_status 1 "run --hull-coordinates cartesian"
expect_in "$ERR" "option '--hull-coordinates' must be one of" "run --hull-coordinates cartesian"
run run "$APC" -o "$WORK/out_opt" --hull-coordinates nodal --hull-modes 12
expect_status 1 "run --hull-coordinates nodal --hull-modes 12"
expect_in "$ERR" "--hull-modes and --hull-cutoff choose a modal hull's modes: not with --hull-coordinates nodal" \
  "run --hull-coordinates nodal --hull-modes 12"
run run "$APC"
expect_status 1 "run without -o"
expect_in "$ERR" "-o DIR" "run without -o"
run run -o "$WORK/out_opt"
expect_status 1 "run without a scenario"
expect_in "$ERR" "missing SCENARIO" "run without a scenario"
expect_absent "$WORK/out_opt" "bad options"

# ---- Bad scenarios, made from the example: exit 2, `file:line:` and the
# key in the message, nothing written.
# bad_scenario NAME LINE PHRASE: runs the scenario $WORK/NAME.yaml.
bad_scenario() {
  local file=$WORK/$1.yaml
  run run "$file" -o "$WORK/out_$1"
  expect_status 2 "$1"
  expect_in "$ERR" "flexbond: $file:$2:" "$1: file:line"
  expect_in "$ERR" "$3" "$1: message"
  expect_absent "$WORK/out_$1" "$1: output"
}
# line_of FILE REGEX: number of the first line of FILE matching REGEX.
line_of() {
  grep -n -m 1 -E "$2" "$1" | cut -d: -f1
}

sed '0,/spring_k:/s/spring_k: *[-0-9.e+]*/spring_k: -1/' "$APC" >"$WORK/negative.yaml"
bad_scenario negative "$(line_of "$WORK/negative.yaml" 'spring_k: -1')" "spring_k: must be > 0"

# A corner that does not exist (the axles make LF .. RR), named by an output.
sed 's/^    of: LM$/    of: XM/' "$APC" >"$WORK/unknown.yaml"
bad_scenario unknown "$(line_of "$WORK/unknown.yaml" '^    of: XM$')" "outputs[4].of: no corner named 'XM'"

# The loader reports a missing key at its mapping (somewhere in `hull:`).
grep -v -E '^  Iyy:' "$APC" >"$WORK/missing.yaml"
run run "$WORK/missing.yaml" -o "$WORK/out_missing"
expect_status 2 "missing key"
checks=$((checks + 1))
grep -qE "^flexbond: $WORK/missing.yaml:[0-9]+:.*'Iyy'" "$ERR" || fail "missing key: file:line and key"
expect_absent "$WORK/out_missing" "missing key: output"

# The last wheel leaves the bump at 8.132 s: a 7 s run is too short.
sed -E 's/^  t_end: *[0-9.e+]+/  t_end: 7/' "$APC" >"$WORK/short.yaml"
run run "$WORK/short.yaml" -o "$WORK/out_short"
expect_status 2 "run shorter than the bump"
checks=$((checks + 1))
grep -qE "^flexbond: $WORK/short.yaml:[0-9]+:[0-9]+: simulation.t_end: .*bump" "$ERR" ||
  fail "run shorter than the bump: file:line and key"
expect_absent "$WORK/out_short" "run shorter than the bump: output"

run run "$WORK/no_such.yaml" -o "$WORK/out_nofile"
checks=$((checks + 1))
[ "$status" -eq 5 ] || [ "$status" -eq 2 ] || fail "missing scenario: exit status $status"
expect_in "$ERR" "$WORK/no_such.yaml" "missing scenario"
expect_absent "$WORK/out_nofile" "missing scenario: output"

# ---- Writing fails: exit 5, and no file of the run is left behind.
printf 'not a directory\n' >"$WORK/plain"
run run "$APC" -o "$WORK/plain/out" -q --system rigid
expect_status 5 "output under a regular file"

# report.md, the last file written, cannot replace a directory: the
# figures, CSV and summary written before it are taken back; the directory
# existed before, so it stays.
mkdir -p "$WORK/blocked/report.md"
run run "$APC" -o "$WORK/blocked" -q --system rigid
expect_status 5 "report.md blocked"
checks=$((checks + 1))
[ "$(ls -A "$WORK/blocked")" = "report.md" ] ||
  fail "blocked run left: $(ls -A "$WORK/blocked" | tr '\n' ' ')"

# Without gnuplot the figures fail first: nothing written, no directory.
run_without_gnuplot() {
  PATH=/nonexistent "$FLEXBOND" "$@" >"$OUT" 2>"$ERR"
  status=$?
}
run_without_gnuplot run "$APC" -o "$WORK/out_nognuplot" -q --system rigid
expect_status 5 "run without gnuplot"
expect_in "$ERR" "gnuplot" "run without gnuplot"
expect_absent "$WORK/out_nognuplot" "run without gnuplot: output"

# ---- modes: 11 natural frequencies of System 1 (hull bounce, roll and
# pitch, driver, engine, six wheels), then the damped eigenvalues.
run modes "$APC"
expect_status 0 "modes apc6x6"
checks=$((checks + 1))
n=$(awk '/^undamped natural frequencies/ { on = 1; next } on && /^$/ { exit }
         on && $1 ~ /^[0-9]+$/ { n++ } END { print n + 0 }' "$OUT")
[ "$n" -eq 11 ] || fail "modes lists $n undamped frequencies, expected 11"
expect_in "$OUT" "undamped natural frequencies: 11 modes" "modes heading"
expect_in "$OUT" "damped eigenvalues:" "modes damped table"
expect_in "$OUT" "static zero mode" "modes static count"
expect_in "$OUT" "wheel hop" "modes descriptions"
# Frequencies ascend (fb_vehicle_modes sorts oscillatory modes by frequency).
checks=$((checks + 1))
awk '/^undamped/ { on = 1; next } on && /^$/ { exit }
     on && $1 ~ /^[0-9]+$/ { if ($2 + 0 < last) bad = 1; last = $2 + 0 } END { exit bad }' \
  "$OUT" || fail "undamped frequencies ascend"

run modes "$APC" --system flexible -o "$WORK/modes2"
expect_status 0 "modes --system flexible"
expect_in "$OUT" "System 2, undamped" "modes --system flexible"
for f in hull_modes.csv modes.csv mode_01.vtu mode_20.vtu mode_01.png mode_02.png mode_08.png \
  mode_13.png; do
  checks=$((checks + 1))
  [ -s "$WORK/modes2/$f" ] || fail "modes --system flexible -o writes $f"
done
expect_in "$WORK/modes2/mode_01.vtu" '<DataArray type="Float64" Name="frequency_hz" NumberOfTuples="1" format="ascii">1.40' \
  "mode_01.vtu carries its frequency"
checks=$((checks + 1))
[ "$(head -n 1 "$WORK/modes2/hull_modes.csv")" = "mode,frequency_hz,kind" ] ||
  fail "hull_modes.csv header"
checks=$((checks + 1))
[ "$(grep -c ',rigid$' "$WORK/modes2/hull_modes.csv")" -eq 6 ] ||
  fail "hull_modes.csv marks six rigid-body modes"
run modes "$APC" -o "$WORK/modes1"
expect_status 1 "modes -o without --system flexible"
expect_absent "$WORK/modes1" "modes -o without --system flexible"
run mesh "$APC" --export "$WORK/hull.inp"
expect_status 0 "mesh --export"
expect_in "$OUT" "28 S3 + 212 S4" "mesh counts"
expect_in "$WORK/hull.inp" "*NSET, NSET=SUSP_LF" "mesh deck node sets"
# Declared hull masses: mesh prints the hull with them after the
# structure, exports their node sets, and report.md lists them.
sed 's/^  material:/  masses: [{name: ballast, mass: 300, x: -2.00, y: 0.55}]\n  material:/' \
  "$APC" >"$WORK/masses.yaml"
run mesh "$WORK/masses.yaml" --export "$WORK/masses.inp"
expect_status 0 "mesh with hull masses"
expect_in "$OUT" "with its 1 hull masses: mass 4341.72 kg" "mesh with hull masses"
expect_in "$WORK/masses.inp" "*NSET, NSET=MASS_BALLAST" "mesh deck's hull mass node set"
run run "$WORK/masses.yaml" -o "$WORK/masses" --system rigid --no-figures -q
expect_status 0 "run with hull masses"
expect_in "$WORK/masses/report.md" "| hull masses | ballast 300 kg at x, y = -2, 0.55 m (300 kg in all" \
  "report.md hull masses"
run mesh "$APC" --export "$WORK/hull.stl"
expect_status 1 "mesh --export with an unknown format"
run modes "$WORK/negative.yaml"
expect_status 2 "modes on a bad scenario"
expect_in "$ERR" "$WORK/negative.yaml:" "modes on a bad scenario"
run modes
expect_status 1 "modes without a scenario"

# --no-figures: the CSV, the summary and the report only.
run run "$REPO_ROOT/examples/apc6x6.yaml" -o "$WORK/nofig" --no-figures -q --system rigid
expect_status 0 "run --no-figures"
checks=$((checks + 1))
[ "$(cd "$WORK/nofig" && ls | tr '\n' ' ')" = "report.md summary.json system1.csv " ] ||
  fail "run --no-figures writes only system1.csv, summary.json and report.md: $(ls "$WORK/nofig")"
# --plain-header: the paper's header, names only; the same numbers.
run run "$REPO_ROOT/examples/apc6x6.yaml" -o "$WORK/plain_header" --no-figures -q --system rigid \
  --plain-header
expect_status 0 "run --plain-header"
checks=$((checks + 1))
[ "$(head -n 1 "$WORK/plain_header/system1.csv")" = "$(echo "$HEADER" | sed 's/ \[[^]]*\]//g')" ] ||
  fail "run --plain-header: header $(head -n 1 "$WORK/plain_header/system1.csv")"
checks=$((checks + 1))
cmp -s <(tail -n +2 "$WORK/plain_header/system1.csv") <(tail -n +2 "$WORK/nofig/system1.csv") ||
  fail "run --plain-header changes the numbers"

# Unilateral tires (examples/apc6x6_liftoff.yaml): wheels leave the road,
# every reaction stays >= 0, the report says so, and the summary counts the
# contact changes; the bilateral run of the same crossing goes tensile.
run run "$REPO_ROOT/examples/apc6x6_liftoff.yaml" -o "$WORK/liftoff" --no-figures -q \
  --system rigid
expect_status 0 "run with unilateral tires"
expect_in "$WORK/liftoff/report.md" "every tire is unilateral, one-sided: it pushes but never pulls" \
  "report.md unilateral tires"
expect_in "$WORK/liftoff/report.md" \
  "System 1 (rigid hull): 5 intervals where a tire carries no load" "report.md lift-off verdict"
# The report names every shock absorber as its damper law describes it
# (the example's front and rear coefficients, docs/scenario-format.md).
expect_in "$WORK/liftoff/report.md" \
  "- Shock absorbers: LF, RF, LM, RM: linear, 25744 N s/m; LR, RR: linear, 39656 N s/m." \
  "report.md shock absorbers"
checks=$((checks + 1))
python3 - "$WORK/liftoff" <<'EOF' || fail "summary.json with unilateral tires"
import csv, json, sys
d = json.load(open(sys.argv[1] + "/summary.json"))["system1"]
tc = d["tire_contact"]
assert tc["model"] == "unilateral", tc["model"]
assert len(tc["contact_loss_intervals"]) == 5, tc["contact_loss_intervals"]
assert all(i["min_force"] == 0 for i in tc["contact_loss_intervals"])
assert all(v["value"] >= 0 for v in tc["min_force"].values())
assert d["solver"]["events"] >= 10, d["solver"]["events"]
rows = list(csv.DictReader(open(sys.argv[1] + "/system1.csv")))
assert min(float(r["tire_force_LF [N]"]) for r in rows) == 0.0
# The spike flag, recomputed from the CSV (tire_force_LF is LF's reaction):
# static = the last sample before the bump window, peak = the largest after.
t0 = d["bump_window"][0]
before = [float(r["tire_force_LF [N]"]) for r in rows if float(r["t [s]"]) < t0]
after = [float(r["tire_force_LF [N]"]) for r in rows if float(r["t [s]"]) >= t0]
lf = tc["peak_force"]["LF"]
assert abs(lf["static"] - before[-1]) <= 1e-9 * before[-1], (lf, before[-1])
assert abs(lf["value"] - max(after)) <= 1e-9 * max(after), (lf, max(after))
assert abs(lf["ratio"] - max(after) / before[-1]) <= 1e-9 * lf["ratio"]
assert tc["spike_ratio_limit"] == 3
want = [c for c, v in tc["peak_force"].items() if v["ratio"] > 3]
assert tc["spikes"] == want == ["LF", "RF", "LM"], (tc["spikes"], want)
EOF
expect_in "$WORK/liftoff/report.md" "Reaction spikes, above 3 times the static reaction: LF" \
  "report.md flags the landing spikes"
expect_in "$WORK/liftoff/report.md" "\`wheel.tire_contact: hunt_crossley\` lets the damping grow" \
  "report.md points to the Hunt-Crossley tire"
# Hunt-Crossley tires: the same lift-off with a damping that starts from
# zero at first contact: the LF landing, 20.7 times its static reaction with
# the constant damper, falls below half of it and is the only spike left.
sed 's/  tire_contact: unilateral .*$/  tire_contact: hunt_crossley/' \
  "$REPO_ROOT/examples/apc6x6_liftoff.yaml" >"$WORK/liftoff_hc.yaml"
run run "$WORK/liftoff_hc.yaml" -o "$WORK/liftoff_hc" --no-figures -q --system rigid
expect_status 0 "run with Hunt-Crossley tires"
expect_in "$WORK/liftoff_hc/report.md" "every tire is hunt\\_crossley, unilateral, its damping" \
  "report.md names the Hunt-Crossley tires"
checks=$((checks + 1))
python3 - "$WORK/liftoff" "$WORK/liftoff_hc" <<'EOF' || fail "summary.json with Hunt-Crossley tires"
import json, sys
kv, hc = (json.load(open(p + "/summary.json"))["system1"]["tire_contact"] for p in sys.argv[1:])
assert hc["model"] == "hunt_crossley", hc["model"]
assert hc["spikes"] == ["LF"], hc["spikes"]
assert hc["peak_force"]["LF"]["value"] < 0.5 * kv["peak_force"]["LF"]["value"]
assert hc["peak_force"]["LF"]["static"] == kv["peak_force"]["LF"]["static"]
assert all(v["value"] >= 0 for v in hc["min_force"].values())
EOF
sed 's/  tire_contact: unilateral .*$/  tire_contact: bilateral/' \
  "$REPO_ROOT/examples/apc6x6_liftoff.yaml" >"$WORK/liftoff_bilateral.yaml"
run run "$WORK/liftoff_bilateral.yaml" -o "$WORK/liftoff_bilateral" --no-figures -q --system rigid
expect_status 0 "run with bilateral tires"
expect_in "$WORK/liftoff_bilateral/report.md" \
  "System 1 (rigid hull): 5 intervals where a tire's normal reaction is tensile" \
  "report.md tensile verdict"

# Mixed tires (the front axle Hunt-Crossley, the others bilateral): each
# corner reported with its own model, a bilateral tire's interval with its
# tensile force, a unilateral one's without.
python3 - "$REPO_ROOT/examples/apc6x6_liftoff.yaml" "$WORK/mixed.yaml" <<'EOF'
import sys
s = open(sys.argv[1]).read().replace("  tire_contact: unilateral ", "  tire_contact: bilateral ")
front = "      damper_c: 25744           # paper: N s/m\n    - name: M"
assert front in s
s = s.replace(front, front.replace("\n", "\n      wheel: {tire_contact: hunt_crossley}\n", 1), 1)
open(sys.argv[2], "w").write(s)
EOF
run run "$WORK/mixed.yaml" -o "$WORK/mixed" --no-figures -q --system rigid
expect_status 0 "run with mixed tires"
# A tire model's name and meaning go through the Markdown escaping.
expect_in "$WORK/mixed/report.md" "LM, RM, LR, RR: bilateral, linear" "report.md: the bilateral corners"
expect_in "$WORK/mixed/report.md" "LF, RF: hunt\\_crossley, unilateral" "report.md: the Hunt-Crossley corners"
checks=$((checks + 1))
python3 - "$WORK/mixed" <<'EOF' || fail "mixed tires: summary.json and the verdict"
import json, re, sys
d = json.load(open(sys.argv[1] + "/summary.json"))["system1"]["tire_contact"]
assert d["model"] == "mixed", d["model"]
assert d["models"] == {"LF": "hunt_crossley", "RF": "hunt_crossley", "LM": "bilateral",
                       "RM": "bilateral", "LR": "bilateral", "RR": "bilateral"}, d["models"]
for i in d["contact_loss_intervals"]:
    assert (i["min_force"] < 0) == (d["models"][i["tire"]] == "bilateral"), i
report = open(sys.argv[1] + "/report.md").read()
for i in d["contact_loss_intervals"]:
    m = re.search(r"%s from [0-9.]+ to [0-9.]+ s( \(down to)?" % i["tire"], report)
    assert m and (m.group(1) is not None) == (i["min_force"] < 0), (i, m)
EOF

# Bump and rebound stops (examples/quarter_car_stops.yaml): the front
# suspension reaches its bump stop on the bump; the stop pushes only while
# the travel is past its gap (0.12 m) and pulls only past the rebound gap
# (0.06 m of extension).
run run "$REPO_ROOT/examples/quarter_car_stops.yaml" -o "$WORK/stops" --no-figures -q
expect_status 0 "run with bump and rebound stops"
expect_in "$WORK/stops/report.md" \
  "- Springs: F: linear, 100000 N/m, preload 2000 N; LR, RR: linear, 100000 N/m." \
  "report.md springs"
expect_in "$WORK/stops/report.md" \
  "- Bump and rebound stops (gap, rate, damping): F: bump at 0.12 m, 1e+06 N/m, 2000 N s/m; rebound at 0.06 m, a table of 3 points; LR, RR: none." \
  "report.md stops"
checks=$((checks + 1))
python3 - "$WORK/stops" <<'EOF' || fail "stops: stop_force against the travel"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/system1.csv")))
x = [float(r["spring_defl_F [m]"]) for r in rows]
f = [float(r["stop_force_F [N]"]) for r in rows]
assert max(f) > 1000.0 and max(x) > 0.12, (max(f), max(x))
for xi, fi in zip(x, f):
    assert not (fi > 0.0 and xi <= 0.12) and not (fi < 0.0 and xi >= -0.06), (xi, fi)
EOF

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
