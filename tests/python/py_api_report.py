# SPDX-License-Identifier: BSD-3-Clause
"""The report's data from Python (Scenario.study: the study layer's
fb_study_report) against what flexbond run states in report.md and
summary.json on the same scenarios. Run by CTest with the system python3:

    py_api_report.py FLEXBOND_EXECUTABLE SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both sides build the same report data (fb_study_report_new) from the same
runs, so every choice (which output, which tire, how many notable) must
be the same, and every number differs by the printing alone: report.md
prints a number to the digits written (%.4f, %.3g, %.1f, 4 significant
digits), so a value must lie within half a unit of the last printed digit
of it; summary.json prints %.10g, a relative 5e-10. System 2 adds the
rounding of its hull's eigen-solve, which the command runs on two threads
and a library user on one (tests/python/py_api.py's StudyTest): at most
1e-7 of an output's range, allowed on top; the choices hold by far
(the closest call below, truck4x4's notable outputs, is 13 points above
the 5 % line)."""

import json
import math
import os
import re
import sys
import unittest

import flexbond
from cli_files import run_cli

CLI = sys.argv[1]
SRC = sys.argv[2]
APC = os.path.join(SRC, "examples", "apc6x6.yaml")  # bilateral tires, one bump
TRUCK = os.path.join(SRC, "examples", "truck4x4.yaml")  # a soft hull: notable differences
SYSTEM2_ROUNDING = 1e-7  # of a value's scale


def run(path, out, system):
    """flexbond run's report.md and summary.json (parsed) in out."""
    run_cli(CLI, "run", path, "--system", system, "-o", out, "--no-figures", "-q")
    with open(os.path.join(out, "report.md"), encoding="utf-8") as f:
        report = f.read()
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        return report, json.load(f)


def study(path, systems, **options):
    with flexbond.Scenario(path) as scenario:
        return scenario.study(systems, **options)


def half_unit(text):
    """Half a unit of the last digit of a printed number ("0.1379",
    "1.184e-05", "17946")."""
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def table(report, header):
    """The rows of report.md's table whose header line starts with header,
    each a list of its cells."""
    lines = report.split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith(header))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip("|").split("|")])
    return rows


def conclusions(report):
    return report.split("## Conclusions\n\n", 1)[1]


class ReportTest(unittest.TestCase):
    def assertPrinted(self, value, text, what, scale=0.0):
        """value as report.md prints text, within its last digit."""
        tol = half_unit(text) * (1 + 1e-9) + SYSTEM2_ROUNDING * scale
        self.assertLessEqual(abs(value - float(text)), tol,
                             "%s: %r printed %s (tolerance %g)" % (what, value, text, tol))

    def check_common(self, st, report, js, labels, flexible):
        """What both kinds of run state: the windows, the tire models and
        each system's tire extremes."""
        bump = js["system1" if "system1" in js else "system2"]["bump_window"]
        for mine, theirs in zip(st.window, bump):
            self.assertLessEqual(abs(mine - theirs), 5e-10 * abs(theirs))
        corners = table(report, "| corner |")
        self.assertEqual([row[0] for row in corners], list(st.wheel_windows))
        for row in corners:
            entry, exit_ = row[2].split(", ")
            self.assertPrinted(st.wheel_windows[row[0]][0], entry, row[0] + " entry")
            self.assertPrinted(st.wheel_windows[row[0]][1], exit_, row[0] + " exit")
        models = js["system1" if "system1" in js else "system2"]["tire_contact"]["models"]
        self.assertEqual(st.tire_models, {m: list(models.values()).count(m)
                                          for m in set(models.values())})
        contact = report.split("## Tire contact", 1)[1]
        for system, (most, least) in st.contact_extremes.items():
            label = "System 1 (rigid hull)" if system == "rigid" else "System 2 (flexible hull)"
            verdict = contact.split("- " + label + ": ", 1)[1].split("\n- ", 1)[0]
            largest = re.search(r"the largest, (\S+), (\S+) times", verdict)
            if largest:  # no tire spikes: the report names the largest ratio
                self.assertEqual(largest.group(1), most)
                self.assertPrinted(st.runs[system].contact_ratio[most], largest.group(2),
                                   "ratio", 1.0 if system == "flexible" else 0.0)
            smallest = re.search(r"smallest normal reaction is (\S+) N \((\S+) tire", verdict)
            if smallest:  # no contact loss: the report names the least loaded tire
                self.assertEqual(smallest.group(2), least)
                scale = st.runs[system].contact[least].peak if flexible else 0.0
                self.assertPrinted(st.runs[system].contact[least].min, smallest.group(1),
                                   "smallest reaction", scale)
        self.assertEqual(len(labels), len(st.runs[next(iter(st.runs))].outputs))

    def test_one_system(self):
        """System 1 of apc6x6.yaml: nothing compared; the output that grows
        the most relative to its static value, as the conclusions name it."""
        report, js = run(APC, "report_rigid", "rigid")
        st = study(APC, ("rigid",))
        labels = [row[0] for row in table(report, "| output | unit | static |")]
        self.check_common(st, report, js, labels, flexible=False)
        self.assertIsNone(st.comparison)
        self.assertIsNone(st.differences)
        self.assertIsNone(st.largest_rms_change)
        name, factor = st.largest_growth
        grows = re.search(r"Over the bump, the (.+?) grows the most relative to its static value: its peak, "
                          r"(\S+) \S+ at (\S+) s, is (\S+) times", conclusions(report))
        self.assertIsNotNone(grows)
        k = list(st.runs["rigid"].outputs).index(name)
        self.assertEqual(labels[k], grows.group(1))
        self.assertPrinted(st.runs["rigid"].outputs[name].peak, grows.group(2), "peak")
        self.assertPrinted(factor, grows.group(4), "growth")
        self.assertEqual(st.torsion_max_abs, {"rigid": 0.0})  # printed for System 2 alone
        # The same run, step for step: summary.json's solver counts exactly.
        solver = js["system1"]["solver"]
        for key in solver:
            if key != "wall_seconds":
                self.assertEqual(st.runs["rigid"].result.stats[key], solver[key], key)

    def test_two_systems(self):
        """Both systems of truck4x4.yaml, whose soft hull makes every output
        that varies differ notably: the largest difference, the notable
        outputs with their differences, the largest r.m.s. change and the
        torsion angles, as the conclusions state them."""
        report, js = run(TRUCK, "report_truck", "both")
        st = study(TRUCK, ("rigid", "flexible"), basis_error=True)
        labels = [row[0] for row in table(report, "| output | unit | peak S1 |")]
        self.check_common(st, report, js, labels, flexible=True)
        names = list(st.runs["rigid"].outputs)
        label = dict(zip(names, labels))
        text = conclusions(report)
        d = st.differences
        head = re.match(r"Over the bump, System 2 departs from System 1 by up to (\S+) % of "
                        r"System 1's peak-to-peak range, in the (.+) \(at t = (\S+) s\); "
                        r"(\d+) of the (\d+) outputs that vary in System 1 differ by more than "
                        r"5 % \(([^)]*)\)", text)
        self.assertIsNotNone(head, text)
        # The largest difference may be shared: the cargo's mount force is
        # its mass times its acceleration, so their relative differences
        # agree to rounding, and which one a sum's last bit favours
        # differs between BLAS builds. Any output within rounding of the
        # largest (1e-9 of it) names it rightly.
        largest = st.comparison[d.largest].rel_diff
        tied = [label[n] for n, c in st.comparison.items()
                if abs(c.rel_diff - largest) <= 1e-9 * largest]
        self.assertIn(head.group(2), tied)
        self.assertPrinted(100 * st.comparison[d.largest].rel_diff, head.group(1), "largest",
                           100.0)
        self.assertEqual((d.nnotable, d.nvarying), (int(head.group(4)), int(head.group(5))))
        self.assertGreater(d.nnotable, 0)
        listed = re.findall(r"(.+?) (\d+\.\d) %(?:, |$)", head.group(6))
        self.assertEqual([label[n] for n in d.notable], [item[0] for item in listed])
        for n, (_, percent) in zip(d.notable, listed):
            self.assertPrinted(100 * st.comparison[n].rel_diff, percent, n, 100.0)
            self.assertGreater(st.comparison[n].rel_diff, flexbond.NOTABLE_DIFF)
        rms = re.search(r"The largest change of an RMS over the bump is the (.+)'s, (\S+) %",
                        text)
        self.assertEqual(label[st.largest_rms_change], rms.group(1))
        self.assertPrinted(100 * st.comparison[st.largest_rms_change].rms_change,
                           rms.group(2), "rms change", 100.0)
        self.assertIn("The rigid hull's torsion angle is identically zero", text)
        self.assertEqual(st.torsion_max_abs["rigid"], 0.0)
        band = re.search(r"frequencies are about (\S+) % to (\S+) % above", report)
        for value, printed in zip(st.mesh_error, band.groups()):
            self.assertPrinted(100 * value, printed, "mesh error")
        reaches = re.search(r"the flexible hull's torsion angle reaches (\S+) rad", text)
        twist = st.torsion_max_abs["flexible"]
        self.assertPrinted(twist, reaches.group(1), "torsion", twist)
        for name, c in st.comparison.items():
            o = js["comparison"][name]
            self.assertLessEqual(abs(c.range1 - o["range_system1"]),
                                 5e-10 * abs(o["range_system1"]))
            if o["max_abs_diff_rel"] is not None:
                self.assertLessEqual(abs(c.rel_diff - o["max_abs_diff_rel"]),
                                     5e-10 * o["max_abs_diff_rel"] + SYSTEM2_ROUNDING)
        self.assertTrue(math.isfinite(st.window[1]))
        self.check_basis_error(st, report, js, label)

    def check_basis_error(self, st, report, js, label):
        """System 2's estimated basis error: summary.json's estimated_error
        (%.10g; both runs of the estimate carry System 2's rounding, hence
        twice its allowance of the output's range) and the output report.md
        names as the worst."""
        self.assertIsNone(st.runs["rigid"].basis_error)
        mine = st.runs["flexible"].basis_error
        theirs = js["system2"]["hull_basis"]["estimated_error"]["of_range"]
        self.assertEqual(set(mine), set(theirs))
        for name, value in mine.items():
            self.assertLessEqual(abs(value - theirs[name]),
                                 5e-10 * abs(theirs[name]) + 2 * SYSTEM2_ROUNDING, name)
        worst = max(mine, key=mine.get)
        most = re.search(r"over each output's range there: at most (\S+) % \((.+?)\); ", report)
        self.assertEqual(label[worst], most.group(2))
        self.assertPrinted(100 * mine[worst], most.group(1), "worst basis error",
                           200 * SYSTEM2_ROUNDING)

    def test_converged_mesh(self):
        """apc6x6.yaml asks for System 2 again at a converged density: the
        rerun's statistics and basis error, its comparison with System 1,
        the table "At a converged mesh" and the conclusion's sentence on
        it."""
        report, js = run(APC, "report_converged", "both")
        st = study(APC, ("rigid", "flexible"), basis_error=True, converged=True)
        labels = [row[0] for row in table(report, "| output | unit | peak S1 |")]
        label = dict(zip(st.runs["rigid"].outputs, labels))
        fine = js["system2_converged"]
        self.assertEqual(st.converged_density, fine["mesh_density"])
        for name, o in st.converged.outputs.items():
            scale = fine["outputs"][name]["peak"] - fine["outputs"][name]["min"]
            for field in ("peak", "min", "rms"):
                self.assertLessEqual(abs(getattr(o, field) - fine["outputs"][name][field]),
                                     5e-10 * abs(fine["outputs"][name][field])
                                     + SYSTEM2_ROUNDING * scale, name + " " + field)
        for name, value in st.converged.basis_error.items():
            theirs = fine["hull_basis"]["estimated_error"]["of_range"][name]
            self.assertLessEqual(abs(value - theirs), 5e-10 * theirs + 2 * SYSTEM2_ROUNDING)
        for name, c in st.comparison_converged.items():
            o = js["comparison_converged"][name]
            if o["max_abs_diff_rel"] is None:
                self.assertTrue(math.isnan(c.rel_diff), name)
                continue
            self.assertLessEqual(abs(c.rel_diff - o["max_abs_diff_rel"]),
                                 5e-10 * o["max_abs_diff_rel"] + 2 * SYSTEM2_ROUNDING, name)
        rows = table(report, "| output | unit | max abs S2 - S1 / S1 range, density")
        self.assertEqual([row[0] for row in rows], labels)
        for name, row in zip(st.comparison_converged, rows):
            cells = (st.comparison[name].rel_diff, st.comparison_converged[name].rel_diff,
                     st.comparison[name].peak_change, st.comparison_converged[name].peak_change,
                     st.mesh_diff[name])
            for value, text in zip(cells, row[2:]):
                if text == "-":
                    self.assertTrue(math.isnan(value), (name, row))
                else:
                    self.assertPrinted(100 * value, text.rstrip(" %"), name, 200.0)
        d1, d3 = st.differences, st.differences_converged
        sentence = re.search(r"At the converged mesh \(density (\d+)\) System 2 departs from "
                             r"System 1 by up to (\S+) % of System 1's range, in the (.+?), "
                             r"against (\S+) % at density \d+: (the conclusion stands)?",
                             conclusions(report))
        self.assertEqual(int(sentence.group(1)), st.converged_density)
        self.assertEqual(label[d3.largest], sentence.group(3))
        self.assertPrinted(100 * st.comparison_converged[d3.largest].rel_diff,
                           sentence.group(2), "converged largest", 200.0)
        self.assertPrinted(100 * st.comparison[d1.largest].rel_diff, sentence.group(4),
                           "largest", 200.0)
        self.assertEqual(sentence.group(5) is not None,
                         st.mesh_crossings == 0 and d3.nnotable == 0)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
