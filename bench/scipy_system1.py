#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""System 1 of examples/apc6x6.yaml from `flexbond export --system rigid`,
integrated with SciPy's solve_ivp (BDF or Radau).

The export is the index-1 descriptor system E x' = A x + Bu u(t) + f,
y = C x, with E the identity at the first nd (differential) variables
and zero elsewhere (docs/export.md). The algebraic variables are
eliminated once, xa = -Aaa^-1 (Aad xd + Ba u + fa), which leaves the
linear ODE xd' = Ar xd + Br u(t) + fr with a constant Jacobian Ar, given
to the solver. u holds the road heights (unused) and the road rates of
the scenario's oblique bump, (pi h V / L) sin(2 pi V (t - t_c) / L) while
wheel c is on it. As flexbond does, the integration stops at each
wheel's bump entry and exit and restarts there.

Usage: scipy_system1.py EXPORT_DIR --method BDF|Radau --rtol X --atol Y
       [-o FILE.csv]
Writes the columns of `flexbond run --system rigid` (system1.csv) at
1 kHz and prints the integration's wall time on stderr as
"solve_seconds S rhs_evals N factorizations M".
"""
import argparse
import json
import math
import sys
import time

import numpy as np
import scipy.io as sio
import scipy.sparse.linalg as sla
from scipy.integrate import solve_ivp

# examples/apc6x6.yaml: the road and the corners it is met by.
SPEED = 10.0 / 3.6  # m/s
BUMP_H, BUMP_L = 0.10, 3.70  # m
ANGLE = math.radians(45.0)
FIRST_CONTACT = 5.0  # s, the left front wheel
CORNERS = [(1.90, 1.05), (1.90, -1.05), (0.40, 1.05), (0.40, -1.05), (-1.00, 1.05), (-1.00, -1.05)]
T_END, RATE = 15.0, 1000.0


def entry_times():
    x0, y0 = CORNERS[0]
    return np.array([FIRST_CONTACT + ((x0 - x) + (y0 - y) * math.tan(ANGLE)) / SPEED
                     for x, y in CORNERS])


def road_rates(t, entry):
    """The six road rates at time t (scalar)."""
    s = SPEED * (t - entry)
    on = (s >= 0.0) & (s <= BUMP_L)
    return np.where(on, SPEED * math.pi * BUMP_H / BUMP_L * np.sin(2 * math.pi * s / BUMP_L), 0.0)


def load(export_dir):
    m = {k: sio.mmread(f"{export_dir}/{k}.mtx").tocsc() for k in ["A", "Bu", "f", "C"]}
    info = json.load(open(f"{export_dir}/model.json"))
    nd = info["ndifferential"]
    A, Bu, f, C = m["A"], m["Bu"].toarray(), m["f"].toarray().ravel(), m["C"]
    Aaa = A[nd:, nd:].tocsc()
    lu = sla.splu(Aaa)
    Aad = A[nd:, :nd].toarray()
    Ada = A[:nd, nd:].toarray()
    # xa = Ka xd + Ku u + ka
    Ka = -lu.solve(Aad)
    Ku = -lu.solve(Bu[nd:, :])
    ka = -lu.solve(f[nd:])
    Ar = A[:nd, :nd].toarray() + Ada @ Ka
    Br = Bu[:nd, :] + Ada @ Ku
    fr = f[:nd] + Ada @ ka
    Cd = C[:, :nd].toarray()
    Ca = C[:, nd:].toarray()
    # y rows = Cy xd + Cu u + cy
    Cy, Cu, cy = Cd + Ca @ Ka, Ca @ Ku, Ca @ ka
    return info, Ar, Br, fr, Cy, Cu, cy


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("export_dir")
    ap.add_argument("--method", default="BDF", choices=["BDF", "Radau", "LSODA"])
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--atol", type=float, default=1e-8)
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    info, Ar, Br, fr, Cy, Cu, cy = load(a.export_dir)
    entry = entry_times()
    # Only the rate columns (the last six) of u enter.
    Brr = Br[:, 6:]

    def rhs(t, x):
        return Ar @ x + Brr @ road_rates(t, entry) + fr

    kinks = np.sort(np.concatenate([entry, entry + BUMP_L / SPEED]))
    edges = np.concatenate([[0.0], kinks[(kinks > 0) & (kinks < T_END)], [T_END]])
    n = int(round(T_END * RATE)) + 1
    ts = np.arange(n) / RATE
    ts[-1] = T_END
    x = np.zeros(Ar.shape[0])
    xs = np.zeros((n, x.size))
    nfev = nlu = 0
    t0 = time.perf_counter()
    for lo, hi in zip(edges[:-1], edges[1:]):
        # the samples in (lo, hi] (and t = 0 in the first segment), then hi itself
        sel = (ts > lo) & (ts <= hi) if lo > 0 else (ts <= hi)
        t_eval = np.append(ts[sel], hi) if not sel.any() or ts[sel][-1] != hi else ts[sel]
        sol = solve_ivp(rhs, (lo, hi), x, method=a.method, rtol=a.rtol, atol=a.atol,
                        jac=Ar, t_eval=t_eval)
        if sol.status != 0:
            sys.exit(f"scipy_system1: {a.method} failed at t = {sol.t[-1]}: {sol.message}")
        xs[sel] = sol.y[:, :sel.sum()].T
        x = sol.y[:, -1]
        nfev += sol.nfev
        nlu += sol.nlu
    solve = time.perf_counter() - t0
    u = np.array([road_rates(t, entry) for t in ts])
    rows = xs @ Cy.T + u @ Cu[:, 6:].T + cy
    cols = [ts]
    names = ["t"]
    for o in info["outputs"]:
        r = o["rows"]
        cols.append(rows[:, r[0]] * rows[:, r[1]] if o["product"] else rows[:, r[0]])
        names.append(o["name"])
    if a.output:
        with open(a.output, "w") as fp:
            fp.write(",".join(names) + "\n")
            for row in np.column_stack(cols):
                fp.write(",".join("%.10g" % v for v in row) + "\n")
    print(f"solve_seconds {solve:.6f} rhs_evals {nfev} factorizations {nlu}", file=sys.stderr)


if __name__ == "__main__":
    main()
