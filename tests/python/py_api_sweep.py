# SPDX-License-Identifier: BSD-3-Clause
"""The Python package's parameter sweeps (Scenario.sweep, docs/python.md)
against flexbond sweep on the same grid. Run by CTest with the system
python3:

    py_api_sweep.py FLEXBOND_CLI SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both front ends run each case through the same library function
(fb_study_sweep_run_case: the case's scenario read with its overrides,
simulated, measured by the study layer), and sweep.csv prints every
metric as the shortest text that reads back to the same double: the
numbers must be equal to the last bit, so the comparison's tolerance is
zero."""

import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest
import warnings

import flexbond

CLI, SRC = sys.argv[1], sys.argv[2]
APC = os.path.join(SRC, "examples", "apc6x6.yaml")

# System 1 over the bump at 36 km/h in a run of 2 s: the left front wheel
# meets it at 0.5 s, the last wheel leaves it before 1.5 s (faster too).
SHORT = {"speed_kmh": 36, "first_contact": 0.5, "t_end": 2.0}

# A 3 x 3 grid of System 1 over the bump, one tire stiffness refused (-1
# N/m: a failed case with its message in both), 9 cases of 20 ms.
GRID = {"speed_kmh": [10, 20, 35], "wheel.tire_k": [300000, 800000, -1]}


def cli_sweep(out, grid, *extra):
    """flexbond sweep over grid into out: its sweep.csv's rows, as dicts."""
    sets = []
    for key, values in grid.items():
        sets += ["--set", "%s=%s" % (key, ",".join(str(v) for v in values))]
    run = subprocess.run([CLI, "sweep", APC] + sets + ["-o", out, "-q", "--no-figures",
                                                       "--plain-header"] + list(extra),
                         capture_output=True, text=True, check=False)
    # 4: some cases failed (the refused tire stiffness); the file is written.
    if run.returncode not in (0, 4):
        raise AssertionError("flexbond sweep failed (%d): %s" % (run.returncode, run.stderr))
    with open(os.path.join(out, "sweep.csv"), newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def same_number(text, value):
    """sweep.csv's cell (empty for NaN) against Python's float, exactly."""
    if text == "":
        return math.isnan(value)
    return float(text) == value


class SweepAgainstCommand(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(dir=".")
        cls.rows = cli_sweep(os.path.join(cls.tmp.name, "grid"), GRID, "-j", "2")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", flexbond.PlausibilityWarning)
            cls.scenario = flexbond.Scenario(APC)
        cls.sweep = cls.scenario.sweep(GRID, system="rigid", threads=2)

    @classmethod
    def tearDownClass(cls):
        cls.scenario.close()
        cls.tmp.cleanup()

    def test_columns(self):
        self.assertEqual(self.sweep.columns, list(self.rows[0].keys()))
        self.assertEqual(self.sweep.keys, ["speed_kmh", "wheel.tire_k"])
        self.assertEqual(self.sweep.units["min_tire_force"], "N")
        self.assertEqual(self.sweep.units["solver_steps"], "-")

    def test_same_numbers(self):
        self.assertEqual(len(self.sweep), 9)
        self.assertEqual(len(self.rows), 9)
        compared = 0
        for row, case in zip(self.rows, self.sweep.cases):
            for key in self.sweep.keys:
                self.assertEqual(row[key], case[key])
            for m in self.sweep.metrics:
                self.assertTrue(same_number(row[m], case[m]),
                                "%s of case %s: sweep.csv %r, Python %r" %
                                (m, row, row[m], case[m]))
                compared += not math.isnan(case[m])
            # The same message, each front end naming the value its own way.
            if row["error"]:
                cli_label, cli_rest = row["error"].split(": ", 1)
                py_label, py_rest = case["error"].split(": ", 1)
                self.assertEqual(cli_rest, py_rest)
                self.assertEqual(cli_label, "--set wheel.tire_k=-1")
                self.assertEqual(py_label, "axes['wheel.tire_k']=-1")
            else:
                self.assertIsNone(case["error"])
        # 6 cases ran, each with its 23 output statistics, contact and ride
        # metrics and steps: hundreds of numbers, every one equal.
        self.assertGreater(compared, 150)
        print("py_api_sweep: %d numbers of %d cases equal to sweep.csv's" %
              (compared, len(self.sweep)), file=sys.stderr)

    def test_failed_cases(self):
        # tire_k = -1, the grid's last value: cases 3, 6 and 9.
        self.assertEqual(self.sweep.failed, [2, 5, 8])
        self.assertIn("wheel.tire_k", self.sweep.cases[2]["error"])
        self.assertIn("must be > 0", self.sweep.cases[2]["error"])
        self.assertTrue(math.isnan(self.sweep["min_tire_force"][2]))
        self.assertEqual(self.sweep["speed_kmh"], ["10"] * 3 + ["20"] * 3 + ["35"] * 3)

    def test_one_thread_the_same(self):
        one = self.scenario.sweep(GRID, threads=1)
        for a, b in zip(one.cases, self.sweep.cases):
            for m in self.sweep.metrics:
                self.assertTrue(a[m] == b[m] or (math.isnan(a[m]) and math.isnan(b[m])), m)


class SweepOptions(unittest.TestCase):
    def test_base_overrides_apply(self):
        # The scenario's own overrides hold in every case (SHORT, one-value
        # axes of the command); a swept key replaces its override.
        with tempfile.TemporaryDirectory(dir=".") as tmp:
            rows = cli_sweep(tmp, {"first_contact": [0.5], "t_end": [2.0],
                                   "speed_kmh": [36, 54]})
        with flexbond.Scenario(APC, overrides=SHORT) as s:
            sw = s.sweep({"speed_kmh": [36, 54]}, threads=2)
        self.assertEqual(sw.failed, [])
        for row, case in zip(rows, sw.cases):
            for m in sw.metrics:
                self.assertTrue(same_number(row[m], case[m]), m)

    def test_system2_same_numbers(self):
        # System 2 (the finite-element hull, its modal basis solved in each
        # case) the same way: OpenBLAS on one thread on both sides.
        with tempfile.TemporaryDirectory(dir=".") as tmp:
            rows = cli_sweep(tmp, {"first_contact": [0.5], "t_end": [2.0],
                                   "speed_kmh": [36, 54]}, "--system", "flexible")
        with flexbond.Scenario(APC, overrides=SHORT) as s:
            sw = s.sweep({"speed_kmh": [36, 54]}, system="flexible", threads=2)
        self.assertEqual(sw.failed, [])
        for row, case in zip(rows, sw.cases):
            for m in sw.metrics:
                self.assertTrue(same_number(row[m], case[m]), m)

    def test_description_sweeps_as_its_file(self):
        with flexbond.Scenario(APC, overrides=SHORT) as s:
            from_file = s.sweep({"speed_kmh": [36]}, threads=1)
        import yaml  # noqa: E402 (only here: the other tests need no YAML reader)
        with open(APC, encoding="utf-8") as f:
            data = yaml.safe_load(f)
        data["simulation"]["t_end"] = SHORT["t_end"]
        data["road"]["bump"]["first_contact"] = SHORT["first_contact"]
        data["road"]["speed_kmh"] = SHORT["speed_kmh"]
        cwd = os.getcwd()
        os.chdir(os.path.dirname(APC))  # the description's files resolve from here
        try:
            with flexbond.Scenario.from_dict(data) as d:
                from_data = d.sweep({"speed_kmh": [36]}, threads=1)
        finally:
            os.chdir(cwd)
        self.assertEqual(from_data.failed, [])
        for m in from_file.metrics:
            self.assertEqual(from_file.cases[0][m], from_data.cases[0][m], m)

    def test_progress(self):
        heard = []
        with flexbond.Scenario(APC, overrides=SHORT) as s:
            s.sweep({"speed_kmh": [36, 45, 54]}, threads=2,
                    progress=lambda stage, f: heard.append((stage, f)))
        self.assertEqual(len(heard), 3)
        self.assertEqual(sorted(f for _, f in heard), [1 / 3, 2 / 3, 1.0])
        self.assertTrue(all(stage.startswith("case ") and stage.endswith(": ok")
                            for stage, _ in heard), heard)

    def test_progress_exception_stops(self):
        class Enough(Exception):
            pass

        heard = []

        def stop(stage, fraction):
            heard.append(stage)
            raise Enough(stage)

        with flexbond.Scenario(APC, overrides=SHORT) as s:
            with self.assertRaises(Enough):
                s.sweep({"speed_kmh": [36, 45, 54]}, threads=1, progress=stop)
            # On one thread, no case starts after the first has finished.
            self.assertEqual(len(heard), 1)
            # The scenario stays usable.
            self.assertEqual(len(s.sweep({"speed_kmh": [36]}, threads=1)), 1)

    def test_bad_arguments(self):
        with flexbond.Scenario(APC) as s:
            with self.assertRaises(TypeError):
                s.sweep({"speed_kmh": "10,20"})
            with self.assertRaises(ValueError):
                s.sweep({"speed_kmh": [10]}, threads=0)
            with self.assertRaises(flexbond.Error):  # no axis
                s.sweep({})
            with self.assertRaises(flexbond.Error):  # an axis without a value
                s.sweep({"speed_kmh": []})


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
