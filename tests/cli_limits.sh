#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The limits of docs/errors.md ("Limits") through the real flexbond command:
# inputs that would make it read, allocate or compute without end are
# refused up front, with the exit status, the file:line:col and key of the
# value at fault (or the file and the bound), and nothing written.
#
# Every case runs under a guard, so that the behaviour these limits
# replaced fails fast instead of taking the machine: `ulimit -v` (1 GB of
# address space: a run that would allocate gigabytes fails to, and exits 6
# instead of 2 or 5), `ulimit -t` (CPU seconds: a run that would take hours
# is killed) and `timeout` (a FIFO that would block the reader).
#
# usage: bash tests/cli_limits.sh PATH/TO/flexbond REPO_ROOT
set -u
NAME=cli_limits
# shellcheck source=clilib.sh
. "$(dirname "${BASH_SOURCE[0]}")/clilib.sh"

EX=$REPO_ROOT/examples
IN=$WORK/in
mkdir -p "$IN" || exit 2
cd "$IN" || exit 2

# guarded ARGS...: run under the guards described above.
# An AddressSanitizer build reserves terabytes of address space for its
# shadow memory at start: there the memory guard is its own allocator's
# (ASan fails a huge allocation loudly, which the test sees), not ulimit -v.
if grep -q __asan_init "$FLEXBOND"; then
  MEMORY_GUARD=unlimited
else
  MEMORY_GUARD=1000000
fi
guarded() {
  (
    ulimit -v "$MEMORY_GUARD"
    ulimit -t 30
    exec timeout 60 "$FLEXBOND" "$@"
  ) >"$OUT" 2>"$ERR"
  status=$?
}

# refused STATUS MESSAGE DESCRIPTION ARGS...: flexbond ARGS, guarded, exits
# with STATUS, says MESSAGE on stderr and leaves its -o directory, if any,
# uncreated (a sweep's --output directory keeps its sweep.csv, checked
# apart).
refused() {
  local want=$1 message=$2 what=$3 prev="" arg
  shift 3
  guarded "$@"
  expect_status "$want" "$what"
  expect_in "$ERR" "$message" "$what"
  for arg in "$@"; do
    [ "$prev" = -o ] && expect_absent "$arg" "$what"
    prev=$arg
  done
}

# where FILE TEXT VALUE: "FILE:LINE:COL:" of VALUE in the first line of FILE
# that holds TEXT.
where() {
  local n text before
  n=$(grep -nF -m1 -- "$2" "$1" | cut -d: -f1)
  text=$(sed -n "${n:-0}p" "$1")
  before=${text%%"$3"*}
  echo "$1:${n:-NOT-FOUND}:$((${#before} + 1)):"
}

# edited NEW FROM SED-ARGS...: NEW is FROM edited by sed, which must change it.
edited() {
  local new=$1 from=$2
  shift 2
  sed "$@" "$from" >"$new"
  checks=$((checks + 1))
  ! cmp -s "$new" "$from" || fail "fixture $new: sed $* changed nothing"
}

cp "$EX/apc6x6.yaml" "$EX/apc6x6_shock_table.yaml" "$EX/apc6x6_iso_road.yaml" \
  "$EX/shock_front.csv" "$EX/shock_rear.csv" "$EX/quarter_car.yaml" \
  "$EX/two_dof_fields.yaml" . || exit 2
# 300 MB that take no disk: beyond the 256 MiB an input file may hold.
truncate -s 300M big.csv big.yaml big.inp || exit 2
mkfifo fifo.csv || exit 2
LIMIT="314.6 MB, more than the 256 MiB an input file may hold"

# ---- Input files: the size bound of the one checked reader.
edited s_bigtable.yaml apc6x6_shock_table.yaml -e '0,/file: shock_front.csv/s//file: big.csv/'
refused 5 "$(where s_bigtable.yaml 'file: big.csv' big.csv) suspensions.axles[0].damper_table.file: ./big.csv: cannot read: $LIMIT" \
  "a 300 MB damper table" run s_bigtable.yaml -o out_table --system rigid

refused 5 "big.yaml: cannot read: $LIMIT" "a 300 MB scenario" run big.yaml -o out_scenario

edited s_bigdeck.yaml apc6x6.yaml -e 's/^    generator:.*/    deck: big.inp/' \
  -e '/^    density: 1 /d' -e '/^    deck: big.inp/,/^ \{0,4\}[a-z]/{/^      /d}'
refused 5 "$(where s_bigdeck.yaml 'deck: big.inp' big.inp) hull.mesh.deck: ./big.inp: cannot read: $LIMIT" \
  "a 300 MB deck" mesh s_bigdeck.yaml

# The sweep's fingerprint hashes every file the study reads: /dev/zero
# once grew it to gigabytes, a FIFO blocked it. Now both are refused as
# the cases' reader refuses them, and the cases fail with its message.
at_table=$(where apc6x6_shock_table.yaml '{file: shock_front.csv' shock_front.csv)
refused 4 "$at_table suspensions.axles[0].damper_table.file: /dev/zero: cannot read: not a regular file" \
  "a sweep over /dev/zero and a FIFO" sweep apc6x6_shock_table.yaml -q --no-figures \
  --set suspensions.axles[0].damper_table.file=/dev/zero,fifo.csv --output out_sweep
expect_in out_sweep/sweep.csv "$at_table suspensions.axles[0].damper_table.file: ./fifo.csv: cannot read: not a regular file" "a sweep over a FIFO"
expect_absent out_sweep/sweep.partial.csv "a sweep over /dev/zero and a FIFO"

# A journal of 300 MB is refused on --resume before it is allocated, and
# kept.
mkdir out_resume && truncate -s 300M out_resume/sweep.partial.csv
refused 5 "out_resume/sweep.partial.csv: cannot read: $LIMIT" "a 300 MB journal" \
  sweep apc6x6.yaml -q --no-figures --resume --set road.speed_kmh=10 --output out_resume
checks=$((checks + 1))
[ "$(stat -c %s out_resume/sweep.partial.csv)" -eq 314572800 ] || fail "a 300 MB journal: not kept"
expect_absent out_resume/sweep.csv "a 300 MB journal"

# ---- A Matrix Market header that declares 2e8 x 2e8 in a few bytes once
# allocated 3.2 GB; a model's matrix law reads it.
printf '%%%%MatrixMarket matrix coordinate real general\n200000000 200000000 1\n1 1 1\n' >huge.mtx
edited m_mtx.yaml two_dof_fields.yaml -e '/# stiffness K, N\/m/{N;N;s/.*/    matrix: {mtx: huge.mtx}/}'
refused 2 "huge.mtx:2: 200000000 rows, more than the 1000000 a Matrix Market file may declare" \
  "a huge Matrix Market header" sim m_mtx.yaml -o out_mtx
expect_in "$ERR" "$(where m_mtx.yaml huge.mtx huge.mtx)" "a huge Matrix Market header"

# ---- A dense eigen-solve beyond FB_DENSE_EIG_MAX (3000) states is refused before anything is
# allocated: its time grows as n^3 and nothing could interrupt it (eig of a model of two
# 1600-dimensional fields: 3200 states).
{
  printf '%%%%MatrixMarket matrix coordinate real general\n1600 1600 1600\n'
  for i in $(seq 1 1600); do echo "$i $i 1"; done
} >diag1600.mtx
cat >m_dense.yaml <<'EOF'
model: big_fields
elements:
  - {name: M, type: I, matrix: {mtx: diag1600.mtx}}
  - {name: K, type: C, matrix: {mtx: diag1600.mtx}}
  - {name: J, type: 1, dim: 1600}
bonds:
  - {name: b_m, from: J, to: M}
  - {name: b_k, from: J, to: K}
EOF
refused 6 "eig: big_fields (3200 states): a dense eigen-solve of order 3200, more than the 3000 it may take" \
  "a dense eigen-solve of 3200 states" eig m_dense.yaml

# ---- Results and meshes that would not fit in memory.
edited s_rate.yaml apc6x6.yaml -e 's/^  sample_rate: 1000 /  sample_rate: 6.6e6/'
refused 2 "$(where s_rate.yaml 'sample_rate: 6.6e6' 6.6e6) simulation.sample_rate: 6.6e+06 Hz over 15 s gives 9.9e+07 samples of 14 columns, which would need about 11.1 GB" \
  "sample_rate 6.6e6" run s_rate.yaml -o out_rate --system rigid

# The model's 5 probes and t: 9.5e7 samples of 6 columns, 4.6 GB; the option
# that raised it is named (a usage error).
refused 1 "flexbond sim: option '--sample-rate': 1.9e+07 Hz over 5 s gives 9.5e+07 samples of 6 columns, which would need about 4.6 GB" \
  "--sample-rate 1.9e7" sim quarter_car.yaml -o out_sim_rate --sample-rate 1.9e7

# max_steps itself is bounded, or a huge one would let any max_step through.
edited s_maxsteps.yaml apc6x6.yaml -e 's/^  t_end: 15 .*/  t_end: 15\n  max_steps: 1000000000000/'
refused 2 "$(where s_maxsteps.yaml 'max_steps: 1000000000000' 1000000000000) simulation.max_steps: must be an integer from 1 to 1000000000" \
  "max_steps 1e12" run s_maxsteps.yaml -o out_maxsteps --system rigid

edited s_dense.yaml apc6x6.yaml -e 's/^    density: 1 /    density: 64 /'
refused 2 "$(where s_dense.yaml 'density: 64' 64) hull.mesh.density: 64 refines the generated mesh's 240 elements into 983040, which would need about 64.4 GB" \
  "hull density 64" mesh s_dense.yaml
# Density 4 (3840 elements, 0.2 GB) is well within the bound.
edited s_dense4.yaml apc6x6.yaml -e 's/^    density: 1 /    density: 4 /'
guarded mesh s_dense4.yaml
expect_status 0 "hull density 4"
expect_in "$OUT" "3392 S4 elements" "hull density 4"

# The same bound for a hull read from a file, deck or gmsh mesh, after it is
# read, at the key that names the file: a 452 x 256 grid of quadrilaterals,
# 115712 elements, such as once took 2.7 GB and 400 s of System 2.
awk -v nx=452 -v ny=256 'BEGIN {
  print "*NODE"
  for (j = 0; j <= ny; j++)
    for (i = 0; i <= nx; i++) printf "%d, %g, %g, 0\n", j * (nx + 1) + i + 1, 0.01 * i, 0.01 * j
  print "*ELEMENT, TYPE=S4"
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      a = j * (nx + 1) + i + 1
      printf "%d, %d, %d, %d, %d\n", j * nx + i + 1, a, a + 1, a + nx + 2, a + nx + 1
    }
}' >huge.inp || exit 2
awk -v nx=452 -v ny=256 'BEGIN {
  n = (nx + 1) * (ny + 1); e = nx * ny
  print "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes"
  print 1, n, 1, n; print 2, 1, 0, n
  for (k = 1; k <= n; k++) print k
  for (j = 0; j <= ny; j++) for (i = 0; i <= nx; i++) print 0.01 * i, 0.01 * j, 0
  print "$EndNodes\n$Elements"; print 1, e, 1, e; print 2, 1, 3, e
  for (j = 0; j < ny; j++)
    for (i = 0; i < nx; i++) {
      a = j * (nx + 1) + i + 1
      print j * nx + i + 1, a, a + 1, a + nx + 2, a + nx + 1
    }
  print "$EndElements"
}' >huge.msh || exit 2
HUGE="the mesh has 115712 elements, which would need about 7.6 GB of memory for System 2 (about 64 KiB per element), more than the 4.3 GB allowed (at most 65536 elements; docs/hull-mesh.md, \"Limits\")"
for ext in inp msh; do
  edited "s_huge$ext.yaml" apc6x6.yaml -e "s/^    generator:.*/    deck: huge.$ext/" \
    -e '/^    density: 1 /d' -e "/^    deck: huge.$ext/,/^ \{0,4\}[a-z]/{/^      /d}"
done
refused 2 "$(where s_hugeinp.yaml 'deck: huge.inp' huge.inp) hull.mesh.deck: ./huge.inp: $HUGE" \
  "a deck of 115712 elements" run s_hugeinp.yaml -o out_hugeinp --system flexible --no-figures
refused 2 "$(where s_hugemsh.yaml 'deck: huge.msh' huge.msh) hull.mesh.deck: ./huge.msh: $HUGE" \
  "a gmsh mesh of 115712 elements" mesh s_hugemsh.yaml

# ---- Runs that cannot finish, or only after hours.
edited s_step.yaml apc6x6.yaml -e 's/^  max_step: 0 /  max_step: 1e-6/'
refused 2 "$(where s_step.yaml 'max_step: 1e-6' 1e-6) simulation.max_step: 1e-06 s over the run's 15 s (t_end - t_start) needs at least 1.5e+07 steps, more than max_steps = 10000000: the run could not finish; raise max_step or max_steps" \
  "max_step 1e-6 over 15 s" run s_step.yaml -o out_step --system rigid

edited s_harm.yaml apc6x6_iso_road.yaml -e 's/^  iso8608:/  iso8608:\n    harmonics: 1000000/'
refused 2 "$(where s_harm.yaml 'harmonics: 1000000' 1000000) road.iso8608.harmonics: must be an integer from 1 to 16384 (got 1000000)" \
  "a million harmonics" run s_harm.yaml -o out_harm --system rigid

echo "$NAME: $checks checks, $failures failed"
[ "$failures" -eq 0 ]
