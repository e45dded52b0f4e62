#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# One frame for every position a user reads (docs/scenario-format.md,
# "Frame"): a scenario with frame.origin (examples/truck4x4.yaml: the front
# axle's centre at floor level) gets back its own numbers from flexbond
# mesh's printout, the exported deck and VTU files (mesh, modes,
# animation), and the report, though the
# library works relative to the hull's centre of mass inside. The checks
# are against the file's values, not against an earlier output: the
# generator's rear wall at x_rear = -4.6 m and its floor at z = 0, the
# front axle's corners at x = 0, y = +-0.95 m, the driver's seat at
# x = -0.4 m, a given hull.centre_of_mass, and (examples/truck6x6_bogie.yaml)
# a bogie's pivot and a floor point's output.
#
# usage: bash tests/cli_frame.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_frame
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/truck4x4.yaml "$REPO_ROOT"/examples/*.csv . || exit 2
checks=$((checks + 1))
grep -q "^  origin: front axle centre, floor level" truck4x4.yaml ||
  fail "truck4x4.yaml no longer declares the front axle's frame"

# near A B TOL WHAT: |A - B| <= TOL.
near() {
  checks=$((checks + 1))
  awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(d <= t && -d <= t) }' ||
    fail "$4: $1, expected $2 (within $3)"
}

# The extent of a VTU's or a deck's nodes: "xmin xmax ymin ymax zmin zmax".
vtu_extent() {
  awk '/<Points>/ { on = 1; next } on && /<\/DataArray>/ { exit }
       on && NF == 3 { print }' "$1" | extent
}
inp_extent() {
  awk -F', *' '/^\*NODE/ { on = 1; next } /^\*/ { on = 0 } on && NF == 4 { print $2, $3, $4 }' \
    "$1" | extent
}
extent() {
  awk 'NR == 1 { for (k = 1; k <= 3; ++k) lo[k] = hi[k] = $k }
       { for (k = 1; k <= 3; ++k) { if ($k < lo[k]) lo[k] = $k; if ($k > hi[k]) hi[k] = $k } }
       END { printf "%.12g %.12g %.12g %.12g %.12g %.12g\n", lo[1], hi[1], lo[2], hi[2], lo[3], hi[3] }'
}

# ---- flexbond mesh: the printout says its frame; the mesh's rear wall and
# floor are where the file puts them (x_rear -4.6 m, z 0), to round-off
# (1e-12 m: a few ulps of the move there and back).
run mesh truck4x4.yaml --export hull.vtu
expect_status 0 "mesh --export hull.vtu"
expect_in "$OUT" "positions in the file's frame, from front axle centre, floor level" \
  "mesh names the frame"
read -r xmin _ ymin ymax zmin _ < <(vtu_extent hull.vtu)
near "$xmin" -4.6 1e-12 "the VTU's rearmost node (x_rear)"
near "$zmin" 0 1e-12 "the VTU's floor (z = 0 at floor level)"
near "$ymin" -1.1 1e-12 "the VTU's right wall (width 2.2 m)"
near "$ymax" 1.1 1e-12 "the VTU's left wall (width 2.2 m)"
run mesh truck4x4.yaml --export hull.inp
expect_status 0 "mesh --export hull.inp"
read -r xmin _ _ _ zmin _ < <(inp_extent hull.inp)
near "$xmin" -4.6 1e-12 "the deck's rearmost node (x_rear)"
near "$zmin" 0 1e-12 "the deck's floor"

# A mode's VTU (flexbond modes -o): the mesh at rest, in the file's frame.
run modes truck4x4.yaml --system flexible -o "$WORK/modes"
expect_status 0 "modes --system flexible -o"
read -r xmin _ _ _ zmin _ < <(vtu_extent "$WORK/modes/mode_01.vtu")
near "$xmin" -4.6 1e-12 "mode_01.vtu's rearmost node (x_rear)"
near "$zmin" 0 1e-12 "mode_01.vtu's floor"

# The structure's centre of mass, given as hull.centre_of_mass (in the
# frame), is what the printout says (to its 4 digits). -1.7356 m is the
# generated plates' (the loader refuses one 0.5 % of the length off).
sed 's/^hull:$/hull:\n  centre_of_mass: {x: -1.7356, y: 0}/' truck4x4.yaml >cg.yaml
checks=$((checks + 1))
! cmp -s cg.yaml truck4x4.yaml || fail "fixture cg.yaml: no 'hull:' line"
run mesh cg.yaml
expect_status 0 "mesh with hull.centre_of_mass"
cg=$(sed -n 's/^mass [^,]* kg, centre of mass (\([^,]*\), \([^,]*\), \([^)]*\)) m$/\1 \2 \3/p' "$OUT")
read -r cx cy _ <<<"$cg"
near "${cx:-nan}" -1.7356 5e-4 "the printed centre of mass's x, the file's hull.centre_of_mass.x"
near "${cy:-nan}" 0 5e-4 "the printed centre of mass's y"

# ---- The report: the corners and the values table as the file wrote them.
run run truck4x4.yaml --system rigid -o "$WORK/report" --animate
expect_status 0 "run --system rigid --animate"
# The animation's first frame is the vehicle at the window's start, every
# displacement measured from there: at rest, in the file's frame. Its
# wheels, drawn hanging below the floor, end ahead of x = -4 m (the rear
# axle at -3.4 m), so behind it are the hull's rear wall and floor alone.
read -r xmin _ _ _ zmin _ < <(vtu_extent "$WORK/report/animation_system1_0000.vtu")
near "$xmin" -4.6 1e-12 "the animation's first frame: rearmost node (x_rear)"
zrear=$(awk '/<Points>/ { on = 1; next } on && /<\/DataArray>/ { exit }
             on && NF == 3 && $1 < -4.0 { if (!n++ || $3 < z) z = $3 } END { print z }' \
  "$WORK/report/animation_system1_0000.vtu")
near "${zrear:-nan}" 0 1e-12 "the animation's first frame: the floor at the rear wall"
R=$WORK/report/report.md
expect_in "$R" "| LF | 0, 0.95 |" "the report's front left corner"
expect_in "$R" "| RR | -3.4, -0.95 |" "the report's rear right corner"
expect_in "$R" "| mounts.driver.x | -0.4 | m |" "the report's driver x"
expect_in "$R" "| hull.edges.rear\\_x | -4.6 | m |" "the report's rear edge"
expect_in "$R" "battery 300 kg at x, y = -0.8, -0.5 m" "the report's battery"
expect_in "$R" "The positions below and the pictures are in this frame" "the report's frame row"

# A bogie's pivot and a hull point's `at` (x, y and z) are positions too.
cp "$REPO_ROOT"/examples/truck6x6_bogie.yaml . || exit 2
sed 's/^outputs:/outputs:\n  - {signal: hull_displacement, at: [0, 0.95, 0], direction: z}/' \
  truck6x6_bogie.yaml >bogie.yaml
! cmp -s bogie.yaml truck6x6_bogie.yaml || fail "fixture bogie.yaml: no 'outputs:' line"
run run bogie.yaml --system rigid --no-figures -o "$WORK/bogie"
expect_status 0 "run the 6x6 with a floor point's output"
R=$WORK/bogie/report.md
expect_in "$R" "| bogies.left.pivot\\_x | -3.45 | m |" "the report's bogie pivot"
expect_in "$R" "| outputs\\[0\\].at | 0, 0.95, 0 | m |" "the report's hull point"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
