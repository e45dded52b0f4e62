#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The work-precision table of bench/work_precision.sh.

usage: wp_table.py MANIFEST.tsv TABLE.csv CURVES.dat

For each case of the manifest (one run's CSV and its reference's), the
error of each output column is max over the samples of
|y - y_ref| / (max y_ref - min y_ref); a column whose reference is
constant (System 1's torsion, identically 0) is left out. err_max is the
largest over the columns. The manifest's times are the runs' (a;b;c):
TABLE.csv has their median and minimum, one row per case (the
references included, with an empty error, and the other solvers at the
references' tolerance, which shows how far the formulations agree; the
first case is a reference and gives its rtol); CURVES.dat one gnuplot block
per curve (system, formulation, solver): the solver's least time over
the runs, err_max and
rtol, from the loosest rtol to the tightest.
"""
import csv
import statistics
import sys

import numpy as np


def read(path):
    with open(path) as fp:
        names = fp.readline().strip().split(",")
    return names, np.loadtxt(path, delimiter=",", skiprows=1)


def errors(path, ref, columns):
    names, y = read(path)
    columns.extend(n for n in names[1:] if n not in columns)
    rnames, r = read(ref)
    if names != rnames or y.shape != r.shape:
        sys.exit(f"wp_table: {path} and {ref} differ in their columns or rows")
    out = {}
    for j, name in enumerate(names[1:], start=1):
        span = r[:, j].max() - r[:, j].min()
        if span > 0:
            out[name] = float(np.abs(y[:, j] - r[:, j]).max() / span)
    return out


def main():
    manifest, table, curves = sys.argv[1:4]
    with open(manifest) as fp:
        cases = list(csv.DictReader(fp, delimiter="\t"))
    columns = []
    for c in cases:
        c["errors"] = errors(c["csv"], c["reference"], columns) if c["reference"] != "-" else {}
    for c in cases:
        for k in ["solver_seconds", "process_seconds"]:
            times = [float(v) for v in c[k].split(";")]
            c[k] = "%.4g" % statistics.median(times)
            c[k + "_min"] = "%.4g" % min(times)
    head = ["system", "formulation", "solver", "rtol", "atol", "solver_seconds",
            "solver_seconds_min", "process_seconds", "process_seconds_min", "steps",
            "rhs_evals", "err_max"] + ["err_" + n for n in columns]
    with open(table, "w", newline="") as fp:
        w = csv.writer(fp, lineterminator="\n")
        w.writerow(head)
        for c in cases:
            e = c["errors"]
            row = [c[k] for k in head[:11]]
            row.append("%.3g" % max(e.values()) if e else "")
            row += ["%.3g" % e[n] if n in e else "" for n in columns]
            w.writerow(row)
    # One curve per (system, formulation, solver), without the references
    # and the other solvers' runs at the reference's tolerance.
    ref_rtol = cases[0]["rtol"]
    for c in cases:
        c["curve"] = bool(c["errors"]) and c["rtol"] != ref_rtol
    order = []
    for c in cases:
        key = (c["system"], c["formulation"], c["solver"])
        if c["curve"] and key not in order:
            order.append(key)
    with open(curves, "w") as fp:
        for key in order:
            label = "%s %s, %s" % ("System 1" if key[0] == "system1" else "System 2", key[1],
                                   key[2])
            fp.write('"%s" "err_max"\n' % label)
            pts = sorted(((float(c["rtol"]), float(c["solver_seconds_min"]), max(c["errors"].values()))
                          for c in cases
                          if c["curve"] and (c["system"], c["formulation"], c["solver"]) == key),
                         reverse=True)
            for rtol, t, e in pts:
                fp.write("%.6g %.6g %g\n" % (t, e, rtol))
            fp.write("\n\n")


if __name__ == "__main__":
    main()
