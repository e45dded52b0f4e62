#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Implausible but legal scenario values through the real flexbond command
# (docs/errors.md, "Warnings"): a plate thickness written in mm, a density
# in g/cm^3, a total weight below the hull's masses and one far above them,
# and a coupling on a generated hull, where it changes nothing. For each:
# the warning at FILE:LINE:COL: KEY with the value in the other unit where
# there is one, exit 0 without --strict, exit 2 and nothing written with it.
#
# usage: bash tests/cli_plausible.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_plausible
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT/examples/truck4x4.yaml" truck.yaml || exit 2

# at FILE TEXT: "FILE:LINE:COL:" with LINE the first line of FILE holding
# TEXT and COL the column of TEXT's value (after "KEY: ").
at() {
  AT_TEXT=$2 awk -v file="$1" '
    index($0, ENVIRON["AT_TEXT"]) {
      t = ENVIRON["AT_TEXT"]
      printf "%s:%d:%d:", file, NR, index($0, t) + index(t, ": ") + 1
      found = 1
      exit
    }
    END { if (!found) printf "NOT-FOUND(%s in %s)", ENVIRON["AT_TEXT"], file }' "$1"
}

# derive NEW SED-SCRIPT: NEW is truck.yaml edited; it must differ.
derive() {
  sed "$2" truck.yaml >"$1"
  checks=$((checks + 1))
  ! cmp -s "$1" truck.yaml || fail "fixture $1: sed $2 changed nothing"
}

# warned FILE WHERE TEXT...: `mesh FILE` warns once with each TEXT, the
# first prefixed by "flexbond: warning: WHERE", and exits 0; under
# --strict it exits 2 with that text as its error and writes no
# directory.
warned() {
  local file=$1 where=$2
  shift 2
  run mesh "$file"
  expect_status 0 "$file without --strict"
  expect_in "$ERR" "flexbond: warning: $where $1" "$file: the warning at its value"
  local t
  for t in "$@"; do
    expect_in "$ERR" "$t" "$file"
  done
  run mesh --strict "$file" --export-matrices "$WORK/out"
  expect_status 2 "$file with --strict"
  expect_in "$ERR" "flexbond: $where $1" "$file with --strict: the error at its value"
  expect_in "$ERR" "(--strict refuses implausible values:" "$file with --strict"
  expect_absent "$WORK/out" "$file with --strict"
  rm -rf "$WORK/out"
}

run mesh truck.yaml
expect_status 0 "the truck"
checks=$((checks + 1))
[ ! -s "$ERR" ] || fail "the truck warns"

# A thickness meant in mm: said in mm, against the plates vehicles have.
derive thick.yaml 's/thickness: 0.005 /thickness: 20 /'
warned thick.yaml "$(at thick.yaml 'thickness: 20')" \
  "hull.material.thickness: 20 m is implausible: 20 m = 20000 mm; plates of ground vehicles are 3-100 mm"

# A density in g/cm^3: said in g/cm^3, against structural metals and
# composites.
derive dense.yaml 's/density: 7850/density: 7.85/'
warned dense.yaml "$(at dense.yaml 'density: 7.85')" \
  "hull.material.density: 7.85 kg/m^3 is implausible: 7.85 kg/m^3 = 0.00785 g/cm^3; structural metals and composites are 900 kg/m^3"

# A weight below the generated mesh's structure (2286 kg, weight-only
# payload) and its battery (300 kg): 20000 N is 2039 kg.
derive light.yaml 's/total_weight: 49050 /total_weight: 20000 /'
warned light.yaml "$(at light.yaml 'total_weight: 20000')" \
  "load.total_weight: 20000 N is implausible: 2039 kg, less than the 2586 kg of the hull (2286 kg) and its masses (300 kg)"

# A weight far above them: 980000 N is 99898 kg, a payload of 97312 kg,
# 37.6 times the 2586 kg. The tires would also deflect too far under it;
# the rules that start from the weight are not said again.
derive heavy.yaml 's/total_weight: 49050 /total_weight: 980000 /'
warned heavy.yaml "$(at heavy.yaml 'total_weight: 980000')" \
  "load.total_weight: 980000 N is implausible: 9.99e+04 kg, which leaves 9.731e+04 kg of payload, more than 10 times the 2586 kg of the hull (2286 kg) and its masses (300 kg)"
run mesh heavy.yaml
checks=$((checks + 1))
! grep -q "tire deflection" "$ERR" || fail "the weight's consequences said again"
# Ten times is not yet implausible: 2586 kg x 11 x 9.81 m/s^2 = 279 kN.
derive heavy10.yaml 's/total_weight: 49050 /total_weight: 275000 /'
run mesh heavy10.yaml
expect_status 0 "ten times the hull's masses"
checks=$((checks + 1))
! grep -q "load.total_weight" "$ERR" || fail "ten times the hull's masses is warned"

# A coupling on the generated hull, whose nodes are on every point.
derive coupled.yaml 's/^    density: 1$/    density: 1\n    coupling: {kind: distributing, radius: 0.3, surface: FLOOR}/'
warned coupled.yaml "$(at coupled.yaml 'coupling: {')" \
  "hull.mesh.coupling: changes nothing: the hull's source, generator, puts a node at every attachment point"
# ... and it does change nothing: the same modes, to the last digit.
run modes --system flexible truck.yaml
cp "$OUT" "$WORK/modes_plain.txt"
run modes --system flexible coupled.yaml
expect_status 0 "modes with a coupling"
checks=$((checks + 1))
cmp -s "$OUT" "$WORK/modes_plain.txt" || fail "a coupling on the generated hull changed its modes"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
