# SPDX-License-Identifier: BSD-3-Clause
"""The Python package's stepping interface (flexbond.Simulation,
docs/python.md) against Scenario.run and against statics. Run by CTest
with the system python3:

    py_api_step.py SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test."""

import os
import sys
import unittest
import warnings

import numpy

import flexbond

SRC = sys.argv[1]
APC = os.path.join(SRC, "examples", "apc6x6.yaml")
TRUCK = os.path.join(SRC, "examples", "truck4x4.yaml")

# System 1 over the bump at 36 km/h: the left front wheel meets it at 0.5 s,
# the last wheel leaves it before 1.5 s.
OVER_BUMP = {"speed_kmh": 36, "first_contact": 0.5, "t_end": 2.0}
# From the static equilibrium, the bump at the run's end (after 7.6 s).
AT_REST = {"initial": "static", "speed_kmh": 72, "first_contact": 7.6, "t_end": 8.2}


def reactions(sim):
    """The sum of the tires' reactions (N)."""
    return sum(v for k, v in sim.outputs.items() if k.startswith("contact_force_"))


def worst_difference(sim, run, times, change=None):
    """The largest |step - run| of any output over its range in the run, at
    times (advancing sim to each); change(sim, t) runs after each advance."""
    # An output constant over the run (System 1's torsion) in its own unit.
    ranges = {n: numpy.ptp(run[n]) or 1.0 for n in sim.names}
    worst = 0.0
    for t in times:
        sim.advance(t)
        k = int(round(t * 1000))  # the run samples at 1000 Hz
        assert abs(run.time[k] - t) < 1e-12
        for name, value in sim.outputs.items():
            worst = max(worst, abs(value - run[name][k]) / ranges[name])
        if change is not None:
            change(sim, t)
    return worst


class StepsAgainstRun(unittest.TestCase):
    def setUp(self):
        self.scenario = flexbond.Scenario(APC, overrides=OVER_BUMP)
        self.run_result = self.scenario.run("rigid")
        self.times = [0.1 * i for i in range(1, 21)]

    def tearDown(self):
        self.scenario.close()

    def check_outputs_equal_run(self, system, run):
        with self.scenario.simulation(system) as sim:
            self.assertEqual(sim.names, run.names[1:])
            self.assertEqual(sim.units["driver_acc"], run.unit("driver_acc"))
            self.assertEqual(sim.time, 0.0)
            worst = worst_difference(sim, run, self.times)
        # Both integrate with the scenario's rtol 1e-6 and differ only where
        # the stepper shortens a step to land on a stop time: of the order
        # of the runs' own global error (measured 1.7e-6 of an output's
        # range for System 1, 3.8e-8 for System 2). 1e-4 fails for outputs
        # read 1 ms off (an acceleration moves by a percent of its range
        # over the bump in 1 ms).
        print("%s steps vs run: worst |difference| / range %.3g" % (system, worst),
              file=sys.stderr)
        self.assertLess(worst, 1e-4)

    def test_outputs_equal_run(self):
        self.check_outputs_equal_run("rigid", self.run_result)

    def test_flexible_outputs_equal_run(self):
        self.check_outputs_equal_run("flexible", self.scenario.run("flexible"))

    def test_unchanged_scenario_goes_on_from_the_state(self):
        """set() with the value the scenario already has realises the vehicle
        again at every 0.1 s and goes on from the state reached: the run's
        numbers still, which a restart from rest or from the initial state
        would miss by the whole response."""
        with self.scenario.simulation("rigid") as sim:
            worst = worst_difference(sim, self.run_result, self.times[:-1],
                                     lambda sim, t: sim.set({"speed_kmh": 36}))
            sim.advance(2.0)
            with self.assertRaises(flexbond.Error) as cm:  # nothing left to go on with
                sim.set({"speed_kmh": 36})
            self.assertEqual(cm.exception.key, "t_end")
        # Each restart is at order 1 with a fresh history, within rtol.
        print("rebuilt every 0.1 s vs run: worst %.3g" % worst, file=sys.stderr)
        self.assertLess(worst, 1e-4)


class Changes(unittest.TestCase):
    def test_load_force_and_weight_against_statics(self):
        """A load force of 20 kN up from 0.5 s, a load 30 kN heavier from 4 s
        (set, a value of the scenario): once settled, the tires carry 20 kN
        less, then 30 kN more. At rest the forces on the vehicle balance,
        whatever its springs (Newton's second law)."""
        with flexbond.Scenario(APC, overrides=AT_REST) as s, s.simulation("rigid") as sim:
            self.assertEqual(sim.inputs, {"load_force": 0.0})
            n0 = reactions(sim)
            sim.advance(0.5).set({"load_force": 20e3})
            self.assertEqual(sim.inputs, {"load_force": 20e3})
            sim.advance(4.0)
            n1 = reactions(sim)
            sim.set({"total_weight": 117720 + 30e3})
            self.assertEqual(sim.time, 4.0)
            self.assertEqual(sim.inputs, {"load_force": 20e3})  # held through the change
            sim.advance(7.5)
            n2 = reactions(sim)
        # 3.5 s of settling leave about 5e-5 of each change (the slowest
        # mode near 1.5 Hz, damping ratio about 0.3): 1 N; bound 10 N.
        print("reactions %.3f -> %.3f -> %.3f N" % (n0, n1, n2), file=sys.stderr)
        self.assertAlmostEqual(n1, n0 - 20e3, delta=10.0)
        self.assertAlmostEqual(n2, n1 + 30e3, delta=10.0)

    def test_errors(self):
        with flexbond.Scenario(APC, overrides=OVER_BUMP) as s:
            sim = s.simulation("rigid")
        sim.advance(0.3)  # the simulation keeps its own copy of the scenario
        with self.assertRaises(flexbond.Error) as cm:
            sim.advance(0.2)
        self.assertEqual(cm.exception.key, "t")
        with self.assertRaises(flexbond.Error):
            sim.advance(2.5)  # past t_end
        with self.assertRaises(flexbond.Error) as cm:
            sim.set_input("road_height", 0.1)
        self.assertEqual(cm.exception.key, "road_height")
        with self.assertRaises(KeyError):
            sim.output("no_such_output")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", flexbond.PlausibilityWarning)
            truck = flexbond.Scenario(TRUCK)
        with self.assertRaises(flexbond.Error) as cm:
            sim.set_scenario(truck)  # four corners, not six
        self.assertIn("states", str(cm.exception))
        truck.close()
        self.assertEqual(sim.time, 0.3)
        sim.advance(0.4)  # unchanged by the refusal
        sim.close()
        with self.assertRaises(ValueError):
            sim.advance(0.5)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
