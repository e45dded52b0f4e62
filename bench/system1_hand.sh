#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# System 1 of examples/apc6x6.yaml: flexbond against the same model written
# by hand on CVODE (bench/system1_hand.c). Checks that both give the same
# outputs, then times them (bench/README.md):
#   - the solver: flexbond's fb_sim_run (summary.json "wall_seconds") and
#     the hand program's same part (CVODE set-up, integration, outputs at
#     the 15001 samples), one run per process, and warm: the median of 21
#     runs in one process (bench_vehicle, system1_hand --repeat 21), also
#     as the thread's CPU time (flexbond's: fb_vehicle_simulate, which adds
#     the block diagram's build, about 1 % of it);
#   - the whole process (wall, user + sys, peak RSS, as /usr/bin/time -v reports them but
#     to the microsecond: bench/proctime.py):
#     `flexbond run examples/apc6x6.yaml --system rigid --no-figures` and
#     `system1_hand -o system1.csv`.
# Each timing is the median of RUNS (default 5) runs, the two programs
# alternating, each run after the machine has been idle for a moment
# (bench/quiet.py), all on one CPU (taskset; BENCH_CPU, default the last
# one): other work on a shared machine disturbs these timings, and on this
# project's machine the two CPUs run the same code at speeds up to 1.4x
# apart. Pinned, OpenBLAS starts no worker thread; one more series runs
# flexbond unpinned, as a user runs it, to show that thread's cost.
#
# usage: bench/system1_hand.sh [BUILD_DIR] [RUNS]   (from the repository root)
set -euo pipefail

build=${1:-build}
runs=${2:-5}
out=$build/hand_vs_flexbond
py=/usr/bin/python3
cmake -S . -B "$build" -DFLEXBOND_BENCH_HAND=ON >/dev/null
cmake --build "$build" -j2 --target flexbond_cli system1_hand bench_vehicle >/dev/null
exe=$build/flexbond
hand=$build/system1_hand
rm -rf "$out"
mkdir -p "$out/flexbond"

echo "== agreement: max |hand - flexbond| / range(flexbond) per column"
"$exe" run examples/apc6x6.yaml --system rigid --no-figures --plain-header -o "$out/flexbond" -q
"$hand" -o "$out/hand.csv" 2>&1 | sed 's/^/  /'
"$py" - "$out/flexbond/system1.csv" "$out/hand.csv" <<'EOF'
import sys, numpy as np
a = np.genfromtxt(sys.argv[1], delimiter=",", names=True)
b = np.genfromtxt(sys.argv[2], delimiter=",", names=True)
for n in a.dtype.names[1:]:
    span = a[n].max() - a[n].min()
    d = np.abs(a[n] - b[n]).max()
    print("  %-16s range %-11.5g max diff %-10.3g relative %s"
          % (n, span, d, "%.2g" % (d / span) if span > 0 else "- (identically %g)" % a[n][0]))
EOF
"$py" -c 'import json,sys; s=json.load(open(sys.argv[1]))["system1"]["solver"]; print("  flexbond: %d steps, %d rhs evals, %d Newton setups, %d Newton iterations, %d error test failures" % (s["steps"], s["rhs_evals"], s["newton_setups"], s["newton_iters"], s["err_test_fails"]))' \
  "$out/flexbond/summary.json"

# time_v FILE CMD...: appends "wall cpu rss_kb" of one run to FILE (bench/proctime.py; the
# command's stderr in $out/time.txt).
# Each run waits first for the machine to be idle (bench/quiet.py, at most 20 s).
time_v() {
  local file=$1
  shift
  "$py" bench/quiet.py 20
  "$py" bench/proctime.py "$out/time.txt" "${pin[@]}" "$@" >>"$file"
}

: >"$out/fb_proc"
: >"$out/fb1_proc"
: >"$out/hand_proc"
: >"$out/fb_solver"
: >"$out/hand_solver"
cpu=${BENCH_CPU:-$(($(nproc) - 1))}
pin=(taskset -c "$cpu")
for ((i = 0; i < runs; ++i)); do
  time_v "$out/fb_proc" "$exe" run examples/apc6x6.yaml --system rigid --no-figures \
    -o "$out/flexbond" -q
  "$py" -c 'import json,sys; print(json.load(open(sys.argv[1]))["system1"]["solver"]["wall_seconds"])' \
    "$out/flexbond/summary.json" >>"$out/fb_solver"
  time_v "$out/hand_proc" "$hand" -o "$out/hand.csv"
  grep -o 'solver [0-9.]* ms' "$out/time.txt" | awk '{print $2 / 1000}' >>"$out/hand_solver"
  pin=()
  time_v "$out/fb1_proc" "$exe" run examples/apc6x6.yaml --system rigid --no-figures \
    -o "$out/flexbond" -q
  pin=(taskset -c "$cpu")
done
"$py" bench/quiet.py 20
"${pin[@]}" "$build/bench_vehicle" examples/apc6x6.yaml 21 rigid >"$out/fb_warm.txt"
sed -n 's/.*(integration \([0-9.]*\) ms.*/\1/p' "$out/fb_warm.txt" | awk '{print $1 / 1000}' \
  >"$out/fb_warm"
sed -n 's/.*cpu \([0-9.]*\) ms).*/\1/p' "$out/fb_warm.txt" | awk '{print $1 / 1000}' \
  >"$out/fb_warm_cpu"
"$py" bench/quiet.py 20
"${pin[@]}" "$hand" --repeat 21 2>"$out/hand_warm.txt"
sed -n 's/^run .*solver \([0-9.]*\) ms.*/\1/p' "$out/hand_warm.txt" | awk '{print $1 / 1000}' \
  >"$out/hand_warm"
sed -n 's/^run .*cpu \([0-9.]*\) ms.*/\1/p' "$out/hand_warm.txt" | awk '{print $1 / 1000}' \
  >"$out/hand_warm_cpu"
rss() { /usr/bin/time -v "$@" 2>&1 >/dev/null | awk -F': ' '/Maximum resident/ {print $2 / 1000}'; }
fb_rss=$(rss "$exe" run examples/apc6x6.yaml --system rigid --no-figures -o "$out/flexbond" -q)
hand_rss=$(rss "$hand" -o "$out/hand.csv")

"$py" - "$out" "$runs" "$cpu" <<'EOF'
import sys, statistics as st
out, runs = sys.argv[1], sys.argv[2]
def col(name, k=0):
    return [float(l.split()[k]) for l in open(f"{out}/{name}") if l.strip()]
def line(what, fb, hand):
    f, h = st.median(fb), st.median(hand)
    print("  %-38s flexbond %7.2f ms (min %7.2f)  hand %7.2f ms (min %7.2f)  ratio %.2f (minima %.2f)"
          % (what, 1e3 * f, 1e3 * min(fb), 1e3 * h, 1e3 * min(hand), f / h, min(fb) / min(hand)))
print(f"== timings on CPU {sys.argv[3]}: median of {runs} runs, the programs alternating (warm: of 21 runs in one process)")
line("solver, one run per process", col("fb_solver"), col("hand_solver"))
line("solver, warm", col("fb_warm"), col("hand_warm"))
line("solver, warm, thread CPU time", col("fb_warm_cpu"), col("hand_warm_cpu"))
line("whole process, wall", col("fb_proc", 0), col("hand_proc", 0))
line("whole process, user + sys", col("fb_proc", 1), col("hand_proc", 1))
line("flexbond not pinned: wall", col("fb1_proc", 0), col("hand_proc", 0))
line("flexbond not pinned: user + sys", col("fb1_proc", 1), col("hand_proc", 1))
EOF
echo "  peak RSS (/usr/bin/time -v): flexbond $fb_rss MB, hand $hand_rss MB"
echo "  (load average after timing: $(cut -d' ' -f1-3 /proc/loadavg))"
