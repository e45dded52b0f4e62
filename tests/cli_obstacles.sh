#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The obstacle road types through the real flexbond command
# (docs/roads.md, "Obstacles"): bad values refused at FILE:LINE:COL and
# their key, the type's rules at the key of the value they name, an
# implausible height warned of, and a road a point-contact tire cannot
# follow (a vertical face, a half-round's base) refused at the road type's
# key with what to do. No output is left behind by a refused run.
#
# usage: bash tests/cli_obstacles.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_obstacles
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2

# road_with NEW TYPE LINES...: the paper's scenario with its road section's
# bump replaced by a section TYPE of the given lines (one key each). An
# error about the whole section is located at its first key.
road_with() {
  local new=$1 type=$2
  shift 2
  local body="  $type:"
  for line in "$@"; do body="$body\\
    $line"; done
  sed -e "/^  bump:/,/crossing of about three seconds/c\\
$body" "$REPO_ROOT/examples/apc6x6.yaml" >"$new"
  checks=$((checks + 1))
  grep -q "^  $type:" "$new" || fail "fixture $new has no $type section"
}

road_with neg_height.yaml halfround 'height: -0.2' 'first_contact: 1'
road_with bad_track.yaml cleat 'height: 0.05' 'length: 0.2' 'track: middle' 'first_contact: 1'
road_with deep_pothole.yaml pothole 'depth: 0.5' 'length: 0.6' 'first_contact: 1'
road_with overlap.yaml cleat 'height: 0.05' 'length: 0.2' 'count: 3' 'spacing: 0.1' 'first_contact: 1'
road_with no_spacing.yaml cleat 'height: 0.05' 'length: 0.2' 'count: 3' 'first_contact: 1'
road_with big_edge.yaml cleat 'height: 0.05' 'length: 0.01' 'edge_radius: 0.04' 'first_contact: 1'
road_with both_ramps.yaml trapezoid 'height: 0.1' 'top_length: 0.5' 'ramp_length: 0.3' 'ramp_angle_deg: 20' 'first_contact: 1'
road_with flat_step.yaml step 'height: 0' 'first_contact: 1'
road_with face.yaml step 'height: 0.1' 'ramp_length: 0' 'first_contact: 1'
road_with halfround.yaml halfround 'height: 0.2' 'track: left' 'first_contact: 1'
road_with walls.yaml pothole 'depth: 0.1' 'length: 0.6' 'shape: rectangular' 'first_contact: 1'
road_with tall.yaml trapezoid 'height: 1.5' 'top_length: 2' 'ramp_length: 3' 'first_contact: 1'
road_with ok_step.yaml step 'height: 0.1' 'first_contact: 1'
# Courses: a bad line, and an obstacle with vertical faces.
printf 'cleat at=0 height=0.05 length=0.2\npothole at=3 depth=-0.05 length=0.5\n' >bad.course
printf 'trapezoid at=0 height=0.05 top_length=0.2 ramp_length=0.3\ncleat at=3 height=0.05 length=0.2 ramp_length=0 track=right\n' >faces.course
road_with bad_course.yaml course 'file: bad.course' 'first_contact: 1'
road_with faces_course.yaml course 'file: faces.course' 'first_contact: 1'

# status|args|expected text on stderr
cases=(
  "2|run neg_height.yaml -o out|$(at neg_height.yaml 'height: -0.2' -0.2) road.halfround.height: must be > 0 m"
  "2|run bad_track.yaml -o out|$(at bad_track.yaml 'track: middle' middle) road.cleat.track: unknown value 'middle'; expected both | left | right"
  "2|run deep_pothole.yaml -o out|$(at deep_pothole.yaml 'depth: 0.5' 0.5) road.pothole.depth: a rounded pothole's walls are an arc of a circle through its rims: it is at most half its length deep (0.3 m; got 0.5 m)"
  "2|run overlap.yaml -o out|$(at overlap.yaml 'spacing: 0.1' 0.1) road.cleat.spacing: the obstacles would overlap: their spacing must be at least one's length, 0.24 m (got 0.1 m)"
  "2|run no_spacing.yaml -o out|$(at no_spacing.yaml '    height: 0.05' height) road.cleat.spacing: a series of obstacles needs their spacing"
  "2|run big_edge.yaml -o out|$(at big_edge.yaml 'edge_radius: 0.04' 0.04) road.cleat.edge_radius: the rounded edges do not fit on the top"
  "2|run both_ramps.yaml -o out|$(at both_ramps.yaml 'ramp_angle_deg: 20' 20) road.trapezoid.ramp_angle_deg: give either ramp_angle_deg or ramp_length, not both"
  "2|run flat_step.yaml -o out|$(at flat_step.yaml '    height: 0' 0) road.step.height: a step of height 0 is no step"
  "2|run face.yaml -o out|$(at face.yaml '    height: 0.1' height) road.step: road: the step's vertical face cannot be followed by a point-contact tire: give it a ramp (ramp_length > 0), or give the tires an envelope (the LF wheel meets it at s = 0 m on the left track)"
  "2|run halfround.yaml -o out|$(at halfround.yaml '    height: 0.2' height) road.halfround: road: the half-round's infinite slope at its base cannot be followed by a point-contact tire: give the tires an envelope"
  "2|run walls.yaml -o out|$(at walls.yaml '    depth: 0.1' depth) road.pothole: road: the pothole's vertical walls cannot be followed by a point-contact tire: make it \`shape: rounded\`"
  "0|modes tall.yaml|$(at tall.yaml 'height: 1.5' 1.5) road.trapezoid.height: 1.5 m is implausible"
  "0|modes ok_step.yaml|"
  "2|run bad_course.yaml -o out|$(at bad_course.yaml 'file: bad.course' bad.course) road.course.file: ./bad.course:2: depth: must be > 0 m (got -0.05)"
  "2|run faces_course.yaml -o out|$(at faces_course.yaml '    file' file) road.course: road: ./faces.course:2: the cleat's vertical faces cannot be followed by a point-contact tire: give it ramps (ramp_length > 0), or give the tires an envelope (the RF wheel meets it at s = 3 m on the right track)"
)

for c in "${cases[@]}"; do
  IFS='|' read -r want args text <<<"$c"
  rm -rf out
  # shellcheck disable=SC2086
  run $args
  expect_status "$want" "$args"
  [ -z "$text" ] || expect_in "$ERR" "$text" "$args"
  if [ "$want" -ne 0 ]; then
    expect_absent out "$args"
  fi
  checks=$((checks + 1))
  [ "$status" -lt 128 ] || fail "$args: crashed (status $status)"
done

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
