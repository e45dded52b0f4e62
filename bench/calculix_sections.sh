#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Plates of several thicknesses, CalculiX against flexbond
# (docs/hull-mesh.md, "Sections"): the reference hull exported at
# hull.mesh.density 1 and 2, its floor and its other plates given their
# own *SHELL SECTION (8.5 mm everywhere, a 20 mm floor, 20 mm everywhere),
# each deck's first four elastic free-free modes from `ccx`
# (bench/calculix_modes.py, quadratic shells) and from `flexbond modes`,
# in order of frequency (not matched by shape). Needs ccx (Debian:
# calculix-ccx) and /usr/bin/python3; about 15 s.
#
# usage: bench/calculix_sections.sh [BUILD_DIR]   (from the repository root)
set -euo pipefail
build=${1:-build}
out=$build/calculix_sections
exe=$build/flexbond
command -v ccx >/dev/null || { echo "calculix_sections: no ccx (apt-get install calculix-ccx)" >&2; exit 1; }
[ -x "$exe" ] || { echo "calculix_sections: no $exe (build first)" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
echo "| density | floor | other plates | ccx modes 7-10 [Hz] | flexbond [Hz] | flexbond / ccx - 1 |"
echo "|---|---|---|---|---|---|"
for d in 1 2; do
  sed "s/^\(    density: \)1 /\1$d /" examples/apc6x6.yaml >"$out/d$d.yaml"
  "$exe" mesh "$out/d$d.yaml" --export "$out/flat_d$d.inp" >/dev/null
  for plates in "0.0085 0.0085" "0.020 0.0085" "0.020 0.020"; do
    set -- $plates
    name=d${d}_$1_$2
    /usr/bin/python3 - "$out/flat_d$d.inp" "$out/$name.inp" "$1" "$2" <<'PY'
import sys
src, dst, floor, other = sys.argv[1:]
s = open(src).read()
s = s[:s.index("*MATERIAL")]
s += "*MATERIAL, NAME=STEEL\n*ELASTIC\n200e9, 0.3\n*DENSITY\n7860\n"
s += f"*SHELL SECTION, ELSET=FLOOR, MATERIAL=STEEL\n{floor}\n"
for plate in ["ROOF", "SIDES", "REAR_WALL", "GLACIS", "BULKHEADS"]:
    s += f"*SHELL SECTION, ELSET={plate}, MATERIAL=STEEL\n{other}\n"
open(dst, "w").write(s)
PY
    # The deck's mass and inertias are its own: the example's typed ones go.
    sed -e "/^    density: $d /d" -e "/^    generator:/,/nose_rung_divisions/c\\    deck: $name.inp" \
      -e '/^  mass: 4041.72/d' -e '/^  Ixx: /d' -e '/^  Iyy: /d' "$out/d$d.yaml" >"$out/$name.yaml"
    ccx_hz=$(/usr/bin/python3 bench/calculix_modes.py "$out/$name.inp" "$out/ccx_$name" 12 | head -4)
    fb_hz=$("$exe" modes "$out/$name.yaml" --system flexible | sed -n 2,5p | awk '{print $4}')
    /usr/bin/python3 - "$d" "$1" "$2" "$ccx_hz" "$fb_hz" <<'PY'
import sys
d, floor, other = sys.argv[1:4]
c = [float(v) for v in sys.argv[4].split()]
f = [float(v) for v in sys.argv[5].split()]
rel = " ".join(f"{100 * (b / a - 1):+.1f} %" for a, b in zip(c, f))
print(f"| {d} | {1000 * float(floor):g} mm | {1000 * float(other):g} mm | "
      f"{' '.join(f'{v:.2f}' for v in c)} | {' '.join(f'{v:.2f}' for v in f)} | {rel} |")
PY
  done
done
