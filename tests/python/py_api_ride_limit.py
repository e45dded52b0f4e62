# SPDX-License-Identifier: BSD-3-Clause
"""The Python package's ride-limiting speeds (Scenario.ride_limit,
docs/python.md) against flexbond ride-limit's ride_limit.csv on the same
study. Run by CTest with the system python3:

    py_api_ride_limit.py FLEXBOND_CLI SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both front ends search with the same library function
(fb_study_ride_limit) on runs made by the same calls (the scenario read
with the value, the speed and the run's end as overrides,
fb_study_ride_limit_duration, the vehicle simulated, the metric measured
by fb_study_ride_limit_measure), so they ask for the same speeds and get
the same metrics: the numbers must be equal to the last bit (the CSV
prints metrics as the shortest text that reads back to the same double,
speeds to 10 digits), the tolerance zero."""

import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest

import flexbond

CLI, SRC = sys.argv[1], sys.argv[2]
APC = os.path.join(SRC, "examples", "apc6x6.yaml")
# Two heights whose limits are found, one never reached (above) in 5..80 km/h.
HEIGHTS = ["0.1", "0.15", "0.02"]


def cli_rows(out):
    """flexbond ride-limit on the study: its rows, as lists."""
    run = subprocess.run([CLI, "ride-limit", APC, "--vary",
                          "road.bump.height=" + ",".join(HEIGHTS), "--metric", "abs_peak",
                          "--limit", "9.81", "-o", out, "-q", "--no-figures", "-j", "2"],
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        raise AssertionError("flexbond ride-limit failed (%d): %s" % (run.returncode, run.stderr))
    with open(os.path.join(out, "ride_limit.csv"), newline="", encoding="utf-8") as f:
        return list(csv.reader(f))[1:]


def same(text, value):
    """A CSV cell (empty: none) against Python's number, exactly."""
    if text == "":
        return value is None or math.isnan(value)
    return value is not None and float(text) == value


class RideLimitTest(unittest.TestCase):
    def test_against_cli(self):
        """Every row of ride_limit.csv, Python's the same to the last bit."""
        with tempfile.TemporaryDirectory() as out:
            rows = cli_rows(out)
        with flexbond.Scenario(APC) as s:
            got = s.ride_limit("road.bump.height", HEIGHTS, "abs_peak", limit=9.81, threads=2)
        self.assertEqual(len(rows), len(got))
        self.assertEqual([r.status for r in got], ["found", "found", "above"])
        for row, r in zip(rows, got):
            value, system, speed, status, metric, over, metric_over, runs, error = row
            self.assertEqual((value, system, status, int(runs)),
                             (r.value, r.system, r.status, r.runs))
            self.assertEqual(speed, "" if r.speed_kmh is None else "%.10g" % r.speed_kmh)
            self.assertEqual(over, "" if r.speed_over_kmh is None else "%.10g" % r.speed_over_kmh)
            self.assertTrue(same(metric, r.metric), (metric, r.metric))
            self.assertTrue(same(metric_over, r.metric_over), (metric_over, r.metric_over))
            self.assertEqual(error, r.error or "")

    def test_bad_metric(self):
        """A metric of no name is refused before anything runs."""
        with flexbond.Scenario(APC) as s:
            with self.assertRaises(ValueError):
                s.ride_limit("road.bump.height", ["0.1"], "power")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
