#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Work-precision study of the finite-element hull's reduced basis
# (bench/basis_choice.c says what is measured and how): free-free modes
# alone, modes plus the static correction, load-dependent Ritz vectors (the
# library's choice) and Craig-Bampton, on examples/apc6x6.yaml at
# hull.mesh.density 1 and 2. Builds build/basis_choice, runs it, and writes
# into OUT_DIR:
#   basis_choice.csv  method,density,coordinates,error,build_seconds
#   basis_choice.png  error against coordinates, log-log, a panel per
#                     density, the library's basis and the modes up to
#                     3 x f_exc with static correction marked
# and prints, per method and density, the fewest coordinates that reach
# an error of 1e-3 and of 1e-4.
#
# usage: bench/basis_choice.sh [OUT_DIR]   (from the repository root;
#   default /tmp/basis_choice). Environment: BUILD_DIR (default build,
#   configured already), SCENARIO (default examples/apc6x6.yaml), F_EXC
#   (Hz, default auto: the library's rule), DENSITIES (default "1 2").
# Needs the build's packages and gnuplot. About 40 s on 2 cores, most of
# it the dense eigen-solve of every mode at density 2 (5274 DOFs).
set -euo pipefail
out=${1:-/tmp/basis_choice}
build=${BUILD_DIR:-build}
scenario=${SCENARIO:-examples/apc6x6.yaml}
fexc=${F_EXC:-auto}
read -r -a densities <<<"${DENSITIES:-1 2}"
[ -f "$build/CMakeCache.txt" ] || { echo "basis_choice: no configured build in $build" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "basis_choice: needs gnuplot" >&2; exit 1; }
mkdir -p "$out"
csv=$out/basis_choice.csv

echo "basis_choice: building $build/basis_choice" >&2
# Configuring again lets the build's glob of bench/*.c see this program.
cmake "$build" >/dev/null
cmake --build "$build" -j4 --target basis_choice >/dev/null

echo "basis_choice: running $scenario at densities ${densities[*]}" >&2
start=$(date +%s.%N)
"$build/basis_choice" "$scenario" "$fexc" "${densities[@]}" >"$csv"
end=$(date +%s.%N)
seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')

# One block per method (a gnuplot index), in increasing coordinates, per
# density; the two markers as blocks of their own.
plots=()
for d in "${densities[@]}"; do
  dat=$out/density_$d.dat
  for m in modes modes_static ritz craig_bampton library modes_3fexc; do
    title=$m
    case $m in
      modes) title="modes alone" ;;
      modes_static) title="modes + static correction" ;;
      ritz) title="load-dependent Ritz vectors" ;;
      craig_bampton) title="Craig-Bampton" ;;
      library) title="the library's basis (Ritz blocks by its tolerance)" ;;
      modes_3fexc) title="modes up to 3 f_exc + static correction" ;;
    esac
    echo "\"$title\""
    awk -F, -v m="$m" -v d="$d" 'NR > 1 && $1 == m && $2 == d { print $3, $4 }' "$csv" | sort -n
    printf '\n\n'
  done >"$dat"
  plots+=("$d")
done

png=$out/basis_choice.png
echo "basis_choice: plotting $png" >&2
{
  cat <<EOF
set terminal pngcairo size $((620 * ${#plots[@]})),700 font ",11"
set output "$png"
set multiplot layout 1,${#plots[@]} title "$(basename "$scenario"): the hull's receptance over 0.25 Hz .. f_{exc}, B = {/Symbol b} K"
set logscale xy
set format y "10^{%T}"
set xrange [9:200]
set xtics (10, 20, 30, 50, 100, 200)
set yrange [1e-8:1e2]
set xlabel "coordinates of the hull"
set ylabel "max over entries and frequencies of |H - H_{ref}| / max |H_{ref}|"
set grid
set key below horizontal maxcols 2 Left reverse noenhanced width -6
set bmargin 10
set linetype 1 lc rgb "#7f7f7f" pt 6
set linetype 2 lc rgb "#1f77b4" pt 7
set linetype 3 lc rgb "#2ca02c" pt 5
set linetype 4 lc rgb "#d62728" pt 9
EOF
  for d in "${plots[@]}"; do
    cat <<EOF
set title "hull.mesh.density $d"
plot for [i=0:3] "$out/density_$d.dat" index i using 1:2 with linespoints lt i+1 lw 2 ps 1.2 title columnheader(1), \\
     "$out/density_$d.dat" index 4 using 1:2 with points pt 3 ps 4 lw 3 lc rgb "black" title columnheader(1), \\
     "$out/density_$d.dat" index 5 using 1:2 with points pt 2 ps 3 lw 3 lc rgb "#1f77b4" title columnheader(1), \\
     1e-3 with lines dt 2 lc rgb "black" notitle, 1e-4 with lines dt 3 lc rgb "black" notitle
EOF
  done
  echo "unset multiplot"
} | gnuplot

# The fewest coordinates that reach each error (a basis reaches it when its
# error and that of every larger basis of the method are at or below it).
echo "fewest coordinates reaching an error (run ${seconds} s):"
printf '%-14s %8s %10s %10s\n' method density "<= 1e-3" "<= 1e-4"
awk -F, 'NR > 1 && $1 != "library" && $1 != "modes_3fexc" { print $1, $2, $3, $4 }' "$csv" | sort -k1,1 -k2,2n -k3,3nr |
  awk '
    function flush() {
      if (key != "")
        printf "%-14s %8s %10s %10s\n", m, d, (r3 ? r3 : "-"), (r4 ? r4 : "-")
    }
    { k = $1 " " $2
      if (k != key) { flush(); key = k; m = $1; d = $2; ok3 = ok4 = 1; r3 = r4 = "" }
      ok3 = ok3 && $4 <= 1e-3; ok4 = ok4 && $4 <= 1e-4
      if (ok3) r3 = $3
      if (ok4) r4 = $3 }
    END { flush() }'
awk -F, 'NR > 1 && ($1 == "library" || $1 == "modes_3fexc") { printf "%s at density %s: %s coordinates, error %.3g\n", $1, $2, $3, $4 }' "$csv"
echo "basis_choice: wrote $csv and $png"
