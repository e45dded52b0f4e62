#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond run --animate: on the APC shortened to 3 s (a 0.5 m bump met
# at 1 s), each system's ParaView time series and GIF, as docs/animation.md
# describes them: one .vtu per frame at the asked rate over the bump
# window (summary.json's), a .pvd naming them in time order, points drawn
# at X + warp_factor * displacement, System 1's hull moving as a rigid
# body (its vertical displacements a plane over the nodes, to the files'
# 10 digits), the wheels and bodies as vertex cells of their parts, a
# complete GIF of as many images as frames, report.md's section linking
# them; bad settings are usage errors that write nothing.
#
# usage: bash tests/cli_animate.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_animate
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

SHORT=$WORK/apc_short.yaml
sed -e 's/^  t_end: 15 /  t_end: 3.0 /' -e 's/first_contact: 5.0/first_contact: 1.0/' \
  -e 's/length: 3.70 /length: 0.5 /' "$REPO_ROOT/examples/apc6x6.yaml" >"$SHORT"

# 15 frames/s: frame times that are not short decimals, so the .pvd and the .vtu
# must each write them exactly to agree.
run run "$SHORT" -o "$WORK/anim" -q --animate --animate-fps 15
expect_status 0 "run --animate --animate-fps 15"
for sys in 1 2; do
  expect_in "$WORK/anim/report.md" "](animation_system$sys.gif)" "report.md embeds system $sys's GIF"
  expect_in "$WORK/anim/report.md" "\`animation_system$sys.pvd\`" "report.md names system $sys's .pvd"
done
expect_in "$WORK/anim/report.md" "## Animation" "report.md's animation section"

checks=$((checks + 1))
python3 - "$WORK/anim" 15 <<'PY' || fail "the animation files"
import json, math, os, sys
import xml.etree.ElementTree as ET
out, fps = sys.argv[1], float(sys.argv[2])
problems = []
def want(cond, what):
    if not cond:
        problems.append(what)
t0, t1 = json.load(open(out + "/summary.json"))["system1"]["bump_window"]
nframes = int(math.floor((t1 - t0) * fps + 1e-9)) + 1
def arrays(piece, where):
    return {a.get("Name"): [float(v) for v in a.text.split()] for a in piece.find(where)}
def gif_frames(path):
    # The GIF89a block walk (header, screen, colour table, blocks, trailer).
    d = open(path, "rb").read()
    if d[:6] != b"GIF89a":
        return -1
    pos = 13 + (3 << ((d[10] & 7) + 1) if d[10] & 0x80 else 0)
    n = 0
    while pos < len(d):
        b = d[pos]; pos += 1
        if b == 0x3B:
            return n if pos == len(d) else -1
        if b == 0x21:
            pos += 1
        elif b == 0x2C:
            packed = d[pos + 8]; pos += 9
            if packed & 0x80:
                pos += 3 << ((packed & 7) + 1)
            pos += 1; n += 1
        else:
            return -1
        while d[pos]:
            pos += d[pos] + 1
        pos += 1
    return -1
for sys_ in (1, 2):
    pvd = ET.parse("%s/animation_system%d.pvd" % (out, sys_)).getroot()
    sets = pvd.find("Collection").findall("DataSet")
    want(len(sets) == nframes, "system %d: %d frames, not %d" % (sys_, len(sets), nframes))
    times = [float(s.get("timestep")) for s in sets]
    want(all(abs(t - (t0 + k / fps)) < 1e-9 for k, t in enumerate(times)), "frame times")
    vtus = sorted(f for f in os.listdir(out) if f.startswith("animation_system%d_" % sys_))
    want(vtus == [s.get("file") for s in sets], "system %d: the .pvd names the .vtu files" % sys_)
    want(gif_frames("%s/animation_system%d.gif" % (out, sys_)) == nframes,
         "system %d: a GIF of %d images" % (sys_, nframes))
    for k in (0, nframes // 2, nframes - 1):
        root = ET.parse("%s/%s" % (out, sets[k].get("file"))).getroot()
        grid = root.find("UnstructuredGrid")
        fields = {a.get("Name"): float(a.text) for a in grid.find("FieldData")}
        want(fields["TimeValue"] == times[k], "TimeValue of frame %d is its .pvd timestep" % k)
        warp = fields["warp_factor"]
        piece = grid.find("Piece")
        pd, cells = arrays(piece, "PointData"), arrays(piece, "Cells")
        pts = [float(v) for v in piece.find("Points").find("DataArray").text.split()]
        npts = int(piece.get("NumberOfPoints"))
        part, u = pd["part"], pd["displacement"]
        want(len(part) == npts and len(u) == 3 * npts and len(pts) == 3 * npts, "array sizes")
        # 6 wheels (part 2), the driver and the engine (part 1), each a
        # vertex cell.
        want(part.count(2) == 6 and part.count(1) == 2, "parts of frame %d" % k)
        want(cells["types"].count(1) == 8, "vertex cells")
        node_id = pd["node_id"]
        hull = [i for i in range(npts) if part[i] == 0]
        # Frame 0 is the reference: nothing has moved yet.
        if k == 0:
            want(max(abs(v) for v in u) == 0, "frame 0 does not move")
        if sys_ == 1 and k > 0:
            # uz = z + y phi - x theta: the plane through three nodes
            # predicts every other (coordinates at rest: X = P - warp u).
            rest = [[pts[3 * i + c] - warp * u[3 * i + c] for c in range(3)] for i in hull]
            uz = [u[3 * i + 2] for i in hull]
            # Three nodes spanning the largest triangle from node 0.
            def area(i, j):
                return abs((rest[i][0] - rest[0][0]) * (rest[j][1] - rest[0][1])
                           - (rest[j][0] - rest[0][0]) * (rest[i][1] - rest[0][1]))
            a = 0
            b = max(range(len(rest)), key=lambda i: (rest[i][0] - rest[0][0]) ** 2
                    + (rest[i][1] - rest[0][1]) ** 2)
            c = max(range(len(rest)), key=lambda j: area(b, j))
            (xa, ya, _), (xb, yb, _), (xc, yc, _) = rest[a], rest[b], rest[c]
            det = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya)
            gx = ((uz[b] - uz[a]) * (yc - ya) - (uz[c] - uz[a]) * (yb - ya)) / det
            gy = ((xb - xa) * (uz[c] - uz[a]) - (xc - xa) * (uz[b] - uz[a])) / det
            big = max(abs(v) for v in uz)
            worst = max(abs(uz[a] + gx * (r[0] - xa) + gy * (r[1] - ya) - uz[j])
                        for j, r in enumerate(rest))
            want(big > 1e-4 and worst <= 1e-8 * big,
                 "system 1 frame %d: rigid to %.3g of %.3g m" % (k, worst, big))
if problems:
    print("\n".join(problems), file=sys.stderr)
    sys.exit(1)
PY

# Without figures: the ParaView files alone.
run run "$SHORT" -o "$WORK/plain" -q --animate --animate-fps 5 --system rigid --no-figures
expect_status 0 "run --animate --no-figures"
expect_absent "$WORK/plain/animation_system1.gif" "no GIF with --no-figures"
checks=$((checks + 1))
[ -f "$WORK/plain/animation_system1.pvd" ] || fail "the .pvd with --no-figures"

# Bad settings: usage errors (exit 1) before anything runs.
for args in "--animate-fps 20" "--animate --animate-fps 0" "--animate --animate-fps 2000" \
  "--animate --animate-fps x" "--animate --animate-scale -1" "--animate-scale 2"; do
  # shellcheck disable=SC2086 # the settings are words
  run run "$SHORT" -o "$WORK/bad" -q $args
  expect_status 1 "run $args"
  expect_absent "$WORK/bad" "run $args writes nothing"
done

# Too many frames is an input error found before anything is simulated: at
# 1 km/h the bump window runs from 5 s to 36.3 s, 31321 frames at 1000 frames/s.
sed -e 's/^  speed_kmh: 10 /  speed_kmh: 1 /' -e 's/^  t_end: 15 /  t_end: 40 /' \
  "$REPO_ROOT/examples/apc6x6.yaml" >"$WORK/slow.yaml"
run run "$WORK/slow.yaml" -o "$WORK/many" --animate --animate-fps 1000
expect_status 2 "run --animate-fps 1000 over 31 s"
expect_in "$ERR" "frames, not 1..10000" "the frame count refused"
checks=$((checks + 1))
! grep -q "simulating" "$ERR" || fail "too many frames refused only after simulating"
expect_absent "$WORK/many" "too many frames writes nothing"

echo "$NAME: $checks checks, $failures failed" >&2
[ "$failures" -eq 0 ]
