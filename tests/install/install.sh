#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The installed package as its users meet it: `cmake --install` into a fresh prefix (and
# staged with DESTDIR), examples/c/peak_tire_force.c built with `pkg-config --cflags --libs
# flexbond` (shared) and `--static` and run, the installed CLI run, and `import flexbond` from
# the installed Python package with no hint of where the library is.
#   install.sh BUILD_DIR SOURCE_DIR C_COMPILER PYTHON3 PYTHON_DIR
set -euo pipefail
build=$1 src=$2 cc=$3 python=$4 pydir=$5
prefix=$PWD/prefix
rm -rf prefix staged
checks=0
fail() { echo "install: FAILED: $*" >&2; exit 1; }
ok() { checks=$((checks + 1)); }

cmake --install "$build" --prefix "$prefix" > install.log
pcfile=$(find "$prefix" -name flexbond.pc)
[ -n "$pcfile" ] || fail "no flexbond.pc under $prefix"
export PKG_CONFIG_PATH=$(dirname "$pcfile")
libdir=$(pkg-config --variable=libdir flexbond)
[ "$(cd "$libdir" && pwd -P)" = "$(cd "$(dirname "$pcfile")/.." && pwd -P)" ] ||
  fail "libdir $libdir is not the .pc file's parent"; ok
for f in "$libdir/libflexbond.so" "$libdir/libflexbond.a" "$prefix/bin/flexbond" \
         "$prefix/include/flexbond/vehicle.h" "$prefix/share/man/man1/flexbond.1" "$prefix/share/doc/flexbond/examples/apc6x6.yaml" \
         "$prefix/share/doc/flexbond/README.md" "$prefix/share/doc/flexbond/LICENSE" "$prefix/$pydir/flexbond/__init__.py"; do
  [ -e "$f" ] || fail "not installed: $f"; ok
done

# The manual page has a subsection per command of `flexbond --help`.
cmds=$("$prefix/bin/flexbond" --help | awk '/^commands:/ { on = 1; next }
                                            on && /^  [a-z]/ { print $1 } on && /^$/ { exit }')
[ -n "$cmds" ] || fail "no commands in the installed flexbond --help"
for cmd in $cmds; do
  grep -qx ".SS flexbond $cmd" "$prefix/share/man/man1/flexbond.1" || fail "flexbond.1: no $cmd"; ok
done

# Shared: found at run time through the rpath given here.
# shellcheck disable=SC2046
"$cc" "$src/examples/c/peak_tire_force.c" $(pkg-config --cflags --libs flexbond) \
  -Wl,-rpath,"$libdir" -o peak_shared
# (ldd's output held first: grep -q would end the pipe early, a failure under pipefail.)
deps=$(ldd peak_shared)
grep -q "$libdir/libflexbond.so" <<< "$deps" || fail "peak_shared does not load $libdir"; ok
# Static: Libs.private and Requires.private must name every dependency.
# shellcheck disable=SC2046
"$cc" "$src/examples/c/peak_tire_force.c" $(pkg-config --cflags flexbond) \
  -L"$libdir" -Wl,-Bstatic -lflexbond -Wl,-Bdynamic \
  $(pkg-config --static --libs flexbond | sed 's/-lflexbond//') -o peak_static
deps=$(ldd peak_static)
! grep -q libflexbond <<< "$deps" || fail "peak_static loads libflexbond"; ok
want=$("$prefix/bin/flexbond" run "$src/examples/apc6x6.yaml" --system rigid -o run > /dev/null 2>&1 &&
       echo ran)
[ "$want" = ran ] || fail "the installed flexbond run failed"; ok
for prog in peak_shared peak_static; do
  out=$(./$prog "$src/examples/apc6x6.yaml" tire_force_LF)
  case $out in "tire_force_LF: peak "*" N at t = "*" s") ok ;; *) fail "$prog: $out" ;; esac
done
[ "$(./peak_shared "$src/examples/apc6x6.yaml" tire_force_LF)" = \
  "$(./peak_static "$src/examples/apc6x6.yaml" tire_force_LF)" ] || fail "shared != static"; ok
# The peak against the run's CSV: the largest tire_force_LF in system1.csv (10 digits).
csv_peak=$(awk -F, 'NR == 1 { for (j = 1; j <= NF; ++j) if ($j == "tire_force_LF [N]") c = j; next }
                    $c > m || NR == 2 { m = $c } END { printf "%.6g", m }' run/system1.csv)
case $(./peak_shared "$src/examples/apc6x6.yaml" tire_force_LF) in
  "tire_force_LF: peak $csv_peak N"*) ok ;;
  *) fail "peak differs from run/system1.csv's $csv_peak" ;;
esac
if ./peak_shared no-such.yaml x 2> err.txt; then fail "a missing file succeeded"; fi
grep -q "no-such.yaml" err.txt || fail "the error does not name the file"; ok

# Python, from the installed package alone.
env -u FLEXBOND_LIBRARY PYTHONPATH="$prefix/$pydir" "$python" -c '
import sys, flexbond
assert flexbond.library_path.startswith(sys.argv[1]), flexbond.library_path
r = flexbond.Scenario(sys.argv[2]).run("rigid")
assert len(r) == 15001 and r.names[0] == "t", r
' "$prefix/" "$src/examples/apc6x6.yaml" || fail "import flexbond from $prefix/$pydir"; ok

# DESTDIR stages the same tree, and the package names the final place, not the stage.
DESTDIR=$PWD/staged cmake --install "$build" --prefix /opt/flexbond > staged.log
[ -e "staged/opt/flexbond/$pydir/flexbond/library_path" ] || fail "DESTDIR: no library_path"
case $(cat "staged/opt/flexbond/$pydir/flexbond/library_path") in
  /opt/flexbond/*/libflexbond.so.0) ok ;;
  *) fail "DESTDIR: library_path $(cat "staged/opt/flexbond/$pydir/flexbond/library_path")" ;;
esac
# `make install` hands PREFIX and DESTDIR to the shell as data: a command in either is never
# run, not even by `make -n` (make's own $(shell) once ran it), and install-check refuses it,
# a "$" make would have expanded, a quote or a line break, before anything is built.
rm -f injected
mk() { env -u MAKEFLAGS -u MAKELEVEL make -s -C "$src" "$@"; }
mk -n install BUILD_DIR="$build" PREFIX="/x/\`touch $PWD/injected\`" > /dev/null 2>&1 || true
[ ! -e injected ] || fail "make -n install ran a command in PREFIX"; ok
nl='
'
for bad in "PREFIX=/x/\`touch $PWD/injected\`" 'PREFIX=$HOME/x' "PREFIX=/a\"b" "PREFIX=/a${nl}b" \
           'PREFIX=relative' "DESTDIR=/s/\$(touch $PWD/injected)"; do
  if mk install-check "$bad" 2> err.txt; then fail "install-check took $bad"; fi
  grep -q "^make install: PREFIX" err.txt || fail "install-check: $(cat err.txt)"; ok
done
[ ! -e injected ] || fail "install-check ran a command"; ok
mk install-check PREFIX=/opt/flexbond-1.0 DESTDIR="$PWD/staged" || fail "install-check refused a plain prefix"; ok
echo "install: $checks checks passed"
