#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Free-free modes of a flexbond hull deck with CalculiX (bench/calculix_modes.sh).

usage: calculix_modes.py DECK.inp WORKDIR [NMODES]

Reads the deck `flexbond mesh --export` writes (S3 and S4 flat shells, one
material and section, and the hull masses as MASS elements, kept as they
are), turns it into quadratic shells of the same geometry
(S4 -> S8R, S3 -> S6: a node at the middle of every element edge, shared by
the elements on that edge), appends a *FREQUENCY step without supports and
runs `ccx`. CalculiX expands shells into solid elements (C3D20R, C3D15),
whose linear versions lock in bending on a coarse mesh; the quadratic ones
are the element for such a check. Prints the elastic frequencies (Hz), the
rigid-body ones dropped: CalculiX lists the modes above the step's lower
frequency bound only.
"""
import os
import re
import subprocess
import sys


def read_deck(path):
    nodes, elements, tail = {}, [], []
    block = None
    with open(path) as fp:
        for line in fp:
            text = line.strip()
            if not text or text.startswith("**"):
                continue
            if text.startswith("*"):
                upper = text.upper()
                if upper.startswith("*NODE") and "FILE" not in upper:
                    block = "node"
                elif upper.startswith("*ELEMENT") and "TYPE=MASS" not in upper.replace(" ", ""):
                    block = "S4" if "TYPE=S4" in upper else "S3"
                elif upper.startswith("*NSET") or upper.startswith("*HEADING"):
                    block = "skip"
                else:
                    block = "tail"
                    tail.append(text)
                continue
            fields = [f.strip() for f in text.split(",") if f.strip()]
            if block == "node":
                nodes[int(fields[0])] = [float(v) for v in fields[1:4]]
            elif block in ("S3", "S4"):
                elements.append((block, int(fields[0]), [int(v) for v in fields[1:]]))
            elif block == "tail":
                tail.append(text)
    return nodes, elements, tail


def quadratic(nodes, elements):
    """Midside nodes for every edge; the elements as S8R and S6."""
    mid, next_id = {}, max(nodes) + 1
    out = []
    for kind, eid, conn in elements:
        corners = len(conn)
        extra = []
        for k in range(corners):
            a, b = conn[k], conn[(k + 1) % corners]
            key = (min(a, b), max(a, b))
            if key not in mid:
                mid[key] = next_id
                nodes[next_id] = [(p + q) / 2 for p, q in zip(nodes[a], nodes[b])]
                next_id += 1
            extra.append(mid[key])
        out.append(("S8R" if corners == 4 else "S6", eid, conn + extra))
    return out


def write_job(path, nodes, elements, tail, nmodes):
    with open(path, "w") as fp:
        fp.write("*NODE, NSET=NALL\n")
        for nid in sorted(nodes):
            x, y, z = nodes[nid]
            fp.write(f"{nid}, {x:.15g}, {y:.15g}, {z:.15g}\n")
        for kind in ("S8R", "S6"):
            rows = [e for e in elements if e[0] == kind]
            if not rows:
                continue
            fp.write(f"*ELEMENT, TYPE={kind}, ELSET=EALL\n")
            for _, eid, conn in rows:
                ids = [str(eid)] + [str(n) for n in conn]
                # at most 16 entries on a line (continuation with a trailing comma)
                fp.write(", ".join(ids[:16]) + (",\n" + ", ".join(ids[16:]) if len(ids) > 16 else "") + "\n")
        for text in tail:
            fp.write(text + "\n")
        # The lower bound (1 Hz) is the shift that keeps K - sigma M regular
        # with the six rigid-body modes of the free-free hull.
        fp.write(f"*STEP\n*FREQUENCY\n{nmodes}, 1.0, 1000.0\n*END STEP\n")


def frequencies(dat_path):
    with open(dat_path) as fp:
        text = fp.read()
    start = text.find("E I G E N V A L U E   O U T P U T")
    if start < 0:
        sys.exit(f"calculix_modes: no eigenvalue output in {dat_path}")
    out = []
    for line in text[start:].splitlines()[6:]:
        fields = line.split()
        if len(fields) != 5 or not re.fullmatch(r"\d+", fields[0]):
            break
        out.append(float(fields[3]))
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    deck, work = sys.argv[1], sys.argv[2]
    nmodes = int(sys.argv[3]) if len(sys.argv) > 3 else 16
    os.makedirs(work, exist_ok=True)
    nodes, elements, tail = read_deck(deck)
    elements = quadratic(nodes, elements)
    job = os.path.join(work, "job")
    write_job(job + ".inp", nodes, elements, tail, nmodes)
    with open(os.path.join(work, "ccx.log"), "w") as log:
        rc = subprocess.run(["ccx", "job"], cwd=work, stdout=log, stderr=subprocess.STDOUT).returncode
    if rc != 0:
        sys.exit(f"calculix_modes: ccx failed with status {rc} (see {work}/ccx.log)")
    for f in frequencies(job + ".dat"):
        print(f"{f:.6f}")


if __name__ == "__main__":
    main()
