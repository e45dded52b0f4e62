#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# report.md speaks of what the scenario has (docs/report.md,
# "Conclusions"): a truck with only a cargo mount (examples/truck4x4.yaml
# without its driver and engine) on an ISO 8608 random road is reported
# "on the ISO 8608 class C road", its title, window, animation and
# conclusions included, and nothing in it speaks of a driver, an engine or
# a bump; on a measured profile the road is named by its file, escaped for
# Markdown.
#
# usage: bash tests/cli_report_words.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_report_words
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2
cp "$REPO_ROOT"/examples/truck4x4.yaml "$REPO_ROOT"/examples/*.csv . || exit 2

# The truck without its driver and engine (and the driver's output), its
# comments dropped (a report quotes no comment, but this test must not
# pass by one), on a random road.
python3 - truck4x4.yaml cargo.yaml <<'EOF' || fail "fixture cargo.yaml"
import re
import sys
t = open(sys.argv[1]).read()
for line in (r"  - \{name: driver.*\n", r"  - \{name: engine.*\n", r"  - \{signal: acc, of: driver\}.*\n"):
    t, n = re.subn("^" + line, "", t, flags=re.M)
    assert n == 1, line
road = re.search(r"^road:\n(?:  .*\n)+", t, flags=re.M).group(0)
t = t.replace(road, "road:\n  speed_kmh: 30\n  iso8608:\n    class: C\n    seed: 2026\n"
              "    fade_in: 10\n    front_start: -5\n")
t = re.sub(r" *#.*", "", t)
t = re.sub(r"^scenario: .*", "scenario: cargo", t, flags=re.M)
t = re.sub(r"^description: .*", "description: a 4x4 truck with a cargo box", t, flags=re.M)
assert not re.search("driver|engine|bump", t, re.I), "the fixture still names them"
open(sys.argv[2], "w").write(t)
EOF

run run cargo.yaml -o "$WORK/cargo" -q --animate
expect_status 0 "run of the cargo truck on a random road"
R=$WORK/cargo/report.md
expect_in "$R" "# cargo: rigid and flexible hull on the ISO 8608 class C road" "the title"
expect_in "$R" "| road window | the vehicle on the ISO 8608 class C road, from " "the road window"
expect_in "$R" "![System 2 (flexible hull) on the ISO 8608 class C road](animation_system2.gif)" \
  "the animation"
expect_in "$R" "On the ISO 8608 class C road, System 2 departs from System 1 by up to " \
  "the conclusions"
expect_in "$R" "cargo" "the mount by its name"
for word in driver engine bump; do
  checks=$((checks + 1))
  ! grep -qi "$word" "$R" || fail "report.md of the cargo truck on a random road says '$word':
$(grep -i -m 3 "$word" "$R")"
done

# A measured profile, named by its file: the underscore and the asterisk
# escaped.
awk 'BEGIN { print "s,z"; for (s = -20; s <= 200; s += 0.5) printf "%g,%g\n", s, (s > 10 && s < 11) ? 0.03 : 0 }' \
  >"my_road*.csv"
sed -e '/^  iso8608:/,$d' cargo.yaml >profile.yaml
printf '  profile:\n    file: "my_road*.csv"\n    front_start: -5\n' >>profile.yaml
sed -n '/^simulation:/,$p' cargo.yaml >>profile.yaml
run run profile.yaml -o "$WORK/profile" -q --system rigid --no-figures
expect_status 0 "run on a measured profile"
head -n 1 "$WORK/profile/report.md" >"$WORK/title"
expect_in "$WORK/title" "# cargo: the vehicle over the profile " "the profile's title"
expect_in "$WORK/title" "my\\_road\\*.csv" "the profile's title: its file's name, escaped"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
