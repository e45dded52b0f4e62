#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A hull reduced elsewhere (hull.mesh.reduced, docs/reduced-hulls.md)
# through the real flexbond command: examples/apc6x6_reduced.yaml runs
# with System 2, its report says what a superelement lacks (no mode
# pictures, no GIF), a hull point on an interface node is an output; and
# each bad input is refused at FILE:LINE:COL: KEY (exit status 5 for a
# missing file, as a missing deck; 2 otherwise): a missing file, a
# non-symmetric K (fb_reduced_check, naming the matrix file), a suspension
# point, a load point or an edge end off the interface, a hull point off
# it, a coupling, a missing or superfluous mass file, and the attach
# file's (points by node id).
#
# usage: bash tests/cli_reduced.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_reduced
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/apc6x6_reduced.yaml "$REPO_ROOT"/examples/apc6x6_reduced_*.mtx \
  "$REPO_ROOT"/examples/apc6x6_reduced_nodes.csv . || exit 2
OK=apc6x6_reduced.yaml

# ---- The example runs; what a superelement cannot draw is said.
run run "$OK" --system flexible --animate -o "$WORK/run"
expect_status 0 "run --system flexible --animate"
expect_in "$ERR" "no hull stresses (stress_peaks.csv): the hull is a superelement, which has no shell elements" \
  "run: a superelement has no stresses"
expect_in "$WORK/run/report.md" "No hull stresses: the hull is a superelement, which has no shell elements." \
  "the report says why there are no stresses"
expect_in "$WORK/run/report.md" "a free-free superelement over 12 interface nodes (72 DOFs)" \
  "the report's hull clause"
expect_in "$WORK/run/report.md" "No mode pictures: the hull is a superelement" \
  "the report says why there are no mode pictures"
expect_in "$WORK/run/report.md" "No GIF: the hull is a superelement" \
  "the report says why there is no GIF"
expect_absent "$WORK/run/mode_01.png" "no mode picture"
expect_absent "$WORK/run/animation_system2.gif" "no GIF"
checks=$((checks + 1))
[ -f "$WORK/run/animation_system2.pvd" ] || fail "the animation's VTU series is written"

# A hull point on an interface node (the left front suspension point's,
# node 24 of the nodes file) is an output.
xyz=$(awk -F', ' '$1 == 24 { print $2 ", " $3 ", " $4 }' apc6x6_reduced_nodes.csv)
sed "s/^road:/  - signal: hull_displacement\n    at: [$xyz]\n    direction: z\n\nroad:/" "$OK" >point.yaml
run run point.yaml --system flexible --no-figures -o "$WORK/point"
expect_status 0 "a hull point on an interface node"
expect_in "$WORK/point/system2.csv" "hull_displacement" "the hull point's column"

# The modes command names the superelement; a hull mass on an interface
# node (the engine's mount point) adds its mass.
sed 's/^  material:/  masses: [{name: battery, mass: 300, x: 1.70, y: -0.55}]\n  material:/' \
  "$OK" >mass.yaml
run modes --system flexible mass.yaml
expect_status 0 "modes with a hull mass on an interface node"
expect_in "$OUT" "free-free hull (a superelement over 12 interface nodes): 6 rigid-body modes" \
  "modes names the superelement"

# ---- Refused at their keys.
sed 's/nodes: apc6x6_reduced_nodes.csv/nodes: none.csv/' "$OK" >b_missing.yaml
awk 'NR == 4 { $0 = "-12345.5" } 1' apc6x6_reduced_K.mtx >k_asym.mtx
sed 's/k: apc6x6_reduced_K.mtx/k: k_asym.mtx/' "$OK" >b_asym.yaml
sed '0,/      x: 1.90 /s//      x: 1.50 /' "$OK" >b_corner.yaml
sed 's/^road:/  - signal: hull_displacement\n    at: [0.0, 0.0, -0.86]\n    direction: z\n\nroad:/' \
  "$OK" >b_point.yaml
sed 's/^      nodes: apc6x6_reduced_nodes.csv.*/&\n    coupling:\n      kind: kinematic\n      radius: 0.1\n      surface: FLOOR/' \
  "$OK" >b_coupling.yaml
sed '/      m: apc6x6_reduced_M.mtx/d' "$OK" >b_nom.yaml
sed 's/      x: \[-1.00, 0.40, 1.90\]/      x: [-1.00, 0.40, 1.90, 2.00]/' "$OK" >b_load.yaml
sed 's/    front_x: 2.47813311938948 /    front_x: 2.30 /' "$OK" >b_edge.yaml
sed 's/      format: mtx /      format: dmig /' "$OK" >b_dmigm.yaml

# Points attached by node id (hull.mesh.reduced.attach): the left front
# suspension point's own node loads; another node is refused at the
# corner's key (System 2 checks the distance); a node that is no interface
# node, a set no point has and a bad line at the file's line.
attach() {
  printf '%b' "$2" >"at_$1.csv"
  sed "s/^      nodes: apc6x6_reduced_nodes.csv.*/&\n      attach: at_$1.csv/" "$OK" >"a_$1.yaml"
}
attach ok 'SUSP_LF, 24\nengine, 18\n'
attach far 'SUSP_LF, 9\n'
attach bad '# set, node\nSUSP_LF, 999\n'
attach set 'SUSP_XX, 24\n'
attach syntax 'SUSP_LF 24\n'
run mesh a_ok.yaml
expect_status 0 "attach by the points' own node ids"

CASES=(
  "2|mesh a_far.yaml|$(at a_far.yaml '      x: 1.90 ' 1.90) suspensions.axles[0].x: the scenario puts SUSP_LF at (1.9, 1.05) m, the mesh's node 9 at (-1, -1.05) m"
  "2|mesh a_bad.yaml|$(at a_bad.yaml 'attach: at_bad.csv' at_bad) hull.mesh.reduced.attach: ./at_bad.csv:2: the node is no interface node"
  "2|mesh a_set.yaml|$(at a_set.yaml 'attach: at_set.csv' at_set) hull.mesh.reduced.attach: ./at_set.csv:1: no corner (SUSP_<CORNER>), mount or hull mass (MASS_<NAME>) of the scenario has this set"
  "2|mesh a_syntax.yaml|$(at a_syntax.yaml 'attach: at_syntax.csv' at_syntax) hull.mesh.reduced.attach: ./at_syntax.csv:1: expected 'SET, id'"
  "5|mesh b_missing.yaml|$(at b_missing.yaml 'nodes: none.csv' none.csv) hull.mesh.reduced.nodes: ./none.csv: cannot open"
  "2|run b_asym.yaml --system flexible -o $WORK/asym|$(at b_asym.yaml 'k: k_asym.mtx' k_asym) hull.mesh.reduced.k: ./k_asym.mtx: K is not symmetric: K(node 1 uy, node 1 ux) = -12345.5 but K(node 1 ux, node 1 uy) = 2.30981e+08"
  "2|mesh b_corner.yaml|$(at b_corner.yaml '      x: 1.50 ' 1.50) suspensions.axles[0].x: the scenario puts SUSP_LF at (1.5, 1.05) m, the mesh's node 24 at (1.9, 1.05) m"
  "2|mesh b_point.yaml|$(at b_point.yaml 'at: [0.0' '[') outputs[7].at: the hull is a superelement, whose motion is known at its interface nodes only: the nearest, node 13, is 1.12 m"
  "2|mesh b_coupling.yaml|$(at b_coupling.yaml 'kind: kinematic' kinematic) hull.mesh.coupling.kind: a reduced hull has no surface to couple to"
  "2|mesh b_load.yaml|$(at b_load.yaml '    grid:' grid) load.points[6]: the scenario puts a point of LOAD at (2, -1.05) m, the nearest interface node, 21, at (1.9, -1.05) m (they must agree within 1 mm)"
  "2|mesh b_edge.yaml|$(at b_edge.yaml 'front_x: 2.30' 2.30) hull.edges.front_x: the scenario puts a point of FRONT_EDGE at (2.3, 1.05) m, the nearest interface node, 32"
  "2|mesh b_nom.yaml|$(at b_nom.yaml 'format: mtx' format) hull.mesh.reduced.m: a hull needs its mass: the file of M"
  "2|mesh b_dmigm.yaml|$(at b_dmigm.yaml 'm: apc6x6_reduced_M.mtx' apc6x6) hull.mesh.reduced.m: a DMIG file holds both matrices (KAAX and MAAX)"
)
for c in "${CASES[@]}"; do
  IFS='|' read -r code args want <<<"$c"
  # shellcheck disable=SC2086 # the arguments are words
  run $args
  expect_status "$code" "$args"
  expect_in "$ERR" "flexbond: $want" "$args"
done
expect_absent "$WORK/asym" "no output of a refused run"

# The mesh command: the superelement's matrices are written, no deck.
run mesh "$OK" --export-matrices "$WORK/matrices"
expect_status 0 "mesh --export-matrices"
expect_in "$OUT" "hull: a superelement over 12 interface nodes (72 DOFs)" "mesh names the superelement"
expect_in "$OUT" "wrote $WORK/matrices: K.mtx, M.mtx (72 x 72)" "mesh --export-matrices"
run mesh "$OK" --export "$WORK/hull.inp"
expect_status 2 "mesh --export hull.inp"
expect_in "$ERR" "the hull is a superelement, whose interface nodes have no elements to write" \
  "mesh --export hull.inp"
expect_absent "$WORK/hull.inp" "no deck written"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
