# SPDX-License-Identifier: BSD-3-Clause
# Shared setup and assertions of the tests/cli_*.sh scripts. Source it
# with NAME set to the script's name and the script's arguments
# (PATH/TO/flexbond REPO_ROOT) in $1 and $2.
if [ $# -ne 2 ]; then
  echo "usage: $0 PATH/TO/flexbond REPO_ROOT" >&2
  exit 2
fi
FLEXBOND=$1
REPO_ROOT=$2
if [ ! -x "$FLEXBOND" ]; then
  echo "$NAME: $FLEXBOND is not an executable" >&2
  exit 2
fi
if [ ! -d "$REPO_ROOT" ]; then
  echo "$NAME: $REPO_ROOT is not a directory" >&2
  exit 2
fi

WORK=$(mktemp -d "${TMPDIR:-/tmp}/fb_$NAME.XXXXXX") || exit 2
trap 'rm -rf "$WORK"' EXIT
OUT=$WORK/stdout
ERR=$WORK/stderr

failures=0
checks=0

fail() {
  echo "$NAME: FAIL: $*" >&2
  echo "  stdout: $(head -c 400 "$OUT")" >&2
  echo "  stderr: $(head -c 400 "$ERR")" >&2
  failures=$((failures + 1))
}

# at FILE TEXT [VALUE]: "FILE:LINE:" of the first line of FILE holding TEXT,
# or "FILE:LINE:COL:" with COL the 1-based column of VALUE in that line.
at() {
  awk -v text="$2" -v value="${3-}" -v file="$1" '
    index($0, text) {
      printf "%s:%d:", file, NR
      if (value != "") printf "%d:", index($0, value)
      found = 1
      exit
    }
    END { if (!found) printf "NOT-FOUND(%s in %s)", text, file }' "$1"
}

# run ARGS...: runs flexbond with stdout and stderr captured; sets $status.
run() {
  "$FLEXBOND" "$@" >"$OUT" 2>"$ERR"
  status=$?
}

# expect_status CODE DESCRIPTION
expect_status() {
  checks=$((checks + 1))
  [ "$status" -eq "$1" ] || fail "$2: exit status $status, expected $1"
}

# expect_in FILE TEXT DESCRIPTION: FILE contains TEXT (fixed string).
expect_in() {
  checks=$((checks + 1))
  grep -qF -- "$2" "$1" || fail "$3: '$2' not in $(basename "$1")"
}

# expect_absent PATH DESCRIPTION
expect_absent() {
  checks=$((checks + 1))
  [ ! -e "$1" ] || fail "$2: $1 was created"
}


# bracket_verdict LIMIT V_LO V_HI METRIC METRIC_OVER SPEED SPEED_OVER: a
# ride-limit row checked against a second tool's metric at its bracket's
# ends (V_LO at SPEED, V_HI at SPEED_OVER): below the limit at SPEED, at
# or above it at SPEED_OVER, the bracket at most 0.1 km/h wide, and the
# two tools' metrics equal to 1e-9 relative. Prints what is wrong;
# non-zero status then.
bracket_verdict() {
  awk -v limit="$1" -v v1="$2" -v v2="$3" -v m="$4" -v mo="$5" -v lo="$6" -v hi="$7" 'BEGIN {
    bad = 0
    if (!(v1 < limit && v2 >= limit)) { print "not bracketed: " v1 ", " v2; bad = 1 }
    if (!(hi - lo <= 0.1 + 1e-9 && hi > lo)) { print "bracket " lo " .. " hi; bad = 1 }
    d1 = v1 - m; d2 = v2 - mo
    if (d1 * d1 > 1e-18 * m * m || d2 * d2 > 1e-18 * mo * mo) { print "metrics differ: " v1 " vs " m ", " v2 " vs " mo; bad = 1 }
    exit bad
  }'
}
