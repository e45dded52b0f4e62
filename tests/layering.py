#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The library's layers (docs/architecture.md): no module below src/io
(core, bg, bd, sim, fem, road, ride, vehicle, study) includes or calls io
or cli, names a scenario file's key, or names the command line; and the
command's own files (src/cli) call one another without a cycle.

  layering.py SOURCE_DIR OBJECT_DIR...

Checked three ways, each from what the build and the format declare, so
that nothing here needs updating when a key or a function is added:
- includes: no "io/...", "cli/..." or flexbond/io.h, flexbond/model.h;
- calls: no symbol a lower module's object file leaves undefined is
  defined by an io or cli object file (nm over the OBJECT_DIRs);
- text: no string literal of a lower module holds a key path of the
  scenario format (the dotted keys of docs/scenario-format.md's tables,
  which test_scenario_docs keeps equal to the reader's table), a command
  line option ("--set") or the command's name before a subcommand;
- cycles: the files of src/cli, as nodes, and "calls a symbol defined
  by" as edges (nm), hold no cycle: each renders what the library
  computes, so none needs another that needs it back.
Exit 1 with every finding; 0 when there is none."""
import os
import re
import subprocess
import sys

LOWER = ("core", "bg", "bd", "sim", "fem", "road", "ride", "vehicle", "study")
UPPER = ("io", "cli")
# The command's subcommands (src/cli/main.c).
COMMANDS = ("run", "sweep", "freq", "modes", "export", "model", "mesh", "sim", "diagram",
            "causality", "eig")
FORBIDDEN_INCLUDES = re.compile(r'#\s*include\s*"(io/|cli/|flexbond/io\.h|flexbond/model\.h)')


def sources(src, module):
    d = os.path.join(src, "src", module)
    return [os.path.join(d, f) for f in sorted(os.listdir(d)) if f.endswith((".c", ".h"))]


def literals(text):
    """The string literals of C source text, comments and character
    constants skipped."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            i = n if end < 0 else end + 2
        elif text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif c in "\"'":
            j, buf = i + 1, []
            while j < n and text[j] != c:
                if text[j] == "\\":
                    buf.append(text[j:j + 2])
                    j += 2
                else:
                    buf.append(text[j])
                    j += 1
            if c == '"':
                out.append("".join(buf))
            i = j + 1
        else:
            i += 1
    return out


def scenario_keys(src):
    """The dotted key paths of the scenario format (its documented tables)."""
    doc = open(os.path.join(src, "docs", "scenario-format.md"), encoding="utf-8").read()
    begin, end = doc.index("<!-- schema:begin -->"), doc.index("<!-- schema:end -->")
    keys = set(re.findall(r"^\| `([A-Za-z_][\w.]*)` \|", doc[begin:end], re.M))
    return sorted(k for k in keys if "." in k)


def defined_symbols(objects):
    out = set()
    for o in objects:
        lines = subprocess.run(["nm", "--defined-only", "-g", o], check=True,
                               capture_output=True, text=True).stdout.splitlines()
        out.update(line.split()[-1] for line in lines if line.strip())
    return out


def undefined_symbols(obj):
    lines = subprocess.run(["nm", "-u", obj], check=True, capture_output=True,
                           text=True).stdout.splitlines()
    return {line.split()[-1] for line in lines if line.strip()}


def cycles(graph):
    """The strongly connected components of more than one node of graph
    (node -> set of nodes), each sorted (Tarjan, iterative)."""
    index, low, on, stack, out, counter = {}, {}, set(), [], [], [0]
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter[0]
                    counter[0] += 1
                    stack.append(child)
                    on.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == node:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def call_graph(objs):
    """Each object's file name -> the files that define what it calls."""
    owner = {}
    for o in objs:
        for sym in defined_symbols([o]):
            owner[sym] = os.path.basename(o)
    return {os.path.basename(o): {owner[s] for s in undefined_symbols(o) if s in owner} -
            {os.path.basename(o)} for o in objs}


def objects(dirs, module):
    found = []
    for d in dirs:
        for root, _, files in os.walk(d):
            if os.path.basename(root) == module and os.sep + "src" in root:
                found += [os.path.join(root, f) for f in files if f.endswith(".o")]
    return found


def main():
    src, objdirs = sys.argv[1], sys.argv[2:]
    findings = []
    keys = scenario_keys(src)
    if len(keys) < 50:
        findings.append("docs/scenario-format.md: only %d keys found" % len(keys))
    # A key as a literal, or a literal that starts with it and goes on
    # into the key's items or members ("hull.masses.%s").
    key_in = re.compile(r"(?<![\w.])(%s)(?![\w])" % "|".join(re.escape(k) for k in keys))
    cli_in = re.compile(r"(?<![\w-])--(set|system|strict|hull-[a-z]+)\b|\bflexbond (%s)\b" %
                        "|".join(COMMANDS))
    # The checks bite: each finds what it is for in text made to hold it.
    bad = 'x = "hull.fe.modes"; /* "road.speed_kmh" */ y = "see --set k=v"; z = \'"\';'
    bites = [lit for lit in literals(bad) if key_in.search(lit) or cli_in.search(lit)]
    if bites != ["hull.fe.modes", "see --set k=v"]:
        findings.append("the text checks do not bite: %r" % bites)
    if not FORBIDDEN_INCLUDES.search('#include "io/scenario_internal.h"'):
        findings.append("the include check does not bite")
    if cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) != [["a", "b", "c"]]:
        findings.append("the cycle check does not bite")
    for module in LOWER:
        for path in sources(src, module):
            text = open(path, encoding="utf-8").read()
            rel = os.path.relpath(path, src)
            for m in FORBIDDEN_INCLUDES.finditer(text):
                findings.append("%s: includes %s" % (rel, m.group(1)))
            for lit in literals(text):
                m = key_in.search(lit)
                if m:
                    findings.append("%s: names the scenario key %s in \"%s\"" %
                                    (rel, m.group(1), lit))
                m = cli_in.search(lit)
                if m:
                    findings.append("%s: names the command line in \"%s\"" % (rel, lit))
    if objdirs:
        upper = defined_symbols([o for m in UPPER for o in objects(objdirs, m)])
        lower = [o for m in LOWER for o in objects(objdirs, m)]
        if not upper or len(lower) < 50:
            findings.append("object files not found under %s" % " ".join(objdirs))
        for o in lower:
            for sym in sorted(undefined_symbols(o) & upper):
                findings.append("%s: calls %s, defined in io or cli" %
                                (os.path.basename(o), sym))
        cli = objects(objdirs, "cli")
        if len(cli) < 10:
            findings.append("src/cli's object files not found under %s" % " ".join(objdirs))
        for comp in cycles(call_graph(cli)):
            findings.append("src/cli: %s call one another in a cycle" % ", ".join(comp))
    for f in findings:
        print("layering: " + f)
    print("layering: %d findings (%d scenario keys checked)" % (len(findings), len(keys)))
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
