#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# flexbond.1, the manual page, from the command's own --help texts (the one place they are
# written): `flexbond --help` as the description, each command's `--help` as a subsection.
#   manpage.sh FLEXBOND_EXECUTABLE OUTPUT
# The page is written to a temporary file beside OUTPUT, checked (a subsection per command the
# overview lists) and only then renamed onto OUTPUT.
set -euo pipefail
flexbond=$1 out=$2
tmp=$(mktemp "$out.XXXXXX")
trap 'rm -f "$tmp"' EXIT

# roff text from plain text, kept as it is laid out (.nf): a backslash is \e, a line that
# would start a request (a leading . or ') is protected with \&, a hyphen is \- (the
# options' dashes, which must not become typographic hyphens).
roff_escape() {
  sed -e 's/\\/\\e/g' -e 's/-/\\-/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"
}

overview=$("$flexbond" --help)
version=$("$flexbond" --version)
commands=$(awk '/^commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { exit }' \
             <<< "$overview")
[ -n "$commands" ] || { echo "manpage.sh: no commands in flexbond --help" >&2; exit 1; }
{
  printf '.TH FLEXBOND 1 "" "%s" "User Commands"\n' "$(roff_escape <<< "$version")"
  printf '.SH NAME\nflexbond \\- modular bond-graph modelling and simulation of vehicles with flexible hulls\n'
  printf '.SH SYNOPSIS\n.nf\n'
  roff_escape <<< "$overview" | sed -n '1,/^$/p'
  printf '.fi\n.SH DESCRIPTION\n.nf\n'
  roff_escape <<< "$overview" | sed '1,/^$/d'
  printf '.fi\n.SH COMMANDS\n'
  for cmd in $commands; do
    printf '.SS flexbond %s\n.nf\n' "$cmd"
    "$flexbond" "$cmd" --help | roff_escape
    printf '.fi\n'
  done
  printf '.SH SEE ALSO\nThe documents installed in share/doc/flexbond: README.md, scenario\\-format.md, model\\-format.md, python.md, install.md.\n'
} > "$tmp"
for cmd in $commands; do
  grep -qx ".SS flexbond $cmd" "$tmp" || { echo "manpage.sh: no section for $cmd" >&2; exit 1; }
done
chmod 644 "$tmp"
mv -f "$tmp" "$out"
trap - EXIT
