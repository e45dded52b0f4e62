#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond fmu: the APC example as FMI 3.0 FMUs, used from the outside by
# our own importer (tests/tools/fmu_import.c, $FLEXBOND_FMU_IMPORT): it
# reads modelDescription.xml and dlopens the binary, as a simulation tool
# would. The descriptions validate against the FMI 3.0 schemas (when
# ../shared/data/fmi3-schema is there); the binary needs nothing outside
# the FMU but glibc; co-simulation and model exchange (our RK4) reproduce
# `flexbond run` over the bump; a tunable parameter reproduces a run of
# the changed scenario; the road as inputs holds the static equilibrium
# and a road step loads its tire by the tire's stiffness; the FMI
# protocol checks pass (also under valgrind when it is installed); bad
# options exit non-zero, name the problem and write nothing.
#
# usage: bash tests/cli_fmu.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_fmu
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

# The importer is built only with libxml2 (CMakeLists.txt): skip (77) without it.
IMPORT=${FLEXBOND_FMU_IMPORT:-}
if [ -z "$IMPORT" ]; then
  echo "$NAME: no fmu_import (FLEXBOND_FMU_IMPORT unset: built without libxml2): skipped" >&2
  exit 77
fi
if [ ! -x "$IMPORT" ]; then
  echo "$NAME: FLEXBOND_FMU_IMPORT ('$IMPORT') is not the built fmu_import" >&2
  exit 2
fi
for tool in unzip python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "$NAME: no $tool (make deps-test): skipped" >&2
    exit 77
  fi
done
APC=$REPO_ROOT/examples/apc6x6.yaml
SCHEMA=$REPO_ROOT/../shared/data/fmi3-schema

# The APC's bump: the left front wheel meets it at 5 s (road.bump.first_contact),
# the last wheel leaves it at 8.13 s (as `flexbond fmu --t-end 7` says): a 9 s
# run covers the start (gravity switched on at t = 0, the vehicle settling on
# its tires) and the whole crossing. `flexbond run` has no --t-end: a copy of
# the scenario with t_end 9 (the FMUs are exported from it too, so that both
# describe one scenario; an FMU's horizon is only the longest run it allows).
T_END=9
sed 's/^  t_end: 15 /  t_end: 9 /' "$APC" >"$WORK/apc.yaml"
sed 's/^  t_end: 15 /  t_end: 9 /; s/^  speed_kmh: 10 /  speed_kmh: 15 /' "$APC" >"$WORK/apc15.yaml"
sed 's/^  t_end: 15 /  t_end: 9 /; s/^  initial: zero /  initial: static /' "$APC" >"$WORK/apc_static.yaml"
checks=$((checks + 1))
grep -q '^  t_end: 9 ' "$WORK/apc.yaml" && grep -q '^  speed_kmh: 15 ' "$WORK/apc15.yaml" &&
  grep -q '^  initial: static ' "$WORK/apc_static.yaml" ||
  fail "the scenario copies: examples/apc6x6.yaml no longer writes t_end, speed_kmh or initial as expected"

# export NAME ARGS...: flexbond fmu of ARGS into $WORK/NAME.fmu, unzipped into $WORK/NAME.
export_fmu() {
  local name=$1
  shift
  run fmu "$@" -q -o "$WORK/$name.fmu"
  expect_status 0 "flexbond fmu $*"
  checks=$((checks + 1))
  unzip -q "$WORK/$name.fmu" -d "$WORK/$name" 2>>"$ERR" || fail "unzip $name.fmu"
}

export_fmu s1 "$WORK/apc.yaml" --system rigid
export_fmu par "$WORK/apc.yaml" --system rigid --parameters road.speed_kmh
export_fmu road "$WORK/apc_static.yaml" --system rigid --road inputs
S1=$WORK/s1
BIN=$S1/binaries/x86_64-linux
ID=$(sed -n 's/.*<CoSimulation modelIdentifier="\([^"]*\)".*/\1/p' "$S1/modelDescription.xml")
checks=$((checks + 1))
[ -n "$ID" ] && [ -f "$BIN/$ID.so" ] || fail "the binary binaries/x86_64-linux/<modelIdentifier>.so ($ID)"

# ---- The descriptions against the FMI 3.0 schemas.
if ! command -v xmllint >/dev/null 2>&1; then
  echo "$NAME: no xmllint (libxml2-utils): the descriptions are not validated" >&2
elif [ -f "$SCHEMA/fmi3ModelDescription.xsd" ] && [ -f "$SCHEMA/fmi3BuildDescription.xsd" ]; then
  for fmu in s1 par road; do
    checks=$((checks + 1))
    xmllint --noout --schema "$SCHEMA/fmi3ModelDescription.xsd" \
      "$WORK/$fmu/modelDescription.xml" >"$OUT" 2>"$ERR" ||
      fail "$fmu: modelDescription.xml against fmi3ModelDescription.xsd"
    checks=$((checks + 1))
    xmllint --noout --schema "$SCHEMA/fmi3BuildDescription.xsd" \
      "$WORK/$fmu/sources/buildDescription.xml" >"$OUT" 2>"$ERR" ||
      fail "$fmu: sources/buildDescription.xml against fmi3BuildDescription.xsd"
  done
else
  echo "$NAME: $SCHEMA has no FMI 3.0 schemas: the descriptions are not validated" >&2
fi
checks=$((checks + 1))
grep -q 'causality="parameter"[^>]*name="road.speed_kmh"\|name="road.speed_kmh"[^>]*causality="parameter"' \
  "$WORK/par/modelDescription.xml" || fail "--parameters road.speed_kmh: no such parameter"

# ---- Self-contained: every library the binary needs resolves inside
# binaries/x86_64-linux/, but glibc's own (and the kernel's vdso), which
# every Linux host has and which must not be bundled.
checks=$((checks + 1))
ldd "$BIN/$ID.so" >"$OUT" 2>"$ERR" || fail "ldd of $ID.so"
outside=$(awk -v bin="$BIN/" '
  $1 ~ /^(linux-vdso|linux-gate)\.so/ || $1 ~ /ld-linux/ { next }
  $1 ~ /^lib(c|m|pthread|dl|rt)\.so\./ { next }
  $2 == "=>" && index($3, bin) != 1 { print $1 " => " $3 }
  $2 != "=>" && $1 !~ /^\// { print $0 }' "$OUT")
[ -z "$outside" ] || fail "libraries resolved outside the FMU: $(echo "$outside" | tr '\n' ' ')"

# ---- Against `flexbond run`: co-simulation at 1 ms and model exchange.
run run "$WORK/apc.yaml" --system rigid --no-figures --plain-header -q -o "$WORK/run"
expect_status 0 "flexbond run (t_end $T_END s)"
run run "$WORK/apc15.yaml" --system rigid --no-figures --plain-header -q -o "$WORK/run15"
expect_status 0 "flexbond run at 15 km/h"

# compare RUN.csv FMU.csv REL DESCRIPTION: every column of RUN (the
# scenario's outputs) against the FMU's column of that name, at every
# sample time of RUN (the FMU's rows are on the same 1 ms grid; a time
# RUN has and FMU lacks fails): max |diff| <= REL * the column's range in
# RUN, or 1e-9 for a column that does not vary (torsion: 0 with the
# rigid hull). Prints each column's worst difference relative to its range.
compare() {
  checks=$((checks + 1))
  python3 - "$1" "$2" "$3" <<'EOF' >"$OUT" 2>"$ERR" || fail "$4: $(cat "$OUT")"
import csv, sys
def read(path):
    with open(path) as fp:
        r = csv.reader(fp)
        head = next(r)
        return head, [[float(v) for v in row] for row in r]
hr, rr = read(sys.argv[1])
hf, rf = read(sys.argv[2])
rel = float(sys.argv[3])
at = {round(row[0] * 1e6): row for row in rf}
bad = []
missing = [row[0] for row in rr if round(row[0] * 1e6) not in at]
if missing or len(rr) < 2:
    bad.append("%d sample times of the run missing in the FMU's (first %s)" % (len(missing), missing[:1]))
for j, name in enumerate(hr[1:], 1):
    if name not in hf:
        bad.append(name + " not an output of the FMU")
        continue
    k = hf.index(name)
    col = [row[j] for row in rr]
    rng = max(col) - min(col)
    worst, when = 0.0, 0.0
    for row in rr:
        other = at.get(round(row[0] * 1e6))
        if other is not None and abs(other[k] - row[j]) > worst:
            worst, when = abs(other[k] - row[j]), row[0]
    limit = rel * rng if rng > 0 else 1e-9
    print("%s: max |diff| %.3g = %.3g of its range %.4g, at t = %g s" % (name, worst, worst / rng if rng > 0 else 0, rng, when))
    if worst > limit:
        bad.append("%s differs by %.3g > %.3g" % (name, worst, limit))
print("; ".join(bad))
sys.exit(1 if bad else 0)
EOF
  echo "$NAME: $4:" >&2
  sed 's/^/  /' "$OUT" >&2
}

# Both sides integrate the same model at the scenario's tolerances (rtol
# 1e-6, atol 1e-8) with CVODE; the FMU restarts CVODE at each 1 ms
# communication point (a fresh step-size history: other steps, not
# another model), so the two differ by their global errors, each of the
# order of rtol times the signal's scale, amplified by the bump's
# transients: measured 2.6e-6 of the range at most (tire_force_LF in the
# bump, 0.053 N of 20.7 kN), 1.3e-6 for the shock's power, 2e-7 for the
# spring's deflection. The run's CSV holds 10 significant digits. 1e-4 of
# the range allows about 40 times that, as result_compare allows two
# integrations at these tolerances (tests/tools/result_compare.c).
REL_CS=1e-4
# Model exchange, classical RK4 at h = 1e-4 s: the stiffest mode is the
# unsprung wheel on its tire's damper, c/m = 140000/175 = 800 1/s, so
# h * lambda = 0.08 and RK4's local error (h lambda)^5 / 120 ~ 3e-8 per step
# of that mode; its global error is below the run's own CVODE error. The
# road's kinks are time events landed on exactly; this System 1 model has
# no event indicators (the APC's tires are linear: no lift-off law), so no
# event is located only to h. Measured 1.5e-6 of the range at most: the
# same 1e-4 as co-simulation. (A model with a lift-off law would need a
# tolerance for the switch up to h = 0.1 ms late: (jump in the force) *
# h / (the mode's period) of the range.)
REL_ME=1e-4

t0=$(date +%s.%N)
"$IMPORT" cs "$S1" 1e-3 "$T_END" "$WORK/cs.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs (1 ms, $T_END s)"
[ "$status" -ne 0 ] || compare "$WORK/run/system1.csv" "$WORK/cs.csv" "$REL_CS" \
  "co-simulation at 1 ms against flexbond run"
t1=$(date +%s.%N)
"$IMPORT" --h 1e-4 me "$S1" 1e-3 "$T_END" "$WORK/me.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import me (RK4 at 0.1 ms, $T_END s)"
expect_in "$ERR" "event iterations" "model exchange: its events counted"
[ "$status" -ne 0 ] || compare "$WORK/run/system1.csv" "$WORK/me.csv" "$REL_ME" \
  "model exchange (RK4, h = 0.1 ms) against flexbond run"
t2=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" -v c="$t2" -v n="$NAME" \
  'BEGIN { printf "%s: co-simulation %.1f s, model exchange %.1f s\n", n, b - a, c - b }' >&2

# ---- A tunable parameter: road.speed_kmh = 15 against the run of the
# scenario written with 15 km/h (the same comparison as above).
"$IMPORT" cs "$WORK/par" 1e-3 "$T_END" "$WORK/cs15.csv" road.speed_kmh=15 >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs with road.speed_kmh=15"
[ "$status" -ne 0 ] || compare "$WORK/run15/system1.csv" "$WORK/cs15.csv" "$REL_CS" \
  "co-simulation with road.speed_kmh = 15 against flexbond run of the scenario at 15 km/h"
# And the parameter is not ignored: at 15 km/h the run at 10 km/h is not reproduced.
checks=$((checks + 1))
if [ "$status" -eq 0 ] && python3 - "$WORK/run/system1.csv" "$WORK/cs15.csv" <<'EOF' >/dev/null 2>&1; then
import csv, sys
a = list(csv.reader(open(sys.argv[1])))[1:]
b = list(csv.reader(open(sys.argv[2])))[1:]
sys.exit(0 if max(abs(float(x[1]) - float(y[1])) for x, y in zip(a, b)) < 1.0 else 1)
EOF
  fail "road.speed_kmh = 15 gives the 10 km/h run's tire_force_LF"
fi

# ---- Events: examples/apc6x6_liftoff.yaml, whose unilateral tires leave
# the road over the bump and land again (18 event indicators). The run
# locates each landing with CVODE's root finding, the co-simulation the
# same way inside its steps, and the importer's model exchange by
# bisection of its RK4 step (tests/tools/fmu_import.c). A landing on the
# tire's damper makes the force jump by c v, which decays in m / c =
# 1.25 ms, at about 2.3e8 N/s: a landing time that differs by dt moves the
# next sample by 2.3e8 dt N. The integrators' landing times follow the
# wheel's position, each to its own global error (rtol 1e-6), and differ
# by a few 1e-7 s: measured 4.7e-5 (co-simulation) and 1.9e-4 (model
# exchange) of the tire force's range, both at the first landing
# (t = 1.676 s); every other output within 1e-4. 1e-3 of the range
# admits five times the larger; a landing one RK4 step (0.1 ms) late,
# the root not located, gives 7e-2.
REL_EVENTS=1e-3
LIFTOFF=$REPO_ROOT/examples/apc6x6_liftoff.yaml
export_fmu lift "$LIFTOFF" --system rigid
checks=$((checks + 1))
[ "$(grep -c '<EventIndicator ' "$WORK/lift/modelDescription.xml")" -gt 0 ] ||
  fail "apc6x6_liftoff: no event indicators in modelDescription.xml"
run run "$LIFTOFF" --system rigid --no-figures --plain-header -q -o "$WORK/runlift"
expect_status 0 "flexbond run apc6x6_liftoff.yaml"
T_LIFT=$(sed -n 's/^  t_end: \([0-9.]*\) .*/\1/p' "$LIFTOFF")
"$IMPORT" cs "$WORK/lift" 1e-3 "$T_LIFT" "$WORK/cslift.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs of apc6x6_liftoff"
[ "$status" -ne 0 ] || compare "$WORK/runlift/system1.csv" "$WORK/cslift.csv" "$REL_EVENTS" \
  "co-simulation with tires leaving the road against flexbond run"
"$IMPORT" --h 1e-4 me "$WORK/lift" 1e-3 "$T_LIFT" "$WORK/melift.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import me of apc6x6_liftoff"
[ "$status" -ne 0 ] || compare "$WORK/runlift/system1.csv" "$WORK/melift.csv" "$REL_EVENTS" \
  "model exchange with tires leaving the road (roots located) against flexbond run"

# ---- The road as inputs, from the static equilibrium (initial: static).
# All road inputs at zero: the vehicle stays where it is, every output
# constant to 1e-9 of the weight (117720 N; load.total_weight) for the
# forces, and to 1e-9 absolute for the other outputs (m, rad, m/s^2, W of
# a vehicle at rest: numerically zero changes). Measured: 8e-10 N.
ROAD=$WORK/road
"$IMPORT" cs "$ROAD" 1e-3 0.5 "$WORK/rest.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs with the road inputs at zero"
checks=$((checks + 1))
python3 - "$WORK/rest.csv" <<'EOF' >"$OUT" 2>"$ERR" || fail "the road inputs at zero: not at rest: $(cat "$OUT")"
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head, data = rows[0], [[float(v) for v in r] for r in rows[1:]]
bad = []
for j, name in enumerate(head[1:], 1):
    col = [r[j] for r in data]
    spread = max(col) - min(col)
    limit = 1e-9 * 117720 if "force" in name else 1e-9
    if spread > limit:
        bad.append("%s moves by %.3g" % (name, spread))
print("; ".join(bad))
sys.exit(1 if bad or len(data) < 500 else 0)
EOF
# A step of +0.01 m under the left front wheel after initialisation: at
# the first communication point, 10 us later, its contact force has risen
# by k_tire * 0.01 = 500000 N/m * 0.01 m = 5000 N (wheel.tire_k), less
# what the wheel's motion takes back: in 10 us the 175 kg wheel reaches
# 5000 / 175 * 1e-5 = 2.9e-4 m/s, on the tire's damper (140000 N s/m) 40
# N: 1 % (measured 4960.2 N). At 1 ms it would be half of it (the wheel
# follows on the damper's time constant m/c = 1.25 ms). Within 2 %; the
# other wheels' forces move by less than 1 N.
"$IMPORT" cs "$ROAD" 1e-5 1e-5 "$WORK/step.csv" @road_z_LF=0.01 >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs with a road step under LF"
checks=$((checks + 1))
python3 - "$WORK/step.csv" <<'EOF' >"$OUT" 2>"$ERR" || fail "a road step of 0.01 m under LF: $(cat "$OUT")"
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head, r0, r1 = rows[0], [float(v) for v in rows[1]], [float(v) for v in rows[2]]
rise = r1[head.index("contact_force_LF")] - r0[head.index("contact_force_LF")]
others = max(abs(r1[head.index(n)] - r0[head.index(n)])
             for n in head if n.startswith("contact_force_") and n != "contact_force_LF")
print("contact_force_LF rises by %.6g N, the others by %.3g N at most" % (rise, others))
sys.exit(0 if abs(rise - 5000.0) <= 0.02 * 5000.0 and others < 1.0 else 1)
EOF

# ---- The FMI protocol checks (tests/tools/fmu_import.c: run_checks).
checks=$((checks + 1))
"$IMPORT" checks "$S1" >"$OUT" 2>"$ERR" || fail "fmu_import checks: $(grep -c '^FAIL' "$OUT") failed: $(grep '^FAIL' "$OUT" | head -20)"
grep '^FAIL' "$OUT" >&2
if ldd "$IMPORT" 2>/dev/null | grep -q 'libasan'; then
  # A sanitizer build: LeakSanitizer has checked the importer's runs
  # above; memcheck cannot run an AddressSanitizer binary.
  echo "$NAME: a sanitizer build: the checks are not run under memcheck" >&2
elif command -v valgrind >/dev/null 2>&1; then
  # One OpenBLAS thread with its SSE3 kernels, as `make valgrind` runs
  # (Makefile): memcheck serialises threads and is slow on AVX2 kernels.
  # One report inside glibc's ld.so is suppressed (tests/valgrind.supp
  # says why); the importer keeps the FMU's libraries mapped
  # (RTLD_NODELETE), so libgomp's block stays reachable.
  # "Still reachable" blocks (OpenBLAS's and glibc's, held until exit) are
  # not errors; definite and indirect leaks are. Exit 99 is memcheck's;
  # 1 is a failed check, already reported above.
  checks=$((checks + 1))
  OPENBLAS_NUM_THREADS=1 OPENBLAS_CORETYPE=Prescott \
    valgrind --leak-check=full --error-exitcode=99 --errors-for-leak-kinds=definite,indirect \
    --suppressions="$REPO_ROOT/tests/valgrind.supp" \
    "$IMPORT" checks "$S1" >"$OUT" 2>"$ERR"
  status=$?
  [ "$status" -ne 99 ] || fail "fmu_import checks under valgrind: memcheck errors: $(grep -E 'ERROR SUMMARY|definitely|indirectly|Invalid|uninitialised' "$ERR" | head -10)"
else
  echo "$NAME: no valgrind: the checks are not run under memcheck" >&2
fi

# ---- System 2: one short co-simulation run of the flexible hull.
export_fmu s2 "$WORK/apc.yaml" --system flexible
"$IMPORT" cs "$WORK/s2" 1e-3 0.5 "$WORK/s2.csv" >"$OUT" 2>"$ERR"
status=$?
expect_status 0 "fmu_import cs of the System 2 FMU (0.5 s)"
checks=$((checks + 1))
[ "$(wc -l <"$WORK/s2.csv")" -eq 502 ] || fail "System 2: $(wc -l <"$WORK/s2.csv") lines, not 502"

# ---- Bad inputs: non-zero, the problem named, no file at -o.
run fmu "$APC" --system rigid
checks=$((checks + 1))
[ "$status" -ne 0 ] || fail "no -o: exit 0"
expect_in "$ERR" "-o" "no -o: named"
run fmu "$WORK/no-such.yaml" --system rigid -o "$WORK/bad1.fmu"
checks=$((checks + 1))
[ "$status" -ne 0 ] || fail "a missing scenario: exit 0"
expect_in "$ERR" "no-such.yaml" "a missing scenario: named"
expect_absent "$WORK/bad1.fmu" "a missing scenario"
run fmu "$APC" --system rigid --parameters no.such.key -o "$WORK/bad2.fmu"
checks=$((checks + 1))
[ "$status" -ne 0 ] || fail "--parameters no.such.key: exit 0"
# The loader names the first part of the key the file lacks ("has no key 'no'").
expect_in "$ERR" "'no'" "--parameters no.such.key: named"
expect_absent "$WORK/bad2.fmu" "--parameters no.such.key"
run fmu "$APC" --system rigid --road nonsense -o "$WORK/bad3.fmu"
checks=$((checks + 1))
[ "$status" -ne 0 ] || fail "--road nonsense: exit 0"
expect_in "$ERR" "nonsense" "--road nonsense: named"
expect_absent "$WORK/bad3.fmu" "--road nonsense"

# bad NAME EXIT TEXT ARGS...: flexbond fmu ARGS exits EXIT (docs/errors.md:
# 1 a bad option, 2 invalid input, 5 I/O), saying TEXT, writing nothing new.
bad() {
  local name=$1 code=$2 text=$3
  shift 3
  run fmu "$@"
  checks=$((checks + 1))
  [ "$status" -eq "$code" ] || fail "$name: exit $status, not $code"
  expect_in "$ERR" "$text" "$name: named"
}
bad "-o without .fmu" 1 ".fmu" "$APC" --system rigid -o "$WORK/bad4.zip"
expect_absent "$WORK/bad4.zip" "-o without .fmu"
bad "--model-identifier my-model" 1 "my-model" "$APC" --system rigid \
  --model-identifier my-model -o "$WORK/bad5.fmu"
expect_absent "$WORK/bad5.fmu" "--model-identifier my-model"
bad "a parameter twice" 1 "twice" "$APC" --system rigid \
  --parameters road.speed_kmh,road.speed_kmh -o "$WORK/bad6.fmu"
mkdir -p "$WORK/dir.fmu"
bad "-o a folder" 5 "folder" "$APC" --system rigid -o "$WORK/dir.fmu"
bad "simulation.t_end as a parameter" 2 "horizon" "$APC" --system rigid \
  --parameters simulation.t_end -o "$WORK/bad7.fmu"
expect_absent "$WORK/bad7.fmu" "simulation.t_end as a parameter"
bad "a road parameter with the road as inputs" 2 "does not use" "$APC" --system rigid \
  --road inputs --parameters road.speed_kmh -o "$WORK/bad8.fmu"
expect_absent "$WORK/bad8.fmu" "a road parameter with the road as inputs"
# -o naming the scenario itself: refused, the scenario left as it was.
cp "$WORK/apc.yaml" "$WORK/self.fmu"
sum_before=$(cksum <"$WORK/self.fmu")
bad "-o the scenario itself" 2 "overwrite" "$WORK/self.fmu" --system rigid -o "$WORK/self.fmu"
checks=$((checks + 1))
[ "$(cksum <"$WORK/self.fmu")" = "$sum_before" ] || fail "-o the scenario itself: it changed"
# With the road as inputs the scenario's road is not driven on: a horizon
# before its bump is no error, and a road value is a fixed parameter
# otherwise (set before initialisation only).
run fmu "$APC" --system rigid --road inputs --t-end 3 -q -o "$WORK/short.fmu"
expect_status 0 "--road inputs --t-end 3 (before the scenario's bump)"
checks=$((checks + 1))
grep -q 'name="road.speed_kmh"[^>]*variability="fixed"' "$WORK/par/modelDescription.xml" ||
  fail "road.speed_kmh: not a fixed parameter"

echo "$NAME: $checks checks, $failures failures" >&2
[ "$failures" -eq 0 ]
