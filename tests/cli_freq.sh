#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond freq: the frequency response of the APC example to the road.
# Both systems write their CSV and the Bode figures; the CSV has one
# magnitude and one phase column per output and track, with units, and
# none for a power; below the hull's first elastic mode (10 Hz) the two
# systems agree; the rigid hull does not twist; a nonlinear shock table
# is linearised at the static equilibrium and says so. Bad options and
# scenarios exit non-zero and write nothing. The response itself is
# checked against closed forms and the time domain in tests/test_freq.c.
#
# usage: bash tests/cli_freq.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_freq
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml
BODES=(bode_driver_acc.png bode_spring_defl_RF.png bode_tire_defl_RM.png bode_tire_force_LF.png
  bode_torsion.png)

run freq "$APC" -o "$WORK/both" --points 41
expect_status 0 "freq, both systems"
checks=$((checks + 1))
[ "$(ls -A "$WORK/both" | sort)" = "$(printf '%s\n' .flexbond-manifest "${BODES[@]}" \
  freq_system1.csv freq_system2.csv | sort)" ] ||
  fail "freq files: $(ls -A "$WORK/both" | tr '\n' ' ')"
expect_in "$OUT" "41 frequencies from 0.1 to 100 Hz" "freq summary"
expect_in "$OUT" "shock_power_LM       a power: no frequency response" "freq: powers left out"
expect_in "$WORK/both/freq_system1.csv" \
  "frequency [Hz],tire_force_LF/left |H| [N/m],tire_force_LF/left phase [deg]," "freq CSV header"
expect_in "$WORK/both/freq_system1.csv" "driver_acc/right |H| [(m/s^2)/m]" "freq CSV: compound unit"
checks=$((checks + 1))
python3 - "$WORK/both" <<'PY' || fail "freq CSV contents"
import csv, sys
d = sys.argv[1]
one = list(csv.reader(open(f"{d}/freq_system1.csv")))
two = list(csv.reader(open(f"{d}/freq_system2.csv")))
head = one[0]
assert head == two[0], "the systems' headers differ"
assert len(one) == 42 and len(two) == 42, (len(one), len(two))
f = [float(r[0]) for r in one[1:]]
assert abs(f[0] - 0.1) < 1e-12 and abs(f[-1] - 100) < 1e-9, f
assert all(b / a > 1.18 and b / a < 1.2 for a, b in zip(f, f[1:])), "not log-spaced"
col = {name: i for i, name in enumerate(head)}
assert not any("power" in name for name in head), "a power has columns"
for r in one[1:] + two[1:]:
    for name, i in col.items():
        if "phase" in name and r[i]:
            assert -180 <= float(r[i]) <= 180, (name, r[i])
# The rigid hull does not twist; the flexible one does.
assert all(float(r[col["torsion/left |H| [rad/m]"]]) == 0 for r in one[1:])
assert max(float(r[col["torsion/left |H| [rad/m]"]]) for r in two[1:]) > 1e-4
# Below 2 Hz, far under the hull's first elastic mode (10.3 Hz), the
# hull's own deformation under the suspension forces changes the response
# by less than 1 % of its largest value there (0.3 % in this run; relative
# to the value itself it is larger in the notches of the wheelbase filter).
low = [(a, b) for a, b in zip(one[1:], two[1:]) if float(a[0]) <= 2]
for name in ["tire_force_LF/left |H| [N/m]", "spring_defl_RF/right |H| [m/m]",
             "driver_acc/left |H| [(m/s^2)/m]"]:
    big = max(float(a[col[name]]) for a, _ in low)
    for a, b in low:
        x, y = float(a[col[name]]), float(b[col[name]])
        assert abs(y - x) <= 0.01 * big, (name, a[0], x, y, big)
PY
for f in "${BODES[@]}"; do
  checks=$((checks + 1))
  [ "$(head -c 8 "$WORK/both/$f" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    fail "$f is not a PNG"
done

run freq "$APC" -o "$WORK/rigid" --system rigid --no-figures --points 11 --f-min 1 --f-max 10
expect_status 0 "freq --system rigid --no-figures"
checks=$((checks + 1))
[ "$(ls -A "$WORK/rigid" | sort | tr '\n' ' ')" = ".flexbond-manifest freq_system1.csv " ] ||
  fail "freq --system rigid files: $(ls -A "$WORK/rigid" | tr '\n' ' ')"
expect_in "$WORK/rigid/freq_system1.csv" $'\n1,' "freq --f-min 1"
expect_in "$WORK/rigid/freq_system1.csv" $'\n10,' "freq --f-max 10"

run freq "$REPO_ROOT/examples/apc6x6_shock_table.yaml" -o "$WORK/table" --system rigid \
  --no-figures --points 5
expect_status 0 "freq of a vehicle with shock tables"
expect_in "$OUT" "nonlinear, linearised at its static equilibrium" "freq says it linearised"

# On an ISO 8608 road: the ride from its spectrum as well.
run freq "$REPO_ROOT/examples/apc6x6_iso_road.yaml" -o "$WORK/iso" --no-figures --points 11
expect_status 0 "freq on an ISO 8608 road"
checks=$((checks + 1))
[ "$(ls -A "$WORK/iso" | sort | tr '\n' ' ')" = \
  ".flexbond-manifest freq_system1.csv freq_system2.csv psd_system1.csv psd_system2.csv ride_psd.json " ] ||
  fail "freq on an ISO road: files $(ls -A "$WORK/iso" | tr '\n' ' ')"
expect_in "$OUT" "ride from the road spectrum: ISO 8608 class C, 0.011 to 2.83 cycles/m" \
  "freq: the road spectrum's band"
expect_in "$WORK/iso/psd_system1.csv" \
  "frequency [Hz],road [m^2/Hz],tire_force_LF [N^2/Hz],spring_defl_RF [m^2/Hz]," "PSD CSV header"
expect_in "$WORK/iso/psd_system1.csv" "driver_acc Wk-weighted [(m/s^2)^2/Hz]" "PSD CSV: weighted"
checks=$((checks + 1))
python3 - "$WORK/iso" <<'PY' || fail "ride_psd.json"
import csv, json, math, sys
d = sys.argv[1]
j = json.load(open(f"{d}/ride_psd.json"))
assert j["road"] == {"class": "C", "gd0_m3": 0.000256, "band_cycles_per_m": [0.011, 2.83],
                     "speed_m_s": j["road"]["speed_m_s"], "tracks": "independent"}, j["road"]
assert abs(j["road"]["speed_m_s"] - 30 / 3.6) < 1e-9
for sys_ in ("system1", "system2"):
    assert 0.3 < j[sys_]["a_w_rms"] < 1.5 and j[sys_]["a_w_output"] == "driver_acc", j[sys_]
# The JSON's a_w is the CSV's weighted PSD integrated (trapezoidal rule in log f).
rows = list(csv.reader(open(f"{d}/psd_system1.csv")))
i = rows[0].index("driver_acc Wk-weighted [(m/s^2)^2/Hz]")
f = [float(r[0]) for r in rows[1:]]
p = [float(r[i]) for r in rows[1:]]
ms = sum(0.5 * (p[k] * f[k] + p[k + 1] * f[k + 1]) * math.log(f[k + 1] / f[k])
         for k in range(len(f) - 1))
assert abs(math.sqrt(ms) - j["system1"]["a_w_rms"]) < 1e-6 * j["system1"]["a_w_rms"]
assert abs(f[0] - 0.011 * 30 / 3.6) < 1e-9 and abs(f[-1] - 2.83 * 30 / 3.6) < 1e-6
PY
run freq "$REPO_ROOT/examples/apc6x6_iso_road.yaml" -o "$WORK/iso_same" --no-figures \
  --points 11 --tracks identical --system rigid
expect_status 0 "freq --tracks identical"
expect_in "$WORK/iso_same/ride_psd.json" '"tracks": "identical"' "ride_psd.json: coherence"
run freq "$APC" -o "$WORK/class" --no-figures --points 11 --road-class b --system rigid
expect_status 0 "freq --road-class b on a bump scenario"
expect_in "$WORK/class/ride_psd.json" '"class": "B", "gd0_m3": 6.4e-05' "freq --road-class"
run freq "$APC" -o "$WORK/bad" --tracks identical
expect_status 1 "freq --tracks on a bump scenario"
expect_in "$ERR" "--tracks is for the ride from an ISO 8608 road" "freq --tracks: message"
expect_absent "$WORK/bad" "freq --tracks on a bump scenario"
run freq "$APC" -o "$WORK/bad" --road-class J
expect_status 1 "freq --road-class J"
expect_in "$ERR" "not an ISO 8608 class A to H" "freq --road-class J: message"
expect_absent "$WORK/bad" "freq --road-class J"

# Beyond FB_FREQ_MAX_HZ the response would overflow (--f-max 1e308 once wrote rows of inf,-nan).
for bad in "--points 1" "--points 2.5" "--f-min 10 --f-max 1" "--f-min -1" "--system both2" \
           "--f-max 1e308" "--f-min 1e-300 --f-max 1e10"; do
  # shellcheck disable=SC2086
  run freq "$APC" -o "$WORK/bad" $bad
  expect_status 1 "freq $bad"
  expect_absent "$WORK/bad" "freq $bad"
done
# The widest range allowed, 1e-300 to 1e9 Hz: every value written is finite (the grid is
# spaced in log f, so the ratio 1e309 never forms).
run freq "$APC" -o "$WORK/wide" --system rigid --no-figures --points 41 --f-min 1e-300 --f-max 1e9
expect_status 0 "freq over 1e-300 to 1e9 Hz"
checks=$((checks + 1))
! grep -qiE 'nan|inf' "$WORK/wide/freq_system1.csv" || fail "freq over 1e-300 to 1e9 Hz: a non-finite value"
run freq "$APC"
expect_status 1 "freq without -o"
expect_in "$ERR" "missing output directory" "freq without -o: message"
run freq "$WORK/none.yaml" -o "$WORK/none"
expect_status 5 "freq of a missing file"
expect_absent "$WORK/none" "freq of a missing file"

# ---- Each command's files stay its own: freq and modes into a run's directory would replace
# run's bode_*.png and mode_NN.png (and a later freq --no-figures remove them from under run's
# report.md); they are refused, nothing changes, and freq's own files still go in beside.
run run "$APC" -o "$WORK/shared" -q
expect_status 0 "run into a directory"
sum_before=$(cd "$WORK/shared" && md5sum bode_*.png mode_*.png report.md)
run freq "$APC" -o "$WORK/shared"
expect_status 5 "freq into run's directory"
expect_in "$ERR" "is flexbond run's, which this freq would replace" "freq into run's directory: message"
run modes "$APC" --system flexible -o "$WORK/shared"
expect_status 5 "modes into run's directory"
expect_in "$ERR" "is flexbond run's, which this modes would replace" "modes into run's directory: message"
run freq "$APC" -o "$WORK/shared" --no-figures
expect_status 0 "freq --no-figures into run's directory"
checks=$((checks + 1))
[ "$(cd "$WORK/shared" && md5sum bode_*.png mode_*.png report.md)" = "$sum_before" ] ||
  fail "run's figures or report changed under freq and modes"
checks=$((checks + 1))
[ -s "$WORK/shared/freq_system1.csv" ] || fail "freq --no-figures: no freq_system1.csv beside run's files"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
