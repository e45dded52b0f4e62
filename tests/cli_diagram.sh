#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond diagram on models and vehicle scenarios (docs/diagrams.md):
# a model without options keeps its flat block diagram; the kinds
# bond-graph and block-diagram; both systems of the 6x6 APC drawn with few
# nodes into DOT, SVG and PNG that are complete; a scenario accepted by
# diagram, causality and eig; strokes of the quarter car at the ends its
# causality puts them (reasoned out below); probe names and units with
# DOT's special characters escaped so that dot reads the file.
#
# usage: bash tests/cli_diagram.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_diagram
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

QC=$REPO_ROOT/examples/quarter_car.yaml
APC=$REPO_ROOT/examples/apc6x6.yaml

# nodes FILE.dot: the number of node statements (a line "  ID [" that is
# not an edge, nor the node/edge defaults).
nodes() {
  grep -E '^ +[^ ]+ \[' "$1" | grep -v -- ' -> ' | grep -cvE '^ +(node|edge) \['
}

# ---- A model: the default is the flat diagram, unchanged by the options
# that name it.
run diagram "$QC"
expect_status 0 "diagram of the quarter car to stdout"
cp "$OUT" "$WORK/default.dot"
run diagram "$QC" --kind flat -o "$WORK/flat.dot"
expect_status 0 "diagram --kind flat"
checks=$((checks + 1))
cmp -s "$WORK/default.dot" "$WORK/flat.dot" || fail "--kind flat differs from the default"

# ---- The quarter car's bond graph. Causality by hand: the gravity
# sources give their effort to the 1-junctions (stroke at the junction,
# the head); the road, a flow source, takes its effort from the tire's
# 0-junction (stroke at the tail, road). The inertias Ms, Mu take their
# effort (integral causality: stroke at the I, the head); the springs Ks,
# Kt give theirs (stroke at the junction, the tail).
run diagram "$QC" --kind bond-graph -o "$WORK/qc_bg.dot"
expect_status 0 "diagram --kind bond-graph"
BG=$WORK/qc_bg.dot
# stroke FROM TO head|tail: the edge "FROM" -> "TO" has the stroke there.
stroke() {
  local want
  if [ "$3" = head ]; then want='arrowhead="teelvee", arrowtail="none"'; else
    want='arrowhead="lvee", arrowtail="tee"'; fi
  checks=$((checks + 1))
  grep -F -- "\"$1\" -> \"$2\" [" "$BG" | grep -qF -- "$want" ||
    fail "bond $1 -> $2: the stroke is not at the $3"
}
stroke grav_body body head
stroke grav_wheel wheel head
stroke road tire tail
stroke body Ms head
stroke wheel Mu head
stroke defl Ks tail
stroke tire Kt tail
checks=$((checks + 1))
[ "$(grep -c -- ' -> ' "$BG")" -eq 12 ] || fail "the quarter car's 12 bonds are not 12 edges"
checks=$((checks + 1))
grep -q 'subgraph "cluster_' "$BG" && fail "the quarter car has no subsystem, but a cluster"

# ---- The 6x6 APC, both systems, both kinds: few nodes, one cluster per
# subsystem instance (hull, driver, engine, six suspensions, road, load),
# the hull's multibonds labelled with their dimension, DOT that dot reads,
# SVG and PNG complete.
for sys in rigid flexible; do
  for kind in bond-graph block-diagram; do
    what="apc6x6 $sys $kind"
    run diagram "$APC" --system "$sys" --kind "$kind" -o "$WORK/$sys-$kind.dot"
    expect_status 0 "$what: DOT"
    n=$(nodes "$WORK/$sys-$kind.dot")
    checks=$((checks + 1))
    [ "$n" -gt 20 ] && [ "$n" -lt 200 ] || fail "$what: $n nodes, expected 20 < n < 200"
    run diagram "$APC" --system "$sys" --kind "$kind" -o "$WORK/$sys-$kind.png"
    expect_status 0 "$what: PNG"
    checks=$((checks + 1))
    head -c 8 "$WORK/$sys-$kind.png" | od -An -tx1 | tr -d ' \n' | grep -qx 89504e470d0a1a0a ||
      fail "$what: not a PNG"
    run diagram "$APC" --system "$sys" --kind "$kind" -o "$WORK/$sys-$kind.svg"
    expect_status 0 "$what: SVG"
    checks=$((checks + 1))
    python3 -c 'import sys, xml.dom.minidom as m; m.parse(sys.argv[1])' "$WORK/$sys-$kind.svg" ||
      fail "$what: the SVG is not XML"
  done
  checks=$((checks + 1))
  [ "$(grep -c '^ *subgraph "cluster_' "$WORK/$sys-bond-graph.dot")" -eq 11 ] ||
    fail "apc6x6 $sys: not 11 clusters, one per instance"
  expect_in "$WORK/$sys-bond-graph.dot" 'label="b_attach [8]"' "apc6x6 $sys: the attachment multibond"
  expect_in "$WORK/$sys-bond-graph.dot" 'label="b_load [56]"' "apc6x6 $sys: the load multibond"
  expect_in "$WORK/$sys-block-diagram.dot" 'subgraph "cluster_top"' "apc6x6 $sys: the top level"
  expect_in "$WORK/$sys-block-diagram.dot" '[8]' "apc6x6 $sys: a vector signal of 8"
done
# The hull's fields carry its modal basis: fewer coordinates than the
# mesh's 1296 degrees of freedom under the default `modes: auto`.
basis=$(sed -n 's/.*label="b_mass \[\([0-9]*\)\]".*/\1/p' "$WORK/flexible-bond-graph.dot" | head -n 1)
checks=$((checks + 1))
[ -n "$basis" ] && [ "$basis" -gt 6 ] && [ "$basis" -lt 1296 ] ||
  fail "System 2: the hull's field multibond has the basis's size, not '$basis'"
expect_in "$WORK/flexible-bond-graph.dot" 'label="C : stiffness"' "System 2: the stiffness field"
checks=$((checks + 1))
grep -q 'b_mass \[' "$WORK/rigid-bond-graph.dot" && fail "System 1 has the finite-element hull"
# Every mode on request: the mesh's own size.
sed 's/^\( *modes:\) auto /\1 all /' "$APC" >"$WORK/apc_all.yaml"
run diagram "$WORK/apc_all.yaml" --system flexible --kind bond-graph -o "$WORK/all.dot"
expect_status 0 "diagram with every hull mode"
expect_in "$WORK/all.dot" 'label="b_mass [1296]"' "modes: all: one coordinate per degree of freedom"
# A scenario's default kind is the two-level block diagram, System 1.
run diagram "$APC"
expect_status 0 "diagram of a scenario to stdout"
checks=$((checks + 1))
cmp -s "$OUT" "$WORK/rigid-block-diagram.dot" || fail "a scenario's default is not the rigid block-diagram"

# ---- causality and eig read a scenario too.
run causality "$APC" --system flexible
expect_status 0 "causality of a scenario"
expect_in "$OUT" "hull.b_mass" "causality lists System 2's hull bond"
expect_in "$OUT" "dim $basis " "causality: the hull's multibond"
run eig "$APC"
expect_status 0 "eig of a scenario"
expect_in "$OUT" "apc6x6: 25 states" "eig: System 1 has 25 states"
run eig "$QC" --system rigid
expect_status 2 "eig of a model with --system"
expect_in "$ERR" "--system" "eig of a model with --system: names the option"
run diagram "$APC" --system stiff
expect_status 1 "diagram --system stiff"
run diagram "$QC" --kind picture
expect_status 1 "diagram --kind picture"
run diagram "$APC" --system flexible --kind bond-graph -o "$WORK/none/x.svg"
expect_status 5 "diagram into a missing directory"

# ---- Probe names (no quotes allowed: docs/model-format.md) and units
# with " \ { } reach the meters escaped.
python3 - "$QC" "$WORK/qc_hostile.yaml" <<'PYEOF'
import json, sys
src, dst = sys.argv[1:3]
text = open(src).read()
text = text.replace("{name: tire_force,", "{name: %s," % json.dumps('tf\\{x}'))
text = text.replace("integrate: true, unit: m}", "integrate: true, unit: %s}" % json.dumps('m"}\\'))
open(dst, "w").write(text)
PYEOF
run diagram "$WORK/qc_hostile.yaml" --kind block-diagram -o "$WORK/hostile.dot"
expect_status 0 "block diagram with a hostile probe name and unit"
expect_in "$WORK/hostile.dot" 'tf\\{x}' "the probe name, escaped"
expect_in "$WORK/hostile.dot" '[m\"}\\]' "the unit, escaped"
checks=$((checks + 1))
dot -Tsvg "$WORK/hostile.dot" >"$WORK/hostile.svg" 2>"$WORK/dot.err" && [ ! -s "$WORK/dot.err" ] ||
  fail "dot refuses the escaped diagram: $(head -c 300 "$WORK/dot.err")"
checks=$((checks + 1))
grep -qF 'tf\{x}' "$WORK/hostile.svg" && grep -qF 'm&quot;}\' "$WORK/hostile.svg" ||
  fail "dot does not show the probe name and unit as written"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
