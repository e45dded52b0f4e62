# SPDX-License-Identifier: BSD-3-Clause
"""The Python package against the flexbond commands on model files:
flexbond sim (ModelFile.simulate). Run by CTest with the system python3:

    py_api_files.py FLEXBOND_EXECUTABLE SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both sides call the same library functions on the same file (fb_model_sim:
the same diagram, initial state and solver settings), so they compute the
same doubles and every difference is the command's printing: probes.csv
writes 10 significant digits (%.10g: a relative 5e-10 of each value is its
rounding)."""

import os
import sys
import unittest

import flexbond
from cli_files import read_csv, run_cli

CLI = sys.argv[1]
SRC = sys.argv[2]
EXAMPLES = os.path.join(SRC, "examples")


class ModelSimTest(unittest.TestCase):
    def check(self, name, *options, **settings):
        """flexbond sim's probes.csv of examples/NAME.yaml against
        ModelFile.simulate with the same settings."""
        out = "sim_" + name
        path = os.path.join(EXAMPLES, name + ".yaml")
        run_cli(CLI, "sim", path, "-o", out, "-q", *options)
        header, table = read_csv(os.path.join(out, "probes.csv"))
        with flexbond.ModelFile(path) as model:
            result = model.simulate(**settings)
        self.assertEqual(["%s [%s]" % nu for nu in zip(result.names, result.units)], header)
        self.assertEqual(result.data.shape, table.shape)
        worst = abs(result.data - table).max(axis=0)
        scale = abs(table).max(axis=0)
        for j, name_j in enumerate(result.names):
            # Each printed value within 5e-10 of itself (a column's zero
            # prints as 0 exactly).
            within = abs(result.data[:, j] - table[:, j]) <= 5e-10 * abs(table[:, j])
            self.assertTrue(within.all(), "%s: %s off by %g of %g" % (name, name_j, worst[j],
                                                                       scale[j]))
        return result

    def test_quarter_car(self):
        """The file's own settings."""
        result = self.check("quarter_car")
        self.assertEqual(result.system, "quarter_car")

    def test_settings_from_the_call(self):
        """--t-end, --rtol and --sample-rate against the same keywords."""
        result = self.check("quarter_car_table", "--t-end", "1.5", "--rtol", "1e-8",
                            "--sample-rate", "200", t_end=1.5, rtol=1e-8, sample_rate=200)
        self.assertEqual(len(result), 301)
        self.assertAlmostEqual(result.time[-1], 1.5, delta=1e-12)

    def test_fields(self):
        self.check("two_dof_fields")

    def test_errors(self):
        """A missing file and a bad setting are flexbond.Error and ValueError."""
        with self.assertRaises(flexbond.Error):
            flexbond.ModelFile(os.path.join(EXAMPLES, "no_such_model.yaml"))
        with flexbond.ModelFile(os.path.join(EXAMPLES, "quarter_car.yaml")) as model:
            with self.assertRaises(ValueError):
                model.simulate(t_end=-1)
            with self.assertRaises(flexbond.Error):
                model.simulate(rtol=2.0)  # fb_sim_run's check: rtol in (0, 1)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
