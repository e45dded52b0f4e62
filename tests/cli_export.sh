#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond export: the APC example's System 1 and System 2 as descriptor
# systems. The files exist and parse as Matrix Market (read here in a few
# lines of Python), their sizes agree with each other and with model.json,
# the inputs are laid out as documented, and System 1's model reproduces
# the paper's start (every state zero, gravity on: the driver in free fall,
# the tires unloaded). Bad options and bad scenarios exit non-zero and
# write nothing; a failure while writing takes back what was written.
#
# usage: bash tests/cli_export.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_export
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

APC=$REPO_ROOT/examples/apc6x6.yaml
EXPECTED_FILES=$(printf '%s\n' .flexbond-manifest A.mtx Bu.mtx C.mtx D.mtx E.mtx f.mtx model.json | sort)

# expect_files DIR DESCRIPTION: DIR holds exactly the files of an export.
expect_files() {
  checks=$((checks + 1))
  [ "$(ls -A "$1" | sort)" = "$EXPECTED_FILES" ] || fail "$2: files $(ls -A "$1" | tr '\n' ' ')"
}

# check_export DIR SYSTEM SOLVE: the files parse and agree with model.json;
# with SOLVE = 1 also the free-fall start (a dense solve in pure Python,
# fine for System 1's ~130 algebraic variables).
check_export() {
  checks=$((checks + 1))
  python3 - "$1" "$2" "$3" <<'EOF' || fail "export contents ($1)"
import json, sys
out, system, solve = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
problems = []
def want(cond, what):
    if not cond:
        problems.append(what)

def read_mtx(path):
    """Matrix Market coordinate real general -> (rows, cols, {(i, j): v}), 0-based."""
    with open(path) as fp:
        head = fp.readline().split()
        want(head == ["%%MatrixMarket", "matrix", "coordinate", "real", "general"], path + " header")
        line = fp.readline()
        while line.startswith("%"):
            line = fp.readline()
        m, n, nnz = (int(t) for t in line.split())
        entries = {}
        for line in fp:
            i, j, v = line.split()
            i, j = int(i) - 1, int(j) - 1
            want(0 <= i < m and 0 <= j < n, "%s: entry (%d, %d) inside %d x %d" % (path, i, j, m, n))
            entries[(i, j)] = entries.get((i, j), 0.0) + float(v)
        want(len(entries) == nnz, "%s: %d entries, header says %d" % (path, len(entries), nnz))
    return m, n, entries

mats = {k: read_mtx("%s/%s.mtx" % (out, k)) for k in ["E", "A", "Bu", "f", "C", "D"]}
d = json.load(open(out + "/model.json"))
n, ns, nu, nr = d["n"], d["ndifferential"], d["ninputs"], d["output_rows"]
want(d["system"] == system and d["scenario"] == "apc6x6", "system and scenario")
shape = {k: v[:2] for k, v in mats.items()}
want(shape == {"E": (n, n), "A": (n, n), "Bu": (n, nu), "f": (n, 1), "C": (nr, n), "D": (nr, nu)},
     "shapes %s for n = %d, %d inputs, %d rows of C" % (shape, n, nu, nr))
want(len(d["variables"]) == n, "one name per variable")
diff = [v["differential"] for v in d["variables"]]
want(diff == [True] * ns + [False] * (n - ns), "differential variables first")
want(mats["E"][2] == {(i, i): 1.0 for i in range(ns)}, "E = identity at the differential rows")
want(not mats["D"][2], "D is zero")
# u = [h_LF .. h_RR, hdot_LF .. hdot_RR]: the heights do not enter.
wheels = ["LF", "RF", "LM", "RM", "LR", "RR"]
want([u["name"] for u in d["inputs"]] == ["h_" + w for w in wheels] + ["hdot_" + w for w in wheels],
     "input names and order")
bu = mats["Bu"][2]
want(all(j >= 6 for (_, j) in bu), "height columns of Bu are zero")
for k, u in enumerate(d["inputs"][6:], start=6):
    want(bu.get((u["defines_variable"], k)) == 1.0 and sum(1 for (_, j) in bu if j == k) == 1,
         u["name"] + " defines its variable")
names = ["tire_force_LF", "spring_defl_RF", "torsion", "driver_acc", "shock_power_LM",
         "tire_defl_RM", "tire_power_LR"]
want([o["name"] for o in d["outputs"]] == names, "output names")
rows = [r for o in d["outputs"] for r in o["rows"]]
want(rows == list(range(nr)), "rows of C in output order")
want([o["product"] for o in d["outputs"]] == [len(o["rows"]) == 2 for o in d["outputs"]]
     and [o["name"] for o in d["outputs"] if o["product"]] == ["shock_power_LM", "tire_power_LR"],
     "the two powers are products of two rows")

if solve:
    # Every state zero, u = 0: solve the algebraic rows 0 = A_aa z + f_a
    # (Gaussian elimination with partial pivoting), then read the outputs.
    A, f = mats["A"][2], mats["f"][2]
    na = n - ns
    M = [[A.get((ns + i, ns + j), 0.0) for j in range(na)] + [-f.get((ns + i, 0), 0.0)]
         for i in range(na)]
    for c in range(na):
        p = max(range(c, na), key=lambda r: abs(M[r][c]))
        M[c], M[p] = M[p], M[c]
        for r in range(c + 1, na):
            g = M[r][c] / M[c][c]
            if g:
                for k in range(c, na + 1):
                    M[r][k] -= g * M[c][k]
    z = [0.0] * na
    for c in reversed(range(na)):
        z[c] = (M[c][na] - sum(M[c][k] * z[k] for k in range(c + 1, na))) / M[c][c]
    x = [0.0] * ns + z
    C = mats["C"][2]
    y = [sum(v * x[j] for (i, j), v in C.items() if i == r) for r in range(nr)]
    out_y = {}
    for o in d["outputs"]:
        v = y[o["rows"][0]]
        out_y[o["name"]] = v * y[o["rows"][1]] if o["product"] else v
    # Data sheet: gravity switched on with every state zero, the driver
    # starts in free fall (-9.81 m/s^2) and nothing else has moved; the
    # solve is exact to rounding (1e-9 is far above it).
    want(abs(out_y["driver_acc"] + 9.81) < 1e-9, "driver_acc = -g at rest: %r" % out_y["driver_acc"])
    for name in names:
        if name != "driver_acc":
            want(abs(out_y[name]) < 1e-9, "%s = 0 at the start: %r" % (name, out_y[name]))
if problems:
    print("\n".join(problems), file=sys.stderr)
    sys.exit(1)
EOF
}

# ---- System 1.
run export "$APC" --system rigid -o "$WORK/rigid"
expect_status 0 "export --system rigid"
expect_files "$WORK/rigid" "export --system rigid"
expect_in "$OUT" "wrote $WORK/rigid" "summary line"
check_export "$WORK/rigid" rigid 1

# ---- System 2 (the default): ~9k variables, about 0.3 s.
run export "$APC" -o "$WORK/flexible"
expect_status 0 "export (flexible)"
expect_files "$WORK/flexible" "export (flexible)"
check_export "$WORK/flexible" flexible 0

# ---- Help and bad options: usage errors, nothing written.
run export --help
expect_status 0 "export --help"
expect_in "$OUT" "usage: flexbond export" "help text"
run export "$APC" --system wobbly -o "$WORK/out_opt"
expect_status 1 "export --system wobbly"
expect_absent "$WORK/out_opt" "bad --system: output"
run export "$APC"
expect_status 1 "export without -o"
expect_in "$ERR" "missing output directory" "missing -o message"

# ---- Bad scenarios: input errors naming the file, nothing written.
printf 'name: broken\nvehicle: [\n' >"$WORK/broken.yaml"
run export "$WORK/broken.yaml" --system rigid -o "$WORK/out_broken"
expect_status 2 "export of a malformed scenario"
expect_in "$ERR" "broken.yaml" "message names the file"
expect_absent "$WORK/out_broken" "malformed scenario: output"
run export "$WORK/no_such.yaml" --system rigid -o "$WORK/out_nofile"
expect_status 5 "export of a missing scenario"
expect_absent "$WORK/out_nofile" "missing scenario: output"

# ---- A failure while writing (model.json, the last file, cannot replace
# a directory) takes back the matrices already written.
mkdir -p "$WORK/partial/model.json/blocker"
run export "$APC" --system rigid -o "$WORK/partial"
expect_status 5 "export into a directory whose model.json is a directory"
for f in A.mtx Bu.mtx C.mtx D.mtx E.mtx f.mtx; do
  expect_absent "$WORK/partial/$f" "failed write: $f"
done

# ---- The hull's own matrices (flexbond mesh --export-matrices): K and M of
# the 216-node hull (1296 DOFs), the rows named, the deck they belong to
# with its coordinates rounded, and that deck read back as a scenario's
# gives the same mass.
run mesh "$APC" --export-matrices "$WORK/hull_matrices"
expect_status 0 "mesh --export-matrices"
expect_in "$OUT" "wrote $WORK/hull_matrices: K.mtx, M.mtx (1296 x 1296), dofs.csv, hull.inp" \
  "mesh --export-matrices summary"
for f in K M; do
  checks=$((checks + 1))
  [ "$(sed -n 2p "$WORK/hull_matrices/$f.mtx" | cut -d' ' -f1-2)" = "1296 1296" ] ||
    fail "$f.mtx: not 1296 x 1296"
done
checks=$((checks + 1))
[ "$(wc -l <"$WORK/hull_matrices/dofs.csv")" -eq 1297 ] || fail "dofs.csv: not 1296 rows"
expect_in "$WORK/hull_matrices/dofs.csv" "1296,216,rz" "dofs.csv: the last row"
# No coordinate is the round-off of a zero (-2.8e-17): the *NODE lines
# carry no exponent below e-12.
checks=$((checks + 1))
! awk '/^\*NODE/ { n = 1; next } /^\*/ { n = 0 } n' "$WORK/hull_matrices/hull.inp" |
  grep -Eq 'e-(1[2-9]|[2-9][0-9]|[1-9][0-9][0-9])' || fail "hull.inp: a coordinate below 1e-12"
sed -e '/^    density: 1 /d' \
  -e "/^    generator:/,/nose_rung_divisions/c\\    deck: $WORK/hull_matrices/hull.inp" \
  "$APC" >"$WORK/apc_deck.yaml"
run mesh "$WORK/apc_deck.yaml"
expect_status 0 "mesh of the exported deck"
expect_in "$OUT" "mass 4041.72 kg" "the exported deck's mass"
mkdir -p "$WORK/hull_blocked/M.mtx/blocker"
run mesh "$APC" --export-matrices "$WORK/hull_blocked"
expect_status 5 "mesh --export-matrices into a directory whose M.mtx is a directory"
expect_absent "$WORK/hull_blocked/K.mtx" "failed matrix export: K.mtx"

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
