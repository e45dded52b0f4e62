#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Bad inputs through the real flexbond command (docs/errors.md): a table of
# broken models, scenarios, the CSV files and meshes they reference, and
# bad command lines. For every case: the exact exit status (README, "Exit
# codes"), the message on stderr with the file:line(:col) of the problem
# and its key or phrase, no crash (status < 128, no sanitizer report), and
# no output left behind: an output that did not exist is not created, and
# one that held a previous result (previous.txt in the directory, or the
# file itself) holds it unchanged and nothing else.
#
# The fixtures are generated in the scratch directory from the examples
# (sed) or written here; line and column numbers are looked up in them
# (`at`), so that the cases do not depend on the examples' line numbers.
#
# usage: bash tests/cli_bad_inputs.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_bad_inputs
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

EX=$REPO_ROOT/examples
IN=$WORK/in
mkdir -p "$IN" "$WORK/out" || exit 2
# Fixtures are named relative to IN, so messages quote them as given.
cd "$IN" || exit 2

# line_of FILE LINE: the number of the first line of FILE that is LINE.
line_of() {
  awk -v text="$2" '$0 == text { print NR; found = 1; exit }
    END { if (!found) printf "NOT-FOUND(%s)", text }' "$1"
}

# derive NEW FROM SED-ARGS...: NEW is FROM edited by sed; it must differ
# (an example that changed would otherwise silently give a good file).
derive() {
  local new=$1 from=$2
  shift 2
  sed "$@" "$from" >"$new"
  checks=$((checks + 1))
  ! cmp -s "$new" "$from" || fail "fixture $new: sed $* changed nothing in $from"
}

# ---- Model fixtures: examples/quarter_car.yaml broken one way each.
cp "$EX/quarter_car.yaml" m_ok.yaml
derive m_unclosed.yaml m_ok.yaml -e 's/{name: Cs, type: R, r: cs}/{name: Cs, type: R, r: cs/'
derive m_tab.yaml m_ok.yaml -e 's/^  - {name: Cs, type: R, r: cs}/\t- {name: Cs, type: R, r: cs}/'
derive m_string.yaml m_ok.yaml -e 's/{name: Ms, type: I, m: ms}/{name: Ms, type: I, m: heavy}/'
derive m_list.yaml m_ok.yaml -e 's/{name: Cs, type: R, r: cs}/{name: Cs, type: R, r: [1, 2]}/'
derive m_unit.yaml m_ok.yaml -e 's/^  ms: 250 /  ms: 250 kg /'
derive m_missing.yaml m_ok.yaml -e 's/{name: Ms, type: I, m: ms}/{name: Ms, type: I}/'
derive m_unknown.yaml m_ok.yaml -e 's/^simulation:/simulaton:/'
derive m_nan.yaml m_ok.yaml -e 's/^  ks: 16000 /  ks: .nan /'
derive m_inf.yaml m_ok.yaml -e 's/{name: Kt, type: C, k: kt,/{name: Kt, type: C, k: -.inf,/'
derive m_negmass.yaml m_ok.yaml -e 's/{name: Mu, type: I, m: mu}/{name: Mu, type: I, m: -35}/'
derive m_zerok.yaml m_ok.yaml -e 's/{name: Ks, type: C, k: ks,/{name: Ks, type: C, k: 0,/'
derive m_dupname.yaml m_ok.yaml -e 's/{name: Mu, type: I, m: mu}/{name: Ms, type: I, m: mu}/'
derive m_dangling.yaml m_ok.yaml -e 's/^  - \[road, tire\]/  - [road, tyre]/'
# A source that turns infinite at 1.5 s, and NaN from the start (solver
# failures that name the element); a run too short for a step.
derive m_log.yaml m_ok.yaml -e 's/value: -ms \* g}/value: -ms * g * log(1.5 - t)}/'
derive m_nan0.yaml m_ok.yaml -e 's/value: -ms \* g}/value: -ms * g * log(t - 1)}/'
derive m_short.yaml m_ok.yaml -e 's/^  t_end: 5/  t_end: 1e-300/'
# Aliases that would expand a 4 KB file a billion times, and one without
# its anchor.
cp "$REPO_ROOT/tests/fuzz/regressions/model/yaml_alias_billion_laughs_oom.yaml" m_bomb.yaml
derive m_alias.yaml m_ok.yaml -e 's/{name: Ms, type: I, m: ms}/{name: Ms, type: I, m: *mass}/'
derive m_dupkey.yaml m_ok.yaml -e 's/^model: quarter_car$/model: quarter_car\nmodel: again/'
# The damper table of examples/quarter_car_table.yaml with a word in it.
cp "$EX/quarter_car_table.yaml" m_table.yaml
derive damper_fv.csv "$EX/damper_fv.csv" -e 's/^0.25, 110$/0.25, lots/'
# A subsystem's port on a 2-dimensional junction bonded to a scalar one.
cat >m_port.yaml <<'EOF'
model: port_dimension
subsystems:
  pair:
    ports:
      - {name: top, at: j}
    elements:
      - {name: j, type: 1, dim: 2}
      - {name: M, type: I, dim: 2, m: 1}
    bonds:
      - [j, M]
elements:
  - {name: F, type: Se, value: 1}
  - {name: body, type: 1}
  - {name: p, type: pair}
bonds:
  - [F, body]
  - [p.top, body]
EOF
: >m_empty.yaml
# Binary data behind a harmless first line: a PNG signature (0x89 can
# start no UTF-8 character), random bytes and NULs.
{
  printf 'model: m\n\x89PNG\r\n\x1a\n'
  head -c 256 /dev/urandom
  printf '\0\0\0\n'
} >m_binary.yaml
mkdir m_dir.yaml
cp m_ok.yaml m_noread.yaml
chmod 000 m_noread.yaml

# ---- Scenario fixtures: examples/apc6x6.yaml broken one way each.
cp "$EX/apc6x6.yaml" s_ok.yaml
cp "$EX/shock_front.csv" "$EX/shock_rear.csv" .
# road_with NEW TEXT: s_ok.yaml with its bump section replaced by TEXT.
road_with() {
  derive "$1" s_ok.yaml -e "/^  bump:/,/crossing of about three seconds/c\\  $2"
}
derive s_speed.yaml s_ok.yaml -e 's/^  speed_kmh: 10 /  speed_kmh: -10 /'
derive s_nan.yaml s_ok.yaml -e '0,/^      spring_k: 145300 /s//      spring_k: .nan /'
# A corner that does not exist, named by an output (the corners are the
# axles' L<name>, R<name>).
derive s_corner.yaml s_ok.yaml -e '0,/^    of: LF$/s//    of: LFF/'
derive s_nowheel.yaml s_ok.yaml -e '/^wheel:/,/^  tire_c:/d'
derive s_kmh.yaml s_ok.yaml -e 's/^  speed_kmh: 10 /  speed_kmh: "10 km\/h" /'
derive s_list.yaml s_ok.yaml -e '0,/^      spring_k: 145300 /s//      spring_k: [145300] /'
derive s_tab.yaml s_ok.yaml -e 's/^  mass: 4041.72 /\tmass: 4041.72 /'
derive s_unclosed.yaml s_ok.yaml -e 's/^\(      bulkheads: \[.*\), 1.90\]/\1, 1.90/'
derive s_gravty.yaml s_ok.yaml -e 's/^gravity:/gravty:/'
derive s_payload.yaml s_ok.yaml -e 's/payload: weight-only /payload: lumpd /'
derive s_initial.yaml s_ok.yaml -e 's/^  initial: zero /  initial: warm /'
derive s_dupkey.yaml s_ok.yaml -e 's/^gravity: 9.81 /gravity: 9.81\ngravity: 9.8 /'
derive s_hullmass.yaml s_ok.yaml -e 's/^  mass: 4041.72 /  mass: -4041.72 /'
derive s_tirek.yaml s_ok.yaml -e 's/^  tire_k: 500000 /  tire_k: 0 /'
derive s_inf.yaml s_ok.yaml -e 's/^  total_weight: 117720 /  total_weight: .inf /'
derive s_short.yaml s_ok.yaml -e 's/^  t_end: 15 /  t_end: 6 /'
# A damper section naming no law (the built-in laws are damper_c and damper_table) would
# leave the corner undamped; a top-level tire section no corner's tire uses would reach none;
# a value kept for the corners to inherit is checked where it is written.
# A bond output on no bond (a misspelt one, with a suggestion) or on a multibond without its
# component is refused at its key before any run.
derive s_bond_typo.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: effort, bond: susp_LF.b_tyre}/'
derive s_bond_multi.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: effort, bond: b_attach}/'
# Both when the file is loaded, before the vehicle is built (modes refuses them too); a
# multibond's component is in range, a scalar bond has none, another signal has none, and
# System 2's hull's bonds are multibonds.
derive s_bond_comp.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: effort, bond: b_attach, component: 9}/'
derive s_bond_scalar.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: effort, bond: susp_LF.b_tire, component: 1}/'
derive s_bond_fe.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: flow, bond: hull.b_mass}/'
derive s_comp_other.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: tire_force, of: LF, component: 2}/'
# A hull point's output: its point on System 2's plates (within 5 cm) and its axis, checked
# when the scenario is loaded, at their keys; a hull signal without a point has none.
derive s_point_off.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_displacement, at: [0.3, 0.2, -0.5], direction: z}/'
derive s_point_nodir.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_velocity, at: [2.10, 0.55, -0.8631]}/'
derive s_point_noat.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_acceleration, direction: y}/'
derive s_point_dir.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_velocity, at: [2.10, 0.55, -0.8631], direction: w}/'
derive s_rigid_at.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_roll, at: [1, 0, 0]}/'
# A hull stress output: its element in the mesh, its point on the plates, one of the two,
# its surface and component; System 1 (which the run builds first) has no elements.
stress_with() {
  derive "$1" s_ok.yaml -e "s/^outputs:/outputs:\n  - {signal: hull_stress, $2}/"
}
stress_with s_stress_elem.yaml 'element: 99999999, surface: top, stress: sx'
stress_with s_stress_off.yaml 'at: [0.3, 0.2, -0.5], surface: top, stress: sx'
stress_with s_stress_both.yaml 'element: 5, at: [2.10, 0.55, -0.8631], surface: top, stress: sx'
stress_with s_stress_none.yaml 'surface: top, stress: sx'
stress_with s_stress_surface.yaml 'element: 5, surface: side, stress: sx'
stress_with s_stress_comp.yaml 'element: 5, surface: top, stress: s1'
stress_with s_stress_dir.yaml 'element: 5, surface: top, stress: sx, direction: z'
stress_with s_stress_rigid.yaml 'element: 5, surface: bottom, stress: sxy'
derive s_point_surface.yaml s_ok.yaml -e 's/^outputs:/outputs:\n  - {signal: hull_displacement, at: [2.10, 0.55, -0.8631], direction: z, surface: top}/'
derive s_damper_empty.yaml s_ok.yaml -e '0,/^      damper_c: 25744 /s//      damper: {} /'
derive s_tire_unused.yaml s_ok.yaml -e 's/^  tire_c: 140000 /  tire_c: 140000\n  hunt_crossley: {deflection_ref: 0.03} /'
derive s_tire_ref.yaml s_ok.yaml -e 's/^  tire_c: 140000 /  tire_c: 140000\n  tire_contact: hunt_crossley\n  hunt_crossley: {deflection_ref: -1} /'
# Points off the floor or on one another; a hull mesh whose edges are no
# longer hull.edges (one bulkhead fewer moves its centre of mass), and more
# modes than the hull has: the late checks are located too.
derive s_driver.yaml s_ok.yaml -e '/^  - name: driver /,/^  - name: engine/s/^    x: 2.10 /    x: 20.1 /'
# Names become mesh node sets (MASS_<NAME>, at most 80 characters): one of 85 is refused where
# it is written, for either system.
# Legal but implausible values: a warning at the value (exit 0), an error under --strict.
derive s_tire1.yaml s_ok.yaml -e 's/^  tire_k: 500000 /  tire_k: 1 /'
derive s_heavy.yaml s_ok.yaml -e 's/^  total_weight: 117720 /  total_weight: 1e12 /'
derive s_bump100.yaml s_ok.yaml -e 's/^    height: 0.10 /    height: 100 /'
LONG=ddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddd
derive s_longname.yaml s_ok.yaml -e "s/^  - name: driver /  - name: $LONG /" -e "s/of: driver/of: $LONG/"
# Anti-roll bars: each end a corner of the scenario, on its side, the two ends apart.
derive s_arb_name.yaml s_ok.yaml -e '/^outputs:/i anti_roll_bars: [{name: front, left: LG, right: RF, stiffness: 50000}]'
derive s_arb_self.yaml s_ok.yaml -e '/^outputs:/i anti_roll_bars: [{name: front, left: LF, right: LF, stiffness: 50000}]'
derive s_arb_side.yaml s_ok.yaml -e '/^outputs:/i anti_roll_bars: [{name: front, left: LF, right: LM, stiffness: 50000}]'
derive s_arb_twice.yaml s_ok.yaml -e '/^outputs:/i anti_roll_bars:\n  - {name: front, left: LF, right: RF, stiffness: 50000}\n  - {name: second, left: LM, right: RF, stiffness: 50000}'
# Bogies: each end a corner of the scenario, both on one side, the pivot between; a bogie's
# wheel measures its tire only.
derive s_bogie_name.yaml s_ok.yaml -e '/^outputs:/i bogies: [{name: tandem, front: LMM, rear: LR, pivot_x: -0.3, beam_mass: 100, beam_inertia: 20, spring_k: 500000}]'
derive s_bogie_side.yaml s_ok.yaml -e '/^outputs:/i bogies: [{name: tandem, front: LM, rear: RR, pivot_x: -0.3, beam_mass: 100, beam_inertia: 20, spring_k: 500000}]'
derive s_bogie_pivot.yaml s_ok.yaml -e '/^outputs:/i bogies: [{name: tandem, front: LM, rear: LR, pivot_x: 3, beam_mass: 100, beam_inertia: 20, spring_k: 500000}]'
derive s_bogie_stops.yaml s_ok.yaml -e '/^outputs:/i bogies: [{name: tandem, front: LM, rear: LR, pivot_x: -0.3, beam_mass: 100, beam_inertia: 20, spring_k: 500000}]' \
  -e 's/^      spring_k: 345550 .*/      spring_k: 345550\n      bump_stop: {gap: 0.1, rate: 1e6}/'
derive s_bogie_signal.yaml s_ok.yaml -e '/^outputs:/i bogies: [{name: tandem, front: LM, rear: LR, pivot_x: -0.3, beam_mass: 100, beam_inertia: 20, spring_k: 500000}]'
derive s_samepoint.yaml s_ok.yaml -e '/^    - name: M /,/^    - name: R /s/^      x: 0.40 /      x: 1.90 /'
derive s_bulkheads.yaml s_ok.yaml -e 's/^\(      bulkheads: \)\[.*\]/\1[1.90, -1.00]/'
derive s_modes.yaml s_ok.yaml -e 's/^    modes: auto /    modes: 99999 /'
derive s_modes0.yaml s_ok.yaml -e 's/^    modes: auto /    modes: 0 /'
derive s_cutoff.yaml s_ok.yaml -e 's/^\(    modes: auto .*\)$/\1\n    cutoff_hz: 2/'
road_with s_tworoads.yaml 'iso8608: {class: C, seed: 1}\n  bump: {height: 0.1, length: 3.7, angle_deg: 45, first_contact: 5}'
road_with s_isoclass.yaml 'iso8608: {class: Z, seed: 1}'
road_with s_profile.yaml 'profile: {file: one_row.csv}'
printf 's,z\n0,0\n' >one_row.csv
# Damper tables: missing, a word among the numbers, velocities going back.
derive s_table_missing.yaml s_ok.yaml \
  -e '0,/damper_c: 25744 /s//damper_table: {file: no_such_table.csv, force: F} /'
derive s_table_word.yaml s_ok.yaml -e '0,/damper_c: 25744 /s//damper_table: {file: word.csv, force: F} /'
derive s_table_order.yaml s_ok.yaml -e '0,/damper_c: 25744 /s//damper_table: {file: order.csv, force: F} /'
# Springs and stops: a spring table that falls, a stop's negative gap, a stop force asked of
# a corner without stops, an implausible gap (a warning, an error under --strict).
derive s_spring_fall.yaml s_ok.yaml \
  -e '0,/^      damper_c: 25744 /s//      spring_table: {points: [[0, 0], [0.1, 9000], [0.2, 8000]]}\n      damper_c: 25744 /'
derive s_stop_gap.yaml s_ok.yaml \
  -e '0,/^      damper_c: 25744 /s//      bump_stop: {gap: -0.1, rate: 1e6}\n      damper_c: 25744 /'
derive s_stop_none.yaml s_ok.yaml -e '0,/signal: tire_force/s//signal: stop_force/'
derive s_stop_far.yaml s_ok.yaml \
  -e '0,/^      damper_c: 25744 /s//      bump_stop: {gap: 2, rate: 1e6}\n      damper_c: 25744 /'
printf 'v,F\n-1,-100\n0,0\n0.5,abc\n1,100\n' >word.csv
# Data files that are not plain text or decimals (core/textfile.c): a NUL
# in a damper table and in a road profile (it used to cut the line there),
# a repeated column, a hexadecimal height.
derive m_table_nul.yaml m_table.yaml -e 's/file: damper_fv.csv/file: nul_fv.csv/'
printf 'v,F\n-1.0,-980\n-0.5,-580\n0,0\0\n0.5,300\n1.0,500\n' >nul_fv.csv
derive s_table_dup.yaml s_ok.yaml -e '0,/damper_c: 25744 /s//damper_table: {file: dup.csv, force: F} /'
printf 'v,F,F\n-1,-100,0\n0,0,0\n1,100,0\n' >dup.csv
road_with s_profile_nul.yaml 'profile: {file: nul_road.csv}'
printf 's,z\n-50,0\n0,0\n\0001,0.05\n2,0\n200,0\n' >nul_road.csv
road_with s_profile_hex.yaml 'profile: {file: hex_road.csv}'
printf 's,z\n-50,0\n0,0\n1,0x5\n2,0\n200,0\n' >hex_road.csv
printf 'v,F\n-1,-100\n0,0\n1,100\n0.5,50\n' >order.csv
: >s_empty.yaml
# An ELF header, random bytes and NULs.
{
  printf '\x7fELF\x02\x01\x01\0'
  head -c 256 /dev/urandom
} >s_binary.yaml

# ---- Mesh fixtures: the example's System 2 hull exported as a deck, read
# back through hull.mesh.deck, with one bad thing appended each.
run mesh s_ok.yaml --export hull.inp
expect_status 0 "fixture: mesh --export hull.inp"
derive s_deck.yaml s_ok.yaml -e '/^    density: 1 /d' -e '/^    generator:/,/nose_rung_divisions/c\    deck: hull.inp'
# deck NAME TEXT: NAME.inp is hull.inp plus TEXT; NAME.yaml reads it.
deck() {
  {
    cat hull.inp
    printf '%b\n' "$2"
  } >"$1.inp"
  derive "$1.yaml" s_deck.yaml -e "s/deck: hull.inp/deck: $1.inp/"
}
# Extra nodes away from the hull: a unit square with one corner lifted
# 0.3 m, and three points on a line.
NODES='*NODE\n9001, 0, 0, 5\n9002, 1, 0, 5\n9003, 1, 1, 5\n9004, 0, 1, 5.3\n9005, 2, 0, 5'
deck d_nset "*NSET, NSET=EXTRA\n99999"
deck d_warped "$NODES\n*ELEMENT, TYPE=S4\n9001, 9001, 9002, 9003, 9004"
deck d_zeroarea "$NODES\n*ELEMENT, TYPE=S3\n9001, 9001, 9002, 9005"
deck d_nonode "$NODES\n*ELEMENT, TYPE=S3\n9001, 9001, 9002, 99999"
# A deck's added masses: a negative *MASS, a MASS element on two nodes,
# a *NONSTRUCTURAL MASS over a set the deck does not have.
deck d_massneg "*ELEMENT, TYPE=MASS, ELSET=PM\n9101, 1\n*MASS, ELSET=PM\n-5"
deck d_mass2 "*ELEMENT, TYPE=MASS, ELSET=PM\n9101, 1, 2\n*MASS, ELSET=PM\n5"
deck d_nsmset "*NONSTRUCTURAL MASS, ELSET=NOPE, UNITS=MASS PER AREA\n10"
derive d_empty.yaml s_deck.yaml -e 's/deck: hull.inp/deck: d_empty.inp/'
: >d_empty.inp
derive d_binary.yaml s_deck.yaml -e 's/deck: hull.inp/deck: d_binary.inp/'
{
  printf '\x7fELF\x02\x01\x01\0'
  head -c 2048 /dev/urandom
} >d_binary.inp
derive d_missing.yaml s_deck.yaml -e 's/deck: hull.inp/deck: no_such_deck.inp/'
# A deck whose left-front suspension node set has another name.
sed 's/NSET=SUSP_LF\b/NSET=SUSP_XX/' hull.inp >d_noset.inp
derive d_noset.yaml s_deck.yaml -e 's/deck: hull.inp/deck: d_noset.inp/'
# A hull mass the deck has no MASS_<NAME> set for (hull.inp has none).
derive d_nomass.yaml s_deck.yaml \
  -e 's/^  material:/  masses: [{name: ballast, mass: 300, x: -2.00, y: 0.55}]\n  material:/'

# deck_at NAME: "NAME.yaml:LINE:COL: hull.mesh.deck:", where NAME.yaml names its deck.
deck_at() {
  printf '%s hull.mesh.deck:' "$(at "$1.yaml" '    deck: ' "$(sed -n 's/^    deck: //p' "$1.yaml")")"
}

# ---- The good fixtures pass, so each bad one fails for its own reason.
run causality m_ok.yaml
expect_status 0 "fixture m_ok.yaml"
run mesh s_ok.yaml
expect_status 0 "fixture s_ok.yaml"
run mesh s_deck.yaml
expect_status 0 "fixture s_deck.yaml"
expect_in "$OUT" "216 nodes, 28 S3 + 212 S4" "fixture s_deck.yaml reads the whole deck"

# ---- The cases: STATUS | ARGUMENTS | TEXT | TEXT ... (each TEXT must be
# on stderr). In the arguments @OUT is an output directory, @FILE an output
# file (each run twice: absent before, and holding a previous result), and
# @EXISTING a regular file that is there before (run once).
CASES=(
  # Model YAML.
  "2|sim m_unclosed.yaml -o @OUT|flexbond: $(at m_unclosed.yaml 'name: Kt' '{') YAML: |unclosed '['"
  "2|sim m_tab.yaml -o @OUT|flexbond: $(at m_tab.yaml 'name: Cs')1: YAML: tab character|indent with spaces"
  "2|sim m_string.yaml -o @OUT|$(at m_string.yaml heavy heavy) elements[0].m: expression 'heavy'|expected a number"
  "2|causality m_list.yaml|$(at m_list.yaml 'r: [1' '[1') elements[3].r: expected a number or expression, got a list"
  "2|sim m_unit.yaml -o @OUT|$(at m_unit.yaml '250 kg' 250) parameters.ms: expected a number, got '250 kg'|write the number alone"
  "2|eig m_missing.yaml|$(at m_missing.yaml 'name: Ms' '{') elements[0]: missing required key 'm'"
  "2|sim m_unknown.yaml -o @OUT|$(at m_unknown.yaml simulaton simulaton) simulaton: unknown key|did you mean 'simulation'?"
  "2|sim m_nan.yaml -o @OUT|$(at m_nan.yaml .nan .nan) parameters.ks: must be finite (got .nan)"
  "2|diagram m_inf.yaml -o @FILE.dot|$(at m_inf.yaml -.inf -.inf) elements[4].k: must be finite (got -.inf)"
  "2|sim m_negmass.yaml -o @OUT|$(at m_negmass.yaml -35 -35) elements[1].m: must be > 0 (got -35)"
  "2|sim m_zerok.yaml -o @OUT|$(at m_zerok.yaml 'k: 0,' '0,') elements[2].k: must be > 0 (got 0)"
  "2|sim m_dupname.yaml -o @OUT|$(at m_dupname.yaml 'm: mu' Ms) elements[1].name: duplicate element name 'Ms'|first defined at line $(line_of m_ok.yaml '  - {name: Ms, type: I, m: ms}'))"
  "2|sim m_dangling.yaml -o @OUT|$(at m_dangling.yaml tyre tyre) bonds[9][1]: unknown element 'tyre'|did you mean 'tire'?"
  "2|causality m_dupkey.yaml|$(at m_dupkey.yaml again model) YAML: duplicate key 'model'"
  "2|sim s_ok.yaml -o @OUT|s_ok.yaml:$(line_of s_ok.yaml 'scenario: apc6x6'):1: scenario: this is a scenario file (docs/scenario-format.md), not a model file|flexbond run, modes, mesh, export, freq, model and sweep read it"
  "2|export m_ok.yaml -o @OUT|m_ok.yaml:$(line_of m_ok.yaml 'model: quarter_car'):1: model: this is a model file (docs/model-format.md), not a scenario file|flexbond sim, diagram, causality and eig read it"
  "2|sweep m_ok.yaml --set ks=1:2:2 -o @OUT|m_ok.yaml:$(line_of m_ok.yaml 'model: quarter_car'):1: model: this is a model file"
  "2|modes m_ok.yaml|m_ok.yaml:$(line_of m_ok.yaml 'model: quarter_car'):1: model: this is a model file"
  "2|sim m_port.yaml -o @OUT|$(at m_port.yaml 'p.top' '[') bonds[1]: bond 'p.top->body': dimension mismatch: 'p.top' has dimension 2, 'body' has dimension 1"
  "2|sim m_table.yaml -o @OUT|./damper_fv.csv:$(line_of damper_fv.csv '0.25, lots'): column 'F': not a number (read: 'lots')|$(at m_table.yaml 'file: damper_fv.csv' 'damper_fv') elements[3].table.file:"
  "4|sim m_log.yaml -o @OUT|flexbond: at t = 1.5 s: CVODE step size |the derivative of state Ms.p is inf; the non-finite value starts at Se 'grav_body' (source): e:grav_body->body = inf; hint: a law or time function evaluated outside its domain"
  "4|sim m_nan0.yaml -o @OUT|flexbond: at t = 0 s: the derivative of state Ms.p is nan at the initial state; the non-finite value starts at Se 'grav_body' (source): e:grav_body->body = nan"
  "2|sim m_short.yaml -o @OUT|$(at m_short.yaml 1e-300 1e-300) simulation.t_end: the run from t_start = 0 s to t_end = 1e-300 s is too short for the solver to take a step|at least 1.49e-154 s"
  "1|sim m_ok.yaml -o @OUT --t-end 1e-300|flexbond sim: option '--t-end': the run from t_start = 0 s to t_end = 1e-300 s is too short"
  "2|sim m_bomb.yaml -o @OUT|flexbond: $(at m_bomb.yaml '  a4: &a4')41: YAML: aliases would expand the document to more than 100000 nodes|*a3 here copies 11111"
  "2|causality m_alias.yaml|flexbond: $(at m_alias.yaml '*mass' mass) YAML: invalid alias '*mass'|no anchor of that name in the file"
  "2|sim m_empty.yaml -o @OUT|flexbond: m_empty.yaml:1:1: the file is empty"
  "2|sim m_binary.yaml -o @OUT|flexbond: m_binary.yaml:2:1: binary data (byte 0x89): not a YAML text file"
  "5|sim m_dir.yaml -o @OUT|flexbond: m_dir.yaml: cannot read|directory"
  "5|sim m_absent.yaml -o @OUT|flexbond: m_absent.yaml: cannot open|No such file"
  "5|sim m_noread.yaml -o @OUT|flexbond: m_noread.yaml: cannot open|Permission denied"

  # Scenario YAML.
  "2|run s_speed.yaml -o @OUT|flexbond: $(at s_speed.yaml 'speed_kmh: -10' -10) road.speed_kmh: must be > 0 km/h (got -10)"
  "2|run s_nan.yaml -o @OUT|$(at s_nan.yaml .nan .nan) suspensions.axles[0].spring_k: must be finite (got .nan)"
  "2|run s_corner.yaml -o @OUT|$(at s_corner.yaml 'of: LFF' LFF) outputs[0].of: no corner named 'LFF'|did you mean 'LF'?"
  "2|modes s_nowheel.yaml|$(at s_nowheel.yaml '    - name: F ' name) suspensions.axles[0]: missing required key 'suspensions.axles[0].wheel.mass' (nor is there a wheel.mass to take it from)"
  "2|run s_kmh.yaml -o @OUT|$(at s_kmh.yaml 'speed_kmh: "' '10 km') road.speed_kmh: expected a number, got '10 km/h'|write the number alone"
  "2|export s_list.yaml -o @OUT|$(at s_list.yaml '[145300]' '[') suspensions.axles[0].spring_k: expected a number or expression, got a list"
  "2|run s_tab.yaml -o @OUT|$(at s_tab.yaml 4041.72)1: YAML: tab character"
  "2|run s_unclosed.yaml -o @OUT|$(at s_unclosed.yaml side_rows side_rows) YAML: |unclosed '['"
  "2|run s_gravty.yaml -o @OUT|$(at s_gravty.yaml gravty gravty) gravty: unknown key 'gravty'|did you mean 'gravity'?"
  "2|run s_payload.yaml -o @OUT|$(at s_payload.yaml lumpd lumpd) load.payload: unknown value 'lumpd'|did you mean 'lumped'?"
  "2|export s_initial.yaml -o @OUT|$(at s_initial.yaml warm warm) simulation.initial: unknown value 'warm'"
  "2|run s_dupkey.yaml -o @OUT|$(at s_dupkey.yaml 'gravity: 9.8 ' gravity) YAML: duplicate key 'gravity'"
  "2|export s_hullmass.yaml -o @OUT|$(at s_hullmass.yaml -4041.72 -4041.72) hull.mass: must be > 0 kg (got -4041.72)"
  "2|modes s_tirek.yaml|$(at s_tirek.yaml 'tire_k: 0' 0) wheel.tire_k: must be > 0 N/m (got 0)"
  "2|sweep s_inf.yaml --set speed_kmh=5,10 -o @OUT|$(at s_inf.yaml .inf .inf) load.total_weight: must be finite (got .inf)"
  "2|run s_bond_typo.yaml -o @OUT|$(at s_bond_typo.yaml 'bond: susp_LF' susp_LF) outputs[0].bond: no bond named 'susp_LF.b_tyre' in the assembled graph (did you mean 'susp_LF.b_tire'?)"
  "2|modes s_bond_multi.yaml|$(at s_bond_multi.yaml 'bond: b_attach' b_attach) outputs[0].bond: bond 'b_attach' is a multibond of 8 components: an output records one of them, chosen with component (1 to 8)"
  "2|modes s_bond_comp.yaml|$(at s_bond_comp.yaml 'component: 9' 9) outputs[0].component: bond 'b_attach' has components 1 to 8 (got 9)"
  "2|modes s_bond_scalar.yaml|$(at s_bond_scalar.yaml 'component: 1' 1) outputs[0].component: bond 'susp_LF.b_tire' is a scalar bond: it has no component"
  "2|modes s_bond_fe.yaml|$(at s_bond_fe.yaml 'bond: hull.b_mass' hull.b_mass) outputs[0].bond: bond 'hull.b_mass' is a multibond of System 2's hull: an output records one of its components, chosen with component"
  "2|modes s_comp_other.yaml|$(at s_comp_other.yaml 'component: 2' 'component: 2') outputs[0].component: only a bond signal has a component"
  "2|run s_point_off.yaml -o @OUT|$(at s_point_off.yaml 'at: [0.3' '[0.3') outputs[0].at: the point is 0.363 m from the hull's nearest element (at most 0.05 m: a point of the hull's plates)"
  "2|modes s_point_nodir.yaml|$(at s_point_nodir.yaml 'signal: hull_velocity' '{') outputs[0]: missing required key 'direction': the axis, x, y or z, a hull_velocity signal measures"
  "2|run s_point_noat.yaml -o @OUT|$(at s_point_noat.yaml 'signal: hull_acceleration' '{') outputs[0]: missing required key 'at': the hull point \`[x, y, z]\` (m) a hull_acceleration signal measures"
  "2|run s_point_dir.yaml -o @OUT|$(at s_point_dir.yaml 'direction: w' w) outputs[0].direction: unknown value 'w'; expected x | y | z"
  "2|run s_rigid_at.yaml -o @OUT|$(at s_rigid_at.yaml 'at: [1' 'at: [1') outputs[0].at: only a hull point's signal has at"
  "2|run s_stress_elem.yaml -o @OUT|$(at s_stress_elem.yaml 'element: 99999999' 99999999) outputs[0].element: the hull's mesh has no element 99999999 (its 240 elements' ids are 1 to 240)"
  "2|run s_stress_off.yaml -o @OUT|$(at s_stress_off.yaml 'at: [0.3' '[0.3') outputs[0].at: the point is 0.363 m from the hull's nearest element (at most 0.05 m: a point of the hull's plates)"
  "2|run s_stress_both.yaml -o @OUT|$(at s_stress_both.yaml 'at: [2.10' 'at: [2.10') outputs[0].at: a hull_stress signal reads one element: give element or at, not both"
  "2|run s_stress_none.yaml -o @OUT|$(at s_stress_none.yaml 'signal: hull_stress' '{') outputs[0]: missing required key 'element' or 'at': the shell element (by its id) or the hull point \`[x, y, z]\` (m) whose element a hull_stress signal reads"
  "2|run s_stress_surface.yaml -o @OUT|$(at s_stress_surface.yaml 'surface: side' side) outputs[0].surface: unknown value 'side'; expected top | bottom"
  "2|run s_stress_comp.yaml -o @OUT|$(at s_stress_comp.yaml 'stress: s1' s1) outputs[0].stress: unknown value 's1' (did you mean 'sx'?); expected sx | sy | sxy"
  "2|run s_stress_dir.yaml -o @OUT|$(at s_stress_dir.yaml 'direction: z' direction) outputs[0].direction: only a hull point's signal has direction"
  "2|run s_stress_rigid.yaml --system rigid -o @OUT|$(at s_stress_rigid.yaml 'signal: hull_stress' hull_stress) outputs[0].signal: System 1's hull is a rigid body: it has no shell elements, whose stresses a hull_stress signal reads: only System 2 gives it"
  "2|run s_point_surface.yaml -o @OUT|$(at s_point_surface.yaml 'surface: top' surface) outputs[0].surface: only a hull stress signal has surface"
  "2|run s_damper_empty.yaml -o @OUT|$(at s_damper_empty.yaml 'damper: {}' '{}') suspensions.axles[0].damper: no damper law is written as a section here"
  "2|run s_tire_unused.yaml -o @OUT|$(at s_tire_unused.yaml 'hunt_crossley:' hunt_crossley) wheel.hunt_crossley: no corner's tire is hunt_crossley"
  "2|run s_tire_ref.yaml -o @OUT|$(at s_tire_ref.yaml 'deflection_ref: -1' -1) wheel.hunt_crossley.deflection_ref: must be > 0 m (got -1)"
  "2|run s_short.yaml -o @OUT|$(at s_short.yaml '  t_end: 6 ' 6) simulation.t_end: the run ends at 6 s, before the last wheel (RR) leaves the road's bump at 8.132 s"
  "2|run s_tworoads.yaml -o @OUT|$(at s_tworoads.yaml 'iso8608: {' iso8608) road.iso8608: give either 'bump' or 'iso8608', not both"
  "2|run s_isoclass.yaml -o @OUT|$(at s_isoclass.yaml 'class: Z' Z) road.iso8608.class: unknown value 'Z'; expected A | B | C | D | E | F | G | H"
  "2|run s_profile.yaml -o @OUT|$(at s_profile.yaml one_row.csv one_row) road.profile.file: ./one_row.csv:2: 1 data row, need at least 2"
  "5|run s_table_missing.yaml -o @OUT|$(at s_table_missing.yaml no_such_table no_such) suspensions.axles[0].damper_table.file: ./no_such_table.csv: cannot open|No such file"
  "2|run s_table_word.yaml -o @OUT|$(at s_table_word.yaml word.csv word) suspensions.axles[0].damper_table.file: ./word.csv:4: column 'F': not a number (read: 'abc')"
  "2|run s_spring_fall.yaml -o @OUT|$(at s_spring_fall.yaml 'spring_table:' '{') suspensions.axles[0].spring_table: table law decreases: at point 3 phi(0.2) = 8000 is below point 2's 9000"
  "2|run s_stop_gap.yaml -o @OUT|$(at s_stop_gap.yaml 'gap: -0.1' -0.1) suspensions.axles[0].bump_stop.gap: must be >= 0 m (got -0.1)"
  "2|run s_stop_none.yaml -o @OUT|$(at s_stop_none.yaml 'of: LF' LF) outputs[0].of: corner 'LF' has no stop (bump_stop or rebound_stop) for stop_force to measure"
  "2|run s_stop_far.yaml --system rigid --strict -o @OUT|$(at s_stop_far.yaml 'gap: 2' 2) suspensions.axles[0].bump_stop.gap: 2 m is implausible: a suspension's travel to its stops is 1 mm to 0.5 m"
  "2|export s_table_order.yaml -o @OUT|$(at s_table_order.yaml order.csv order) suspensions.axles[0].damper_table.file: ./order.csv:5: column 'v': 0.5 does not exceed the previous row's 1|strictly increasing"
  "2|run s_tire1.yaml --system rigid --strict -o @OUT|$(at s_tire1.yaml 'tire_k: 1 ' 1) wheel.tire_k: 1 N/m is implausible: a tire's radial stiffness is 1e4 to 1e8 N/m|--strict refuses implausible values: 2 in this scenario"
  "2|export s_heavy.yaml --system rigid --strict -o @OUT|$(at s_heavy.yaml 'total_weight: 1e12' 1e12) load.total_weight: 1e+12 N is implausible"
  "2|freq s_bump100.yaml --system rigid --strict -o @OUT|$(at s_bump100.yaml 'height: 100' 100) road.bump.height: 100 m is implausible"
  "2|run s_longname.yaml --system rigid -o @OUT|$(at s_longname.yaml "name: $LONG" "$LONG") mounts[0].name: a name of 85 characters, more than 64"
  "2|run s_driver.yaml --system rigid -o @OUT|$(at s_driver.yaml 'x: 20.1' 20.1) mounts[0].x: must lie on the hull's floor, between the rear edge's x = -2.657984123 and the front edge's x = 2.478133119 m (got 20.1)"
  "2|run s_arb_name.yaml --system rigid -o @OUT|$(at s_arb_name.yaml 'left: LG' LG) anti_roll_bars[0].left: no corner named 'LG' (did you mean 'LF'?); the corners are LF, RF, LM, RM, LR, RR"
  "2|run s_arb_self.yaml --system rigid -o @OUT|$(at s_arb_self.yaml 'right: LF' 'LF, stiffness') anti_roll_bars[0].right: the bar's two ends are one corner, LF"
  "2|freq s_arb_side.yaml --system rigid -o @OUT|$(at s_arb_side.yaml 'right: LM' LM) anti_roll_bars[0].right: corner LM is on the left (y = 1.05 m): a bar's right corner has y < 0"
  "2|run s_arb_twice.yaml --system rigid -o @OUT|$(at s_arb_twice.yaml 'name: second' RF) anti_roll_bars[1].right: corner RF is under bar front already (a corner carries one bar)"
  "2|run s_bogie_name.yaml --system rigid -o @OUT|$(at s_bogie_name.yaml 'front: LMM' LMM) bogies[0].front: no corner named 'LMM' (did you mean 'LM'?)"
  "2|modes s_bogie_side.yaml|$(at s_bogie_side.yaml 'rear: RR' RR) bogies[0].rear: corner RR is at y = -1.05 m, the front corner LM at y = 1.05 m: a bogie's wheels are on one line along the vehicle"
  "2|run s_bogie_pivot.yaml --system rigid -o @OUT|$(at s_bogie_pivot.yaml 'pivot_x: 3' 3) bogies[0].pivot_x: must lie between the rear corner LR's x = -1 m and the front corner LM's x = 0.4 m (got 3)"
  "2|run s_bogie_stops.yaml --system rigid -o @OUT|$(at s_bogie_stops.yaml 'front: LM' LM) bogies[0].front: corner LM has bump or rebound stops: a bogie's wheel rides on the beam, with no suspension travel of its own for them"
  "2|run s_bogie_signal.yaml --system rigid -o @OUT|$(at s_bogie_signal.yaml 'signal: shock_power' shock_power) outputs[4].signal: corner LM is a bogie's wheel, which has no shock_power"
  "2|export s_samepoint.yaml --system rigid -o @OUT|$(at s_samepoint.yaml '    - name: M ' name) suspensions.axles[1]: at (1.9, 1.05) m, where corner LF already is (two corners at one point)"
  "2|mesh s_bulkheads.yaml --export @FILE.inp|$(at s_bulkheads.yaml 'front_x: 2.478' 2.478) hull.edges.front_x: the scenario puts FRONT_EDGE's left end at (2.47813, 1.05) m, the mesh's node 76 at (2.33187, 1.05) m"
  "2|run s_modes.yaml --system flexible -o @OUT|$(at s_modes.yaml 'modes: 99999' 99999) hull.fe.modes: 99999 modes, more than the hull's 1296 degrees of freedom"
  "2|run s_modes0.yaml --system flexible -o @OUT|$(at s_modes0.yaml 'modes: 0' 0) hull.fe.modes: "
  "2|run s_cutoff.yaml --system flexible -o @OUT|$(at s_cutoff.yaml 'cutoff_hz: 2' 2) hull.fe.cutoff_hz: a cut-off of 2 Hz is below the hull's first elastic mode, at 10.3 Hz"
  "2|sim m_table_nul.yaml -o @OUT|$(at m_table_nul.yaml 'file: nul_fv.csv' 'nul_fv') elements[3].table.file: ./nul_fv.csv:4: binary data (byte 0x00 in column 4): not a CSV text file (expected UTF-8 text)"
  "2|run s_table_dup.yaml -o @OUT|$(at s_table_dup.yaml dup.csv dup) suspensions.axles[0].damper_table.file: ./dup.csv:1: column 'F' appears twice"
  "2|modes s_profile_nul.yaml|$(at s_profile_nul.yaml nul_road.csv nul_road) road.profile.file: ./nul_road.csv:4: binary data (byte 0x00 in column 1): not a CSV text file"
  "2|run s_profile_hex.yaml -o @OUT|$(at s_profile_hex.yaml hex_road.csv hex_road) road.profile.file: ./hex_road.csv:4: column 'z': not a decimal number (read: '0x5')"
  "2|run s_empty.yaml -o @OUT|flexbond: s_empty.yaml:1:1: the file is empty"
  "2|modes s_binary.yaml|flexbond: s_binary.yaml:1:1: binary data (byte 0x7f)"

  # Meshes (a deck read through hull.mesh.deck): at the scenario's key, then the deck's line.
  "2|mesh d_nset.yaml --export @FILE.inp|flexbond: $(deck_at d_nset) ./d_nset.inp:$(line_of d_nset.inp 99999): node set 'EXTRA' names node 99999, which is not defined"
  "2|run d_warped.yaml --system flexible -o @OUT|flexbond: $(deck_at d_warped) ./d_warped.inp:$(line_of d_warped.inp '9001, 9001, 9002, 9003, 9004'): element 9001 (S4) is warped: node 9004 is 300 mm off the plane"
  # The deck is read at load: a sweep refuses the scenario before any case.
  "2|sweep d_warped.yaml --system flexible --set speed_kmh=5,10 -o @OUT|flexbond: $(deck_at d_warped) ./d_warped.inp:$(line_of d_warped.inp '9001, 9001, 9002, 9003, 9004'): element 9001 (S4) is warped"
  # An input every case shares that only the cases find (the hull's degrees
  # of freedom): each case fails on it, and the study with the first's message.
  "2|sweep s_modes.yaml --system flexible --set speed_kmh=5,10 -o @OUT|flexbond: every case failed on its input; the first: $(at s_modes.yaml 'modes: 99999' 99999) hull.fe.modes: 99999 modes"
  "2|modes d_zeroarea.yaml --system flexible -o @OUT|flexbond: $(deck_at d_zeroarea) ./d_zeroarea.inp:$(line_of d_zeroarea.inp '9001, 9001, 9002, 9005'): element 9001 (S3) is degenerate: area 0 m^2"
  "2|export d_nonode.yaml -o @OUT|flexbond: $(deck_at d_nonode) ./d_nonode.inp:$(line_of d_nonode.inp '9001, 9001, 9002, 99999'): element 9001 refers to node 99999, which is not defined"
  "2|mesh d_massneg.yaml|flexbond: $(deck_at d_massneg) ./d_massneg.inp:$(line_of d_massneg.inp '-5'): *MASS: mass -5 is negative"
  "2|mesh d_mass2.yaml|flexbond: $(deck_at d_mass2) ./d_mass2.inp:$(line_of d_mass2.inp '9101, 1, 2'): MASS element 9101 has 2 nodes, not 1"
  "2|mesh d_nsmset.yaml|flexbond: $(deck_at d_nsmset) ./d_nsmset.inp:$(line_of d_nsmset.inp '*NONSTRUCTURAL MASS, ELSET=NOPE, UNITS=MASS PER AREA'): *NONSTRUCTURAL MASS names element set 'NOPE', which is not defined"
  "2|mesh d_empty.yaml --export @FILE.vtu|flexbond: $(deck_at d_empty) ./d_empty.inp:1: empty file"
  "2|mesh d_binary.yaml|flexbond: $(deck_at d_binary) ./d_binary.inp:1: binary data (byte 0x7f in column 1): not an Abaqus input deck"
  "5|mesh d_missing.yaml --export @FILE.inp|flexbond: $(deck_at d_missing) ./no_such_deck.inp: cannot open|No such file"
  "2|run d_noset.yaml --system flexible -o @OUT|flexbond: $(deck_at d_noset) ./d_noset.inp: the mesh has no node set SUSP_LF (the vehicle needs LOAD,"
  "2|run d_nomass.yaml --system flexible -o @OUT|flexbond: $(at d_nomass.yaml 'masses: [' '{') hull.masses[0]: ./hull.inp: the mesh has no node set MASS_BALLAST (the vehicle needs LOAD,"

  # Command lines.
  "1|run s_ok.yaml -o @OUT --frobnicate|flexbond run: unknown option '--frobnicate'|flexbond run --help"
  "1|run s_ok.yaml --system|flexbond run: option '--system' needs a value"
  "1|sim m_ok.yaml -o|flexbond sim: option '-o' needs a value"
  "1|run s_ok.yaml -o @OUT --system banana|option '--system' must be one of rigid, flexible, both (got 'banana')"
  "1|modes s_ok.yaml --system banana|option '--system' must be one of rigid, flexible (got 'banana')"
  "1|sweep s_ok.yaml --set speed_kmh=5,10 -o @OUT -j -2|option '-j' needs an integer in 1..1024 (got '-2')"
  "1|sweep s_ok.yaml --set speed_kmh -o @OUT|--set needs KEY=SPEC (got 'speed_kmh')"
  "1|sweep s_ok.yaml --set speed_kmh=1:0:5 -o @OUT|--set speed_kmh=1:0:5: step 0"
  "1|sweep s_ok.yaml --set no_such_key=5 -o @OUT|no key 'no_such_key' in the scenario"
  "1|sim m_ok.yaml -o @OUT --t-end -1|option '--t-end' needs a finite number > 0"
  "1|sim m_ok.yaml -o @OUT --rtol 5|flexbond sim: option '--rtol': must be in (0, 1), got 5"
  "1|sim m_ok.yaml -o @OUT --sample-rate 1e12|flexbond sim: option '--sample-rate': 1e+12 Hz over 5 s gives 5e+12 samples, more than the limit of 1e+08"
  "1|run s_ok.yaml -o @OUT --hull-modes 3|flexbond run: option '--hull-modes' needs auto, all (every mode) or an integer in 6..100000 (got '3')"
  "1|run s_ok.yaml -o @OUT --hull-cutoff -5|flexbond run: option '--hull-cutoff' needs a finite number > 0"
  "1|run s_ok.yaml --system flexible -o @OUT --hull-cutoff 2|flexbond run: option '--hull-cutoff': a cut-off of 2 Hz is below the hull's first elastic mode, at 10.3 Hz"
  "1|run s_ok.yaml --system flexible -o @OUT --hull-modes 100000|flexbond run: option '--hull-modes': 100000 modes, more than the hull's 1296 degrees of freedom"
  "5|export s_ok.yaml --system rigid -o @EXISTING|@EXISTING: cannot create directory: exists and is not a directory"
  "5|sim m_ok.yaml -o @EXISTING/sub|@EXISTING/sub: cannot create directory|not a directory"
)

# expect_clean: no crash and no sanitizer report.
expect_clean() {
  checks=$((checks + 1))
  [ "$status" -lt 128 ] || fail "$1: killed by signal $((status - 128))"
  checks=$((checks + 1))
  ! grep -qE 'Sanitizer|runtime error:' "$ERR" || fail "$1: sanitizer report"
}

# expect_untouched KIND PATH DESCRIPTION: after a failed run, PATH is as
# before: absent, or a directory holding only previous.txt, or a file,
# with the previous result.
expect_untouched() {
  checks=$((checks + 1))
  case $1 in
  absent) [ ! -e "$2" ] || fail "$3: $2 was created: $(ls -A "$2" 2>&1 | tr '\n' ' ')" ;;
  dir)
    [ "$(ls -A "$2")" = previous.txt ] && [ "$(cat "$2/previous.txt")" = "previous result" ] ||
      fail "$3: $2 changed: $(ls -A "$2" | tr '\n' ' ')"
    ;;
  file) [ -f "$2" ] && [ "$(cat "$2")" = "previous result" ] || fail "$3: $2 changed" ;;
  esac
}

# run_case N STATUS ARGS TEXT...: runs case N once per state of its output.
run_case() {
  local n=$1 want=$2 argstr=$3
  shift 3
  local states=none suffix=
  case $argstr in
  *@EXISTING*) states="file" ;;
  *@OUT*) states="absent dir" ;;
  *@FILE*)
    states="absent file"
    # The output file's name ends as the case wants (.inp, .dot, ...).
    suffix=${argstr#*@FILE}
    suffix=${suffix%% *}
    ;;
  esac
  local state target output words what text
  for state in $states; do
    target=$WORK/out/case$n-$state
    output=$target$suffix
    case $state in
    dir) mkdir -p "$output" && echo "previous result" >"$output/previous.txt" ;;
    file) echo "previous result" >"$output" ;;
    esac
    words=${argstr//@OUT/$target}
    words=${words//@FILE/$target}
    words=${words//@EXISTING/$target}
    what="case $n ($state): flexbond $words"
    read -ra args <<<"$words"
    "$FLEXBOND" "${args[@]}" >"$OUT" 2>"$ERR"
    status=$?
    expect_status "$want" "$what"
    expect_clean "$what"
    for text in "$@"; do
      expect_in "$ERR" "${text//@EXISTING/$target}" "$what"
    done
    [ "$state" = none ] || expect_untouched "$state" "$output" "$what"
  done
}

if [ "$(id -u)" -eq 0 ]; then
  # root reads a file whatever its mode: the case cannot fail as intended.
  echo "$NAME: SKIP case m_noread.yaml (chmod 000): running as root" >&2
fi
ncases=0
for line in "${CASES[@]}"; do
  ncases=$((ncases + 1))
  IFS='|' read -ra fields <<<"$line"
  if [ "$(id -u)" -eq 0 ] && [[ ${fields[1]} == *m_noread.yaml* ]]; then
    continue
  fi
  run_case "$ncases" "${fields[@]}"
done
checks=$((checks + 1))
[ "$ncases" -ge 40 ] || fail "the table has $ncases cases, fewer than 40"

# Without --strict the implausible tire runs, said once per warning at the value.
run run s_tire1.yaml --system rigid --no-figures -q -o "$WORK/out/tire1"
expect_status 0 "an implausible tire without --strict"
expect_in "$ERR" "flexbond: warning: $(at s_tire1.yaml 'tire_k: 1 ' 1) wheel.tire_k: 1 N/m is implausible" \
  "an implausible tire: the warning at its value"
expect_in "$ERR" "the static tire deflection would be 2.13e+04 m" "an implausible tire: its consequence"
checks=$((checks + 1))
[ "$(grep -c 'warning:' "$ERR")" -eq 2 ] || fail "an implausible tire: not two warnings"

echo "$NAME: $ncases cases, $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
