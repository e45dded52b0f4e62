#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The reference hull's free-free modes by CalculiX, against flexbond's
# convergence table (docs/hull-mesh.md, "Convergence"): the decks
# `flexbond mesh --export` writes at hull.mesh.density 2, 3 and 4, each
# turned into quadratic shells of the same geometry and solved by `ccx`
# (bench/calculix_modes.py), then per mode the observed order p of the
# three (element size 1/2, 1/3, 1/4) and the extrapolated limit
# f4 - (f3 - f4) / ((4/3)^p - 1). With BUILD_DIR/hull_convergence/
# convergence.csv from bench/hull_convergence.sh, flexbond's Richardson
# limit is printed beside it. Needs ccx (Debian: calculix-ccx) and
# /usr/bin/python3; about 70 s and 600 MB.
#
# usage: bench/calculix_modes.sh [BUILD_DIR]   (from the repository root)
set -euo pipefail
build=${1:-build}
out=$build/calculix_modes
exe=$build/flexbond
command -v ccx >/dev/null || { echo "calculix_modes: no ccx (apt-get install calculix-ccx)" >&2; exit 1; }
[ -x "$exe" ] || { echo "calculix_modes: no $exe (build first)" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
for d in 2 3 4; do
  sed "s/^\(    density: \)1 /\1$d /" examples/apc6x6.yaml >"$out/apc6x6_d$d.yaml"
  "$exe" mesh "$out/apc6x6_d$d.yaml" --export "$out/hull_d$d.inp" >/dev/null
  /usr/bin/python3 bench/calculix_modes.py "$out/hull_d$d.inp" "$out/ccx_d$d" 16 \
    >"$out/freq_d$d.txt"
  echo "density $d: $(wc -l <"$out/freq_d$d.txt") elastic modes from ccx" >&2
done
/usr/bin/python3 - "$out" "$build/hull_convergence/convergence.csv" <<'EOF'
import csv, math, os, sys
out, flexbond_csv = sys.argv[1], sys.argv[2]
f = {d: [float(x) for x in open(f"{out}/freq_d{d}.txt")] for d in (2, 3, 4)}
limits = {}
if os.path.exists(flexbond_csv):
    for row in csv.DictReader(open(flexbond_csv)):
        limits[int(row["mode"])] = float(row["richardson_hz"])


def order(a, b, c):
    """p with (a - b) / (b - c) = (2^-p - 3^-p) / (3^-p - 4^-p), by bisection."""
    target = (a - b) / (b - c)
    g = lambda p: (2 ** -p - 3 ** -p) / (3 ** -p - 4 ** -p) - target
    lo, hi = 0.5, 8.0
    if g(lo) * g(hi) > 0:
        return float("nan")
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
    return (lo + hi) / 2


print("| mode | ccx d = 2 | d = 3 | d = 4 | order p | ccx limit | flexbond limit | difference |")
print("|---|---|---|---|---|---|---|---|")
with open(f"{out}/calculix.csv", "w") as fp:
    fp.write("mode,ccx_d2_hz,ccx_d3_hz,ccx_d4_hz,order_p,ccx_limit_hz,flexbond_limit_hz\n")
    for k in range(min(10, *(len(v) for v in f.values()))):
        a, b, c = f[2][k], f[3][k], f[4][k]
        p = order(a, b, c) if (a - b) * (b - c) > 0 else float("nan")
        lim = c - (b - c) / ((4 / 3) ** p - 1) if p == p else c
        mode = k + 7
        ref = limits.get(mode)
        diff = f"{100 * (lim / ref - 1):+.2f} %" if ref else "-"
        print(f"| {mode} | {a:.3f} | {b:.3f} | {c:.3f} | {p:.2f} | {lim:.3f} | "
              f"{ref:.3f} | {diff} |" if ref else
              f"| {mode} | {a:.3f} | {b:.3f} | {c:.3f} | {p:.2f} | {lim:.3f} | - | - |")
        fp.write(f"{mode},{a},{b},{c},{p:.3f},{lim:.6f},{ref if ref else ''}\n")
print(f"\nwrote {out}/calculix.csv")
EOF
