#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# examples/ifv6x6_turret.yaml, the vehicle of the mounted rigid bodies, the
# stops and the bogies together (docs/scenario-format.md): both systems run
# it, and their results hold to answers that do not come from the run:
#   - at rest, the roof ring carries the turret and the two seats hung in
#     it, -(2500 + 2 x 110) kg x g = -26683.2 N on the ring (the bushing's
#     effort is the force of the body on its parent, up positive);
#   - at rest, the tires carry everything: load.total_weight plus the
#     weights of the driver's mount, the three bodies, the six wheels and
#     the two bogies' beams (each fragment adds its own weight);
#   - the left front suspension reaches its bump stop over the 0.3 m
#     obstacle, and no stop pushes before the first wheel meets it;
#   - the roof's vertical acceleration at the ring, read from the hull's
#     six rigid coordinates in System 1 (M^-1 times the effort), integrates
#     to the roof's velocity there, read from their flows (an output the
#     test adds): within 1e-3 of its range (trapezoids at 1 kHz);
#   - the report and the modes name what the vehicle has (its turret, its
#     seats, its bogies, the free horizontal motions of a hull in six
#     degrees of freedom) and nothing it lacks (an engine).
# Tolerances: the static state is the solver's equilibrium, exact to its
# Newton tolerance; 1e-6 of the forces is far above that and far below
# any modelling slip (one wheel's weight is 1.3 % of the tires' sum).
#
# usage: bash tests/cli_turret.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_turret
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
EX=$IN/ifv.yaml
sed 's/^outputs:/outputs:\n  - {signal: hull_velocity, at: [-1.90, 0.00, 1.80], direction: z, name: ring_vel_z}/' \
  "$REPO_ROOT/examples/ifv6x6_turret.yaml" >"$EX"
checks=$((checks + 1))
grep -q "name: ring_vel_z" "$EX" || fail "fixture: no outputs line"
run run "$EX" -o "$WORK/out" --no-figures -q
expect_status 0 "run both systems"
for f in system1.csv system2.csv report.md summary.json; do
  checks=$((checks + 1))
  [ -s "$WORK/out/$f" ] || fail "no $f"
done

checks=$((checks + 1))
python3 - "$WORK/out" <<'EOF' || fail "the static forces and the stops"
import csv, sys
g = 9.81
bodies = 2500 + 2 * 110              # the turret and its two seats
weight = (107910                     # load.total_weight
          + g * (100                 # the driver's mount
                 + bodies
                 + 6 * 200           # the wheels
                 + 2 * 250))         # the bogies' beams
for system in ("system1", "system2"):
    rows = list(csv.DictReader(open(f"{sys.argv[1]}/{system}.csv")))
    first = rows[0]
    ring = float(first["ring_force_z [N]"])
    assert abs(ring + bodies * g) <= 1e-6 * bodies * g, (system, ring, -bodies * g)
    stop = [float(r["stop_force_LF [N]"]) for r in rows]
    t = [float(r["t [s]"]) for r in rows]
    assert max(stop) > 1000.0, (system, max(stop))
    assert all(f == 0.0 for ti, f in zip(t, stop) if ti < 0.5), system
    if system == "system1":
        a = [float(r["ring_acc_z [m/s^2]"]) for r in rows]
        v = [float(r["ring_vel_z [m/s]"]) for r in rows]
        w, worst = v[0], 0.0
        for k in range(1, len(rows)):
            w += 0.5 * (a[k] + a[k - 1]) * (t[k] - t[k - 1])
            worst = max(worst, abs(w - v[k]))
        assert worst <= 1e-3 * (max(v) - min(v)), (worst, max(v) - min(v))
# Every tire's static reaction, each system's, from summary.json.
import json
data = json.load(open(f"{sys.argv[1]}/summary.json"))
def tire_statics(node):
    if isinstance(node, dict):
        if "peak_force" in node and isinstance(node["peak_force"], dict):
            yield {k: v["static"] for k, v in node["peak_force"].items()}
        for v in node.values():
            yield from tire_statics(v)
    elif isinstance(node, list):
        for v in node:
            yield from tire_statics(v)
found = list(tire_statics(data))
assert len(found) == 2, len(found)
for statics in found:
    assert len(statics) == 6, statics
    total = sum(statics.values())
    assert abs(total - weight) <= 1e-6 * weight, (total, weight)
EOF

R=$WORK/out/report.md
expect_in "$R" "| layout | 6 corners, 1 mounted body on a spring, 3 rigid bodies on bushings, 2 walking-beam bogies, 1 anti-roll bar, 20 outputs |" \
  "the report's layout"
expect_in "$R" "  - turret: 2500 kg on the hull, 1 bushing, in System 2 coupled to the nodes of ROOF within 0.9 m." \
  "the report's turret"
expect_in "$R" "  - gunner: 110 kg on turret, 1 bushing." "the report's gunner"
# The hull in six degrees of freedom: its surge, sway and yaw are free, three
# zero modes besides the support's self-stress.
expect_in "$R" "and 3 of the vehicle's free surge, sway and yaw left out." "the zero modes"
for word in turret gunner commander "bogie pitch left" "turret pitch"; do
  expect_in "$R" "$word" "the report names the $word"
done
checks=$((checks + 1))
! grep -qi "engine" "$R" || fail "the report speaks of an engine the vehicle lacks"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
