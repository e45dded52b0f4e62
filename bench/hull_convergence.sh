#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Mesh convergence of the reference hull's free-free modes
# (docs/hull-mesh.md, "Convergence"): `flexbond modes --system flexible`
# of examples/apc6x6.yaml at hull.mesh.density 1 .. DMAX (default 6), the
# first ten elastic modes (hull modes 7 .. 16) of each, then per mode:
#   - the observed order of convergence p from densities 1, 2 and 4
#     (element size halved twice): p = log2((f1 - f2) / (f2 - f4));
#   - a Richardson estimate of the converged frequency from the two finest
#     densities d1 < d2 and order 2: f_inf = f2 + (f2 - f1) / ((d2/d1)^2 - 1);
#   - each density's error against f_inf, in per cent.
# Modes are matched by rank (sorted frequency); a pair that crosses
# between densities shows as a jump in its two rows.
# Writes BUILD_DIR/hull_convergence/convergence.csv and prints a Markdown
# table. Needs the build and /usr/bin/python3 (no modules).
#
# usage: bench/hull_convergence.sh [BUILD_DIR] [DMAX]   (from the repository root)
set -euo pipefail
build=${1:-build}
dmax=${2:-6}
out=$build/hull_convergence
exe=$build/flexbond
[ -x "$exe" ] || { echo "hull_convergence: no $exe (build first)" >&2; exit 1; }
[ "$dmax" -ge 4 ] || { echo "hull_convergence: DMAX must be at least 4" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
for d in $(seq 1 "$dmax"); do
  sed "s/^\(    density: \)1 /\1$d /" examples/apc6x6.yaml >"$out/apc6x6_d$d.yaml"
  grep -q "^    density: $d " "$out/apc6x6_d$d.yaml" ||
    { echo "hull_convergence: cannot set the density" >&2; exit 1; }
  start=$(date +%s.%N)
  "$exe" modes "$out/apc6x6_d$d.yaml" --system flexible >"$out/modes_d$d.txt"
  end=$(date +%s.%N)
  echo "density $d: $(head -n 1 "$out/modes_d$d.txt" | sed 's/^[^(]*(//; s/).*//'), \
$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s" >&2
done
/usr/bin/python3 - "$out" "$dmax" <<'EOF'
import math, re, sys
out, dmax = sys.argv[1], int(sys.argv[2])
freq = {}
for d in range(1, dmax + 1):
    with open(f"{out}/modes_d{d}.txt") as fp:
        text = fp.read()
    found = [float(f) for m, f in re.findall(r"hull mode +(\d+) +([0-9.]+) Hz", text)]
    if len(found) < 10:
        sys.exit(f"hull_convergence: density {d}: {len(found)} hull modes listed, not 10")
    freq[d] = found[:10]
d1, d2 = dmax // 2, dmax
rows = []
for k in range(10):
    f = [freq[d][k] for d in range(1, dmax + 1)]
    a, b, c = freq[1][k], freq[2][k], freq[4][k]
    p = math.log2((a - b) / (b - c)) if (a - b) * (b - c) > 0 else float("nan")
    finf = freq[d2][k] + (freq[d2][k] - freq[d1][k]) / ((d2 / d1) ** 2 - 1)
    rows.append((k + 7, f, p, finf))
with open(f"{out}/convergence.csv", "w") as fp:
    fp.write("mode," + ",".join(f"density_{d}_hz" for d in range(1, dmax + 1))
             + ",order_p,richardson_hz\n")
    for mode, f, p, finf in rows:
        fp.write(f"{mode}," + ",".join(f"{x:.6f}" for x in f) + f",{p:.3f},{finf:.6f}\n")
head = "| mode | " + " | ".join(f"d = {d}" for d in range(1, dmax + 1)) + " | order p | converged |"
print(head)
print("|" + "---|" * (dmax + 3))
for mode, f, p, finf in rows:
    cells = [f"{x:.3f} ({100 * (x / finf - 1):+.2f} %)" for x in f]
    print(f"| {mode} | " + " | ".join(cells) + f" | {p:.2f} | {finf:.3f} |")
print(f"\nconverged: Richardson from densities {d1} and {d2}, order 2; "
      f"wrote {out}/convergence.csv")
EOF
