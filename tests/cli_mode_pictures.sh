#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# System 2's modes pictured by what they are (docs/report.md): flexbond
# modes --system flexible -o pictures, of the modes its modes.csv
# describes, the first hull pitch, roll and bounce, each mounted body's
# first dominated mode, the first wheel hop and the first two elastic
# modes; on the paper's vehicle that keeps modes 1, 2 and 8 of the
# pictures of old (the paper's Figs. 3-4; its mode 10 is a later wheel
# hop); a turret-like mount gets its picture; report.mode_pictures and
# --picture-modes list them instead, and a mode number that is no whole
# number from 1 is refused at its key.
#
# usage: bash tests/cli_mode_pictures.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_mode_pictures
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/apc6x6.yaml "$REPO_ROOT"/examples/*.csv . || exit 2

# pictured DIR: the numbers of DIR's mode_NN.png, one line.
pictured() {
  (cd "$1" && ls mode_*.png 2>/dev/null) | sed 's/^mode_0*\([0-9]*\)\.png$/\1/' | sort -n |
    tr '\n' ' '
}

# expected CSV: the modes the rules choose, from modes.csv's descriptions
# (mode,frequency_hz,"description (NN%)"), mounts named in $MOUNTS.
expected() {
  awk -F, -v mounts="$MOUNTS" '
    BEGIN { n = split(mounts, m, " "); for (i = 1; i <= n; ++i) is_mount[m[i]] = 1 }
    NR == 1 { next }
    {
      d = $3; gsub(/"/, "", d); sub(/ \([0-9]+%\)$/, "", d)
      if ((d == "hull pitch" || d == "hull roll" || d == "hull bounce") && !(d in seen)) pick[$1] = 1
      if ((d in is_mount) && !(d in seen)) pick[$1] = 1
      if (d ~ /^wheel hop / && !hop++) pick[$1] = 1
      if (d == "hull elastic" && elastic++ < 2) pick[$1] = 1
      seen[d] = 1
    }
    END { for (k in pick) print k }' "$1" | sort -n | tr '\n' ' '
}

# contains LIST N: N is one of LIST's words.
contains() {
  case " $1 " in *" $2 "*) return 0 ;; esac
  return 1
}

# ---- The paper's vehicle.
run modes --system flexible apc6x6.yaml -o "$WORK/apc"
expect_status 0 "modes of the paper's vehicle"
got=$(pictured "$WORK/apc")
MOUNTS="driver engine"
want=$(expected "$WORK/apc/modes.csv")
# Every rule's mode is pictured; the engine, which dominates no mode here,
# adds the one that gives it its largest share (mode 3, beside the driver).
for k in $want; do
  checks=$((checks + 1))
  contains "$got" "$k" || fail "the paper's vehicle: mode $k (of $want) not pictured: $got"
done
for k in 1 2 8; do
  checks=$((checks + 1))
  contains "$got" "$k" || fail "the paper's vehicle: mode $k, pictured before, is not: $got"
done
checks=$((checks + 1))
[ "$got" = "1 2 3 4 5 6 8 13 " ] || fail "the paper's vehicle pictures $got"

# ---- A turret: a heavy, stiff mount ahead of the middle.
sed 's/^mounts: .*/mounts:\n  - {name: turret, mass: 1500, stiffness: 3000000, damping: 20000, x: 0.3, y: 0.0}/' \
  apc6x6.yaml >turret.yaml
checks=$((checks + 1))
! cmp -s turret.yaml apc6x6.yaml || fail "fixture turret.yaml: no 'mounts:' line"
run modes --system flexible turret.yaml -o "$WORK/turret"
expect_status 0 "modes with a turret"
turret=$(awk -F, '$3 ~ /^"turret / { print $1; exit }' "$WORK/turret/modes.csv")
checks=$((checks + 1))
[ -n "$turret" ] && contains "$(pictured "$WORK/turret")" "$turret" ||
  fail "the turret's mode (${turret:-none}) is not pictured: $(pictured "$WORK/turret")"

# ---- Listed: report.mode_pictures in the file, --picture-modes over it.
sed 's/^simulation:/report:\n  mode_pictures: [3, 1, 7]\nsimulation:/' apc6x6.yaml >listed.yaml
run modes --system flexible listed.yaml -o "$WORK/listed"
expect_status 0 "modes with report.mode_pictures"
checks=$((checks + 1))
[ "$(pictured "$WORK/listed")" = "1 3 7 " ] ||
  fail "report.mode_pictures [3, 1, 7] pictures $(pictured "$WORK/listed")"
run modes --system flexible listed.yaml --picture-modes 2,9 -o "$WORK/option"
expect_status 0 "modes with --picture-modes"
checks=$((checks + 1))
[ "$(pictured "$WORK/option")" = "2 9 " ] ||
  fail "--picture-modes 2,9 pictures $(pictured "$WORK/option")"
run run listed.yaml -o "$WORK/run" -q
expect_status 0 "run with report.mode_pictures"
expect_in "$WORK/run/report.md" "The modes the scenario lists" "the report says the modes are listed"
checks=$((checks + 1))
[ "$(grep -c '^!\[System 2, mode ' "$WORK/run/report.md")" -eq 3 ] ||
  fail "the report of report.mode_pictures [3, 1, 7] has not 3 mode pictures"
expect_in "$WORK/run/report.md" "](mode_07.png)" "the report pictures mode 7"

# ---- Refused: not a whole number from 1, at its key; a bad option.
sed 's/^simulation:/report:\n  mode_pictures: [1, 2.5]\nsimulation:/' apc6x6.yaml >half.yaml
line=$(grep -n '^  mode_pictures: \[1, 2.5\]' half.yaml | cut -d: -f1)
run modes --system flexible half.yaml
expect_status 2 "report.mode_pictures [1, 2.5]"
expect_in "$ERR" "half.yaml:$line:" "report.mode_pictures [1, 2.5]: at its line"
expect_in "$ERR" "report.mode_pictures[1]: must be a mode number: a whole number from 1 (got 2.5)" \
  "report.mode_pictures [1, 2.5]: the item and why"
run modes --system flexible apc6x6.yaml --picture-modes 0,2 -o "$WORK/zero"
expect_status 1 "--picture-modes 0,2"
expect_in "$ERR" "option '--picture-modes' needs up to 16 mode numbers from 1" "--picture-modes 0,2"
expect_absent "$WORK/zero" "--picture-modes 0,2"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
