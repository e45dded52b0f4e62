# SPDX-License-Identifier: BSD-3-Clause
"""The Python package (python/flexbond, docs/python.md) against the CLI and
against independent answers. Run by CTest with the system python3:

    py_api.py FLEXBOND_EXECUTABLE SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test."""

import csv
import math
import json
import os
import re
import subprocess
import sys
import unittest

import numpy

import flexbond
from cli_files import read_csv, run_cli

CLI = sys.argv[1]
SRC = sys.argv[2]
APC = os.path.join(SRC, "examples", "apc6x6.yaml")
EPS = numpy.finfo(float).eps


def cli(*args):
    """Runs the flexbond executable; its stdout."""
    return run_cli(CLI, *args)


def apc_with_speed(text, path):
    """examples/apc6x6.yaml with its speed_kmh written as text, at path."""
    with open(APC, encoding="utf-8") as f:
        original = f.read()
    edited = original.replace("speed_kmh: 10 ", "speed_kmh: %s " % text, 1)
    assert edited != original, "no speed_kmh: 10 in " + APC
    with open(path, "w", encoding="utf-8") as f:
        f.write(edited)
    return path


def line_of(path, key):
    """The 1-based line of the first `key:` in a file."""
    with open(path, encoding="utf-8") as f:
        for number, text in enumerate(f, 1):
            if re.match(r"\s*%s\s*:" % re.escape(key), text):
                return number
    raise AssertionError("no %s in %s" % (key, path))


class RunTest(unittest.TestCase):
    def test_run_equals_cli_csv(self):
        """System 1's outputs equal flexbond run's system1.csv, written with 10
        significant digits: a relative 5e-10 of each value is its rounding."""
        cli("run", APC, "--system", "rigid", "-o", "run_rigid")
        header, table = read_csv(os.path.join("run_rigid", "system1.csv"))
        r = flexbond.Scenario(APC).run("rigid")
        # The CSV's header names each column with its unit: "tire_force_LF [N]".
        self.assertEqual(["%s [%s]" % (n, r.unit(n)) for n in r.names[:len(header)]], header)
        self.assertEqual(r.data.shape[0], table.shape[0])
        numpy.testing.assert_allclose(r.data[:, :len(header)], table, rtol=5e-10, atol=0)
        self.assertEqual(r.unit("tire_force_LF"), "N")
        self.assertEqual(r.names[len(header):],
                         ["contact_force_" + c.name for c in flexbond.Scenario(APC).corners])
        numpy.testing.assert_array_equal(r.time, table[:, 0])

    def test_override_equals_edited_file(self):
        """An override is the file's value: speed_kmh 20 given as an override
        runs as the file with 20 written in it (flexbond run of an edited
        copy), and differently from the file's 10."""
        fast = flexbond.Scenario(APC, overrides={"speed_kmh": 20}).run("rigid")
        cli("run", apc_with_speed("20", "fast.yaml"), "--system", "rigid", "-o", "run_fast")
        header, table = read_csv(os.path.join("run_fast", "system1.csv"))
        numpy.testing.assert_allclose(fast.data[:, :len(header)], table, rtol=5e-10, atol=0)
        slow = flexbond.Scenario(APC).run("rigid")
        self.assertFalse(numpy.array_equal(slow["tire_force_LF"], fast["tire_force_LF"]))


def apc_description():
    """examples/apc6x6.yaml's System 1 as Python data: its hull, load,
    mounts, wheels, suspensions, outputs, road and run, written by hand."""
    return {
        "scenario": "apc6x6",
        "gravity": 9.81,
        "hull": {"mass": 4041.72, "Ixx": 4173.49, "Iyy": 15175.96,
                 "material": {"young": 200e9, "poisson": 0.3, "density": 7860,
                              "thickness": 0.0085},
                 "edges": {"front_x": 2.47813311938948, "rear_x": -2.65798412344113,
                           "left_y": 1.05, "right_y": -1.05}},
        "load": {"total_weight": 117720, "payload": "weight-only",
                 "points": {"grid": {
                     "x": [-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15, 0.10, 0.40, 0.65,
                           0.95, 1.30, 1.90, 2.10],
                     "y": [-1.05, -0.55, 0.55, 1.05]}}},
        "mounts": [{"name": "driver", "mass": 100, "stiffness": 19620, "damping": 1400,
                    "x": 2.10, "y": 0.55},
                   {"name": "engine", "mass": 500, "stiffness": 122625, "damping": 24761,
                    "x": 1.70, "y": -0.55}],
        "wheel": {"mass": 175, "tire_k": 500000, "tire_c": 140000},
        "suspensions": {"motion_ratio": 1, "axles": [
            {"name": "F", "x": 1.90, "y": 1.05, "spring_k": 145300, "damper_c": 25744},
            {"name": "M", "x": 0.40, "y": 1.05, "spring_k": 345550, "damper_c": 25744},
            {"name": "R", "x": -1.00, "y": 1.05, "spring_k": 602100, "damper_c": 39656}]},
        "outputs": [{"signal": "tire_force", "of": "LF"}, {"signal": "spring_defl", "of": "RF"},
                    {"signal": "torsion"}, {"signal": "acc", "of": "driver", "name": "driver_acc"},
                    {"signal": "shock_power", "of": "LM"}, {"signal": "tire_defl", "of": "RM"},
                    {"signal": "tire_power", "of": "LR"}],
        "road": {"speed_kmh": 10,
                 "bump": {"height": 0.10, "length": 3.70, "angle_deg": 45,
                          "first_contact": 5.0}},
        "simulation": {"t_end": 15, "rtol": 1e-6, "atol": 1e-8, "sample_rate": 1000,
                       "initial": "zero"},
    }


class FromDictTest(unittest.TestCase):
    def test_dict_runs_as_its_file(self):
        """A vehicle described by Python data runs as the same description
        written in a file does (JSON, which YAML reads) and as
        examples/apc6x6.yaml, whose values it copies: the same outputs, bit
        for bit."""
        description = apc_description()
        with open("apc.json", "w", encoding="utf-8") as f:
            json.dump(description, f)
        from_data = flexbond.Scenario.from_dict(description).run("rigid")
        from_file = flexbond.Scenario("apc.json").run("rigid")
        numpy.testing.assert_array_equal(from_data.data, from_file.data)
        example = flexbond.Scenario(APC).run("rigid")
        self.assertEqual(from_data.names, example.names)
        numpy.testing.assert_array_equal(from_data.data, example.data)

    def test_hull_point_and_component_outputs(self):
        """A hull point's output and a multibond's component are outputs like
        any other: columns with their names and units; the driver's
        attachment point moves as the assembly's multibond b_attach's
        seventh component (the corners', then the mounts'), to rounding;
        a multibond without its component is refused at its data path."""
        description = apc_description()
        description["outputs"] = [
            {"signal": "hull_velocity", "at": [2.10, 0.55, -0.86306], "direction": "z"},
            {"signal": "hull_pitch"},
            {"signal": "flow", "bond": "b_attach", "component": 7}]
        r = flexbond.Scenario.from_dict(description).run("rigid")
        names = ["hull_velocity_z", "hull_pitch", "flow_b_attach_7"]
        self.assertEqual(r.names[1:4], names)
        self.assertEqual([r.unit(n) for n in names], ["m/s", "rad", "m/s"])
        scale = numpy.ptp(r["flow_b_attach_7"])
        self.assertGreater(scale, 0.1)
        numpy.testing.assert_allclose(r["hull_velocity_z"], r["flow_b_attach_7"], rtol=0,
                                      atol=1e-12 * scale)
        del description["outputs"][2]["component"]
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario.from_dict(description)
        self.assertTrue(caught.exception.message.startswith(
            "description['outputs'][2]['bond']: bond 'b_attach' is a multibond of 8 components"),
            caught.exception.message)

    def test_hull_stress_output(self):
        """A hull stress output passes through as any other: System 2's
        column, with its default name and unit, the same given by a point of
        the floor and by the id of the element holding it (48 of the
        generated mesh, beside the driver's mount); System 1, which has no
        shell elements, refuses it at its key."""
        with open(APC, encoding="utf-8") as f:
            text = f.read()
        outputs = ("outputs:\n"
                   "  - {signal: hull_stress, at: [2.0, 0.8, -0.86306], surface: top, "
                   "stress: sx}\n"
                   "  - {signal: hull_stress, element: 48, surface: top, stress: sx, "
                   "name: by_id}\n")
        self.assertIn("\noutputs:\n", text)
        with open("stress.yaml", "w", encoding="utf-8") as f:
            f.write(text.replace("\noutputs:\n", "\n" + outputs, 1))
        scenario = flexbond.Scenario("stress.yaml")
        r = scenario.run("flexible")
        self.assertEqual(r.names[1:3], ["hull_stress_sx_top", "by_id"])
        self.assertEqual(r.unit("hull_stress_sx_top"), "Pa")
        self.assertGreater(numpy.ptp(r["hull_stress_sx_top"]), 1e6)
        numpy.testing.assert_array_equal(r["hull_stress_sx_top"], r["by_id"])
        with self.assertRaises(flexbond.Error) as caught:
            scenario.run("rigid")
        self.assertIn("outputs[0].signal: System 1's hull is a rigid body",
                      caught.exception.message)

    def test_errors_name_the_data_path(self):
        """An error names the value by its path in the data, never by a line
        of the text it was read from: a range error of the reader, a rule of
        the library's check, an unknown key, a plausibility warning."""
        cases = [(("suspensions", "axles", 1, "spring_k"), -5,
                  "description['suspensions']['axles'][1]['spring_k']: must be > 0"),
                 (("mounts", 0, "x"), 9.0,
                  "description['mounts'][0]['x']: must lie on the hull's floor"),
                 (("road", "speed_kmh"), "fast", "description['road']['speed_kmh']: ")]
        for path, value, start in cases:
            description = apc_description()
            where = description
            for k in path[:-1]:
                where = where[k]
            where[path[-1]] = value
            with self.assertRaises(flexbond.Error, msg=start) as caught:
                flexbond.Scenario.from_dict(description)
            e = caught.exception
            self.assertTrue(e.message.startswith(start), e.message)
            self.assertEqual(e.path, start.split(":")[0])
            self.assertIsNone(e.file)
            self.assertNotIn("<description>", e.message)
        description = apc_description()
        description["wheel"]["tire_k"] = 1.0  # legal, implausible
        with self.assertWarns(flexbond.PlausibilityWarning) as warned:
            flexbond.Scenario.from_dict(description, name="truck")
        self.assertTrue(str(warned.warning).startswith("truck['wheel']['tire_k']: "),
                        str(warned.warning))


class HullModesTest(unittest.TestCase):
    def test_hull_modes_equal_cli(self):
        """Scenario.hull_modes lists what flexbond modes --system flexible
        writes (hull_modes.csv, modes.csv, %.10g): the same realised vehicle
        and eigen-solves, so the frequencies to their printed digits (the
        command's eigen-solve runs on two threads, this one on one: the
        frequencies move by rounding, far below 5e-10 of themselves), and
        the same descriptions."""
        cli("modes", APC, "--system", "flexible", "-o", "modes_flex")
        with open(os.path.join("modes_flex", "hull_modes.csv"), newline="",
                  encoding="utf-8") as f:
            hull_rows = list(csv.reader(f))[1:]
        with open(os.path.join("modes_flex", "modes.csv"), newline="", encoding="utf-8") as f:
            vehicle_rows = list(csv.reader(f))[1:]
        modes = flexbond.Scenario(APC).hull_modes()
        self.assertEqual(len(modes.hull_freq_hz), len(hull_rows))
        self.assertEqual(modes.nrigid, sum(row[2] == "rigid" for row in hull_rows))
        for f, row in zip(modes.hull_freq_hz[modes.nrigid:], hull_rows[modes.nrigid:]):
            self.assertTrue(abs(f - float(row[1])) <= 5e-10 * f, (f, row))
        self.assertEqual(len(modes.vehicle), len(vehicle_rows))
        for (f, description), row in zip(modes.vehicle, vehicle_rows):
            self.assertTrue(abs(f - float(row[1])) <= 5e-10 * f, (f, row))
            self.assertEqual(description, row[2])


class StudyTest(unittest.TestCase):
    """Scenario.study gives the numbers flexbond run writes in summary.json:
    the same library calls (flexbond/study.h), printed there with 10
    significant digits, so a relative 5e-10 of each value is its rounding
    (and 1e-12 absolute for a value that is 0, such as System 1's torsion).
    System 2 adds the rounding of its hull's eigen-solve, which the command
    runs on two threads and a library user on one (fb_vehicle_opts.threads),
    and of BLAS (one thread here, as in the command: CMakeLists.txt): the
    integration carries it to at most 3e-8 of an output's range over the
    response (measured: the driver's settled acceleration before the bump,
    a residual of 1e-4 m/s^2; the ride metrics 7e-9 of themselves), so
    System 2's values may differ by 1e-7 of their output's range, its ride
    metrics by 1e-7 of themselves, and an extreme's time may move to another
    sample where two extremes tie to that rounding."""

    def assertSame(self, py, js, what, scale=0.0, rtol=5e-10):
        if js is None:  # JSON's null for NaN
            self.assertTrue(math.isnan(py), what)
            return
        tol = rtol * abs(js) + max(1e-12, 1e-7 * scale)
        self.assertTrue(abs(py - js) <= tol, "%s: %r vs %r (tolerance %g)" % (what, py, js, tol))

    def study_and_summary(self, path, out, systems):
        cli("run", path, "--system", "both" if len(systems) == 2 else systems[0], "-o", out,
            "--no-figures")
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            summary = json.load(f)
        scenario = flexbond.Scenario(path)
        try:
            return scenario.study(systems), summary
        finally:
            scenario.close()

    def check_run(self, run, js, flexible):
        """run against summary.json's js; flexible: with System 2's rounding."""
        self.assertSame(run.window[0], js["bump_window"][0], "window")
        for name, st in run.outputs.items():
            o = js["outputs"][name]
            scale = o["peak"] - o["min"] if flexible else 0.0
            for field in ("static", "peak", "min", "rms"):
                self.assertSame(getattr(st, field), o[field], "%s.%s" % (name, field), scale)
            for field, value in (("peak_time", "peak"), ("min_time", "min")):
                if not flexible:
                    self.assertSame(getattr(st, field), o[field], "%s.%s" % (name, field))
                    continue
                # Two extremes that tie to System 2's rounding may swap: the
                # value at Python's time must be the command's extreme.
                at = int(numpy.argmin(abs(run.result.time - getattr(st, field))))
                self.assertSame(run.result[name][at], o[value], "%s at %s" % (name, field), scale)
        contact = js["tire_contact"]
        for tire, st in run.contact.items():
            peak, low = contact["peak_force"][tire], contact["min_force"][tire]
            scale = peak["value"] - low["value"] if flexible else 0.0
            self.assertSame(st.min, low["value"], tire + " min", scale)
            self.assertSame(st.peak, peak["value"], tire + " peak", scale)
            self.assertSame(st.static, peak["static"], tire + " static", scale)
            self.assertSame(run.contact_ratio[tire], peak["ratio"], tire + " ratio",
                            scale / peak["static"])
            at = int(numpy.argmin(abs(run.result.time - st.min_time)))
            self.assertSame(run.result["contact_force_" + tire][at], low["value"], tire, scale)
        self.assertEqual(run.spikes, contact["spikes"])
        self.assertEqual(len(run.contact_loss), len(contact["contact_loss_intervals"]))
        for loss, iv in zip(run.contact_loss, contact["contact_loss_intervals"]):
            self.assertEqual(loss.tire, iv["tire"])
            for field, key in (("start", "from"), ("end", "to"), ("min_force", "min_force"),
                               ("at", "at")):
                self.assertSame(getattr(loss, field), iv[key], "loss " + key)
        ride = js["ride"]
        self.assertEqual(run.ride is None, "note" in ride)
        if run.ride is not None:
            self.assertSame(run.ride_window[1], ride["window"][1], "ride window")
            for field, key in (("a_w_rms", "a_w_rms"), ("mtvv", "mtvv"), ("vdv", "vdv"),
                               ("crest", "crest_factor"), ("jerk_peak", "jerk_peak"),
                               ("jerk_rms", "jerk_rms"), ("absorbed_power", "absorbed_power"),
                               ("nrmm_peak", "nrmm_peak"), ("se", "se"), ("dz", "dz"),
                               ("vdv_ratio", "vdv_ratio"), ("crest_over_9", "crest_over_9")):
                self.assertSame(run.ride[field], ride[key], "ride " + key,
                                rtol=1e-7 if flexible else 5e-10)

    def test_both_systems_equal_summary_json(self):
        study, js = self.study_and_summary(APC, "study_apc", ("rigid", "flexible"))
        self.check_run(study.runs["rigid"], js["system1"], flexible=False)
        self.check_run(study.runs["flexible"], js["system2"], flexible=True)
        for name, c in study.comparison.items():
            o = js["comparison"][name]
            r1 = o["range_system1"]
            self.assertSame(c.range1, r1, name + " range_system1")
            self.assertSame(c.max_diff, o["max_abs_diff"], name + " max_abs_diff", r1)
            self.assertSame(c.rel_diff, o["max_abs_diff_rel"], name + " max_abs_diff_rel", 1.0)
            for field, key, of in (("peak_change", "peak_change_rel", "peak_system1"),
                                   ("rms_change", "rms_change_rel", "rms_system1")):
                base = abs(o[of]) if o[of] else 1.0
                self.assertSame(getattr(c, field), o[key], "%s %s" % (name, key), r1 / base)
        self.assertIsNotNone(study.runs["rigid"].ride)

    def test_contact_loss_equals_summary_json(self):
        """A wheel that leaves the road (apc6x6_liftoff.yaml): its intervals
        and spikes as summary.json lists them."""
        path = os.path.join(SRC, "examples", "apc6x6_liftoff.yaml")
        study, js = self.study_and_summary(path, "study_liftoff", ("rigid",))
        run = study.runs["rigid"]
        self.assertGreater(len(run.contact_loss), 0)
        self.assertIsNone(study.comparison)
        self.check_run(run, js["system1"], flexible=False)


class ProgressTest(unittest.TestCase):
    def test_progress_hears_stages_and_steps(self):
        """progress(stage, fraction) hears System 2's set-up stages in the
        library's words and every solver step, its fraction growing to 1."""
        heard = []
        flexbond.Scenario(APC).run("flexible", progress=lambda s, f: heard.append((s, f)))
        stages = {s for s, _ in heard if not s.startswith("simulating")}
        self.assertTrue(any("eigen-solve" in s for s in stages), stages)
        steps = [f for s, f in heard if s.startswith("simulating System 2 (flexible hull)")]
        self.assertGreater(len(steps), 100)
        self.assertEqual(steps, sorted(steps))
        self.assertAlmostEqual(steps[-1], 1.0)

    def test_progress_exception_stops_the_run(self):
        """An exception progress raises stops the library at its next report
        and reaches the caller as it was raised."""
        class Enough(Exception):
            pass

        def stop_halfway(stage, fraction):
            if stage.startswith("simulating") and fraction > 0.5:
                raise Enough(stage)

        calls = []
        with self.assertRaises(Enough):
            flexbond.Scenario(APC).run("rigid",
                                       progress=lambda s, f: (calls.append(f),
                                                              stop_halfway(s, f)))
        self.assertLess(max(calls), 0.6)  # stopped at the next step, not at the end


class InterruptTest(unittest.TestCase):
    def test_ctrl_c_stops_a_run(self):
        """SIGINT during a run stops it between solver steps (KeyboardInterrupt)
        and gives the previous handler back. The run, 1e5 s in steps of at
        most 10 ms, would take about 35 s here (1e4 s: 3.5 s); stopped 0.3 s
        in, it ends within one step."""
        import signal
        import threading
        import time
        before = signal.getsignal(signal.SIGINT)
        s = flexbond.Scenario(APC, overrides={"simulation.t_end": 1e5, "sample_rate": 0.1,
                                              "max_step": 0.01, "max_steps": 100000000})
        timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
        start = time.monotonic()
        timer.start()
        with self.assertRaises(KeyboardInterrupt):
            s.run("rigid")
        timer.join()
        self.assertLess(time.monotonic() - start, 10.0)  # far under the 35 s of the run
        self.assertIs(signal.getsignal(signal.SIGINT), before)


    def test_ctrl_c_stops_a_set_up(self):
        """Every long call raises KeyboardInterrupt at once, also in System 2's
        set-up (the hull's assembly, factorisation and eigen-solve, about
        1.6 s at density 6), and the library stops at its next report, well
        before the set-up's end: close() waits for it."""
        import signal
        import threading
        import time
        s = flexbond.Scenario(APC, overrides={"hull.mesh.density": 6})
        start = time.monotonic()
        s.export("flexible")
        whole = time.monotonic() - start  # the set-up and a linearisation, on this machine now
        for call in (lambda: s.export("flexible"), lambda: s.modes("flexible"),
                     lambda: s.run("flexible")):
            timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
            start = time.monotonic()
            timer.start()
            with self.assertRaises(KeyboardInterrupt):
                call()
            timer.join()
            # 0.2 s and the 50 ms the caller waits at a time; far under the set-up.
            self.assertLess(time.monotonic() - start, 1.0)
            # The library itself stops at its next report (every few tenths
            # of a second): the call's thread ends well before the whole
            # set-up would, however loaded the machine (close() waits for it).
            with s._calls:
                self.assertTrue(s._calls.wait_for(lambda: s._ncalls == 0, timeout=whole))
            self.assertLess(time.monotonic() - start, 0.2 + 0.7 * whole)
        s.close()
        with self.assertRaises(ValueError):  # closed: no call starts
            s.modes("rigid")


class ModesTest(unittest.TestCase):
    def test_modes_equal_cli(self):
        """flexbond modes prints the undamped natural frequencies with %g (six
        significant digits: a relative 5e-6)."""
        out = cli("modes", APC)
        undamped = next(part for part in out.split("\n\n") if "undamped natural" in part)
        printed = re.findall(r"^\s+\d+\s+(\S+)\s+(.*\S)\s*$", undamped, re.M)
        self.assertTrue(printed)
        modes = flexbond.Scenario(APC).modes("rigid", undamped=True)
        self.assertEqual(len(modes), len(printed))
        self.assertEqual(modes.nstatic, int(re.search(r"(\d+) static zero modes?", out).group(1)))
        for mode, (freq, description) in zip(modes, printed):
            self.assertAlmostEqual(mode.freq_hz / float(freq), 1.0, delta=5e-6)
            self.assertEqual(mode.description, description)
        damped = flexbond.Scenario(APC).modes("rigid")
        for mode in damped:
            # The definitions of freq_hz and damping_ratio (flexbond/vehicle.h).
            lam = mode.eigenvalue
            self.assertAlmostEqual(mode.freq_hz, abs(lam) / (2 * numpy.pi), delta=1e-12 * abs(lam))
            self.assertAlmostEqual(mode.damping_ratio, -lam.real / abs(lam), delta=1e-12)


class FreqTest(unittest.TestCase):
    def road_inputs(self, scenario, model, omega):
        """Each track's road rates, by hand: the wheels on a track (y > 0 left)
        see its height e^{j omega t} delayed by their distance behind the
        leading axle over the speed; a rate is j omega times the height."""
        corners = scenario.corners
        lead = max(c.x for c in corners)
        u = numpy.zeros((len(model.input_names), 2), dtype=complex)
        for c in corners:
            track = 0 if c.y > 0 else 1
            delay = (lead - c.x) / scenario.speed
            u[model.input_names.index("road.v_" + c.name), track] = \
                1j * omega * numpy.exp(-1j * omega * delay)
        return u

    def check_system(self, system, freqs):
        """fr.H against C (j omega E - A)^-1 B u + D u solved by SuperLU
        (scipy.sparse.linalg.splu), another sparse LU than KLU's."""
        import scipy.sparse
        import scipy.sparse.linalg as sla
        s = flexbond.Scenario(APC)
        model = s.export(system)
        fr = s.freq_response(system, freqs)
        self.assertEqual(fr.skipped, [n for n, rows in zip(model.output_names, model.output_rows)
                                      if len(rows) == 2])
        rows = [r[0] for r in model.output_rows if len(r) == 1]
        for k, f in enumerate(freqs):
            omega = 2 * numpy.pi * f
            pencil = (1j * omega * model.E - model.A).tocsc()
            # Rows then columns scaled to a largest entry of 1 (the descriptor
            # mixes stiffnesses of 1e6 N/m with the unit entries of algebraic
            # rows): the condition that bounds an LU solve's error is the
            # equilibrated matrix's (Higham, "Accuracy and Stability of
            # Numerical Algorithms", 2nd ed., 2002, secs. 7.3 and 9.8).
            r = 1 / abs(pencil).max(axis=1).toarray().ravel()
            scaled_rows = scipy.sparse.diags(r) @ pencil
            c = 1 / abs(scaled_rows).max(axis=0).toarray().ravel()
            scaled = (scaled_rows @ scipy.sparse.diags(c)).tocsc()
            lu = sla.splu(scaled)
            u = self.road_inputs(s, model, omega)
            x = c[:, None] * lu.solve(r[:, None] * (model.B @ u))
            want = (model.C @ x + model.D @ u)[rows, :]
            # Two LU solves of one matrix differ by about cond * eps relative
            # to the solution (ibid., ch. 9); cond_1 estimated (Higham &
            # Tisseur's block 1-norm estimator, scipy's onenormest) and a
            # factor 10 for the growth factors and C's sums. Measured: cond
            # about 5e7 for System 1, 2e13 for System 2 at 20 Hz, and the
            # two answers 1e-13 apart.
            inverse = sla.LinearOperator(scaled.shape, matvec=lu.solve, dtype=complex,
                                         rmatvec=lambda y: lu.solve(y, trans="H"))
            cond = sla.norm(scaled, 1) * sla.onenormest(inverse)
            tol = 10 * cond * EPS
            self.assertLess(tol, 0.1, "%s: j omega E - A too ill-conditioned at %g Hz"
                            % (system, f))
            for o in range(len(rows)):
                scale = numpy.abs(want[o, :]).max()
                err = numpy.abs(fr.H[k, o, :] - want[o, :]).max()
                self.assertLessEqual(err, tol * scale + 1e-300,
                                     "%s %s at %g Hz" % (system, fr.names[o], f))

    def test_rigid_against_superlu(self):
        self.check_system("rigid", [0.1, 1.0, 1.7, 9.7, 55.0])

    def test_flexible_against_superlu(self):
        self.check_system("flexible", [0.5, 3.0, 20.0])

    def test_shape_and_names(self):
        s = flexbond.Scenario(APC)
        fr = s.freq_response("rigid", numpy.logspace(-1, 2, 7))
        self.assertEqual(fr.H.shape, (7, len(fr.names), 2))
        self.assertEqual(fr["tire_force_LF"].shape, (7, 2))
        self.assertFalse(fr.linearised)  # apc6x6's laws are all linear
        with self.assertRaises(KeyError):
            fr["tire_power_LR"]  # a power output has no frequency response

    def test_bad_frequencies(self):
        """No frequency response is non-finite: inf, NaN, a negative value or
        one above 1 GHz (where omega E overflowed) raises flexbond.Error."""
        s = flexbond.Scenario(APC)
        for bad in (numpy.inf, numpy.nan, -1.0, 1e308):
            with self.assertRaises(flexbond.Error, msg=repr(bad)):
                s.freq_response("rigid", [1.0, bad])
        fr = s.freq_response("rigid", [1e-3, 1e9])
        self.assertTrue(numpy.all(numpy.isfinite(fr.H)))


class ExportTest(unittest.TestCase):
    def check_export_equals_cli(self, path, out, linearised):
        """The matrices flexbond export writes (Matrix Market, %.17g): E, A, C
        and f bit for bit; Bu's rate columns are B's; both say whether a
        nonlinear law made the model a linearisation."""
        import scipy.io
        cli("export", path, "--system", "rigid", "-o", out)
        model = flexbond.Scenario(path).export("rigid")
        for name in ("E", "A", "C", "f"):
            want = scipy.io.mmread(os.path.join(out, name + ".mtx")).toarray()
            numpy.testing.assert_array_equal(getattr(model, name).toarray(), want, name)
        bu = scipy.io.mmread(os.path.join(out, "Bu.mtx")).toarray()
        corners = flexbond.Scenario(path).corners
        for c, corner in enumerate(corners):
            j = model.input_names.index("road.v_" + corner.name)
            numpy.testing.assert_array_equal(model.B.toarray()[:, j], bu[:, len(corners) + c])
        self.assertEqual(model.E.shape, (len(model.var_names), len(model.var_names)))
        with open(os.path.join(out, "model.json"), encoding="utf-8") as f:
            self.assertEqual(json.load(f)["linearised"], linearised)
        self.assertEqual(model.linearised, linearised)

    def test_export_equals_cli(self):
        self.check_export_equals_cli(APC, "export_rigid", False)

    def test_nonlinear_export_equals_cli(self):
        """A damper table: both front ends linearise it at the static
        equilibrium, through the same library call."""
        self.check_export_equals_cli(os.path.join(SRC, "examples", "apc6x6_shock_table.yaml"),
                                     "export_table", True)


class ErrorTest(unittest.TestCase):
    def test_bad_override_names_file_line_key(self):
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario(APC, overrides={"speed_kmh": "fast"})
        e = caught.exception
        self.assertEqual(e.status, "FB_EPARSE")
        self.assertEqual(os.path.abspath(e.file), os.path.abspath(APC))
        self.assertEqual(e.line, line_of(APC, "speed_kmh"))
        self.assertGreater(e.column, 0)
        self.assertEqual(e.key, "road.speed_kmh")
        self.assertEqual(e.source_text, "overrides['speed_kmh']='fast'")
        self.assertTrue(e.message.startswith("overrides['speed_kmh']='fast': "), e.message)
        self.assertNotIn("--set", e.message)

    def test_vehicle_error_names_its_part_and_override(self):
        """An error the vehicle finds (more modes than the hull has) names the
        part of the description (Error.part) and, located, the override as
        Python wrote it at the file's line of hull.fe.modes."""
        s = flexbond.Scenario(APC, overrides={"hull.fe.coordinates": "modal",
                                              "hull.fe.modes": 99999})
        try:
            with self.assertRaises(flexbond.Error) as caught:
                s.run("flexible")
        finally:
            s.close()
        e = caught.exception
        self.assertEqual(e.part, ("vehicle", 0, "hull_modes", None))
        self.assertEqual(e.key, "hull.fe.modes")
        self.assertEqual(os.path.abspath(e.file), os.path.abspath(APC))
        self.assertGreater(e.line, 0)
        self.assertEqual(e.source_text, "overrides['hull.fe.modes']=99999")
        self.assertIn("99999 modes, more than the hull's", e.message)

    def test_part_kinds_follow_the_header(self):
        """Error.part's kind names are fb_part_kind's, in its order: read
        from flexbond/vehicle.h, FB_PART_<NAME> = value, so that a kind added
        in C and not here (or in another place) fails."""
        header = open(os.path.join(SRC, "include", "flexbond", "vehicle.h")).read()
        enum = header[header.index("typedef enum fb_part_kind"):]
        enum = enum[:enum.index("} fb_part_kind;")]
        kinds = {int(v): n.lower() for n, v in re.findall(r"FB_PART_(\w+) = (\d+)", enum)}
        count_value = max(kinds)
        count = kinds.pop(count_value)  # FB_PART_KINDS, the count
        self.assertEqual(count, "kinds")
        # Python names a hull mass as the description's list does.
        kinds = {i: {"none": None, "hull_mass": "point_mass"}.get(n, n) for i, n in kinds.items()}
        # A kind assigned but not in this header (a gap of the enum) is None.
        names = [kinds.get(i) for i in range(count_value)]
        self.assertEqual(tuple(names), flexbond._PART_KINDS)

    def test_nul_is_refused(self):
        """C would read text only up to a NUL: an override "12\\x0099" as 12.
        A NUL in a value, a key or the path raises Error, naming what."""
        cases = [({"speed_kmh": "12\x0099"}, APC, "override value"),
                 ({"speed_kmh\x00junk": 12}, APC, "override key"),
                 ({}, APC + "\x00.x", "path")]
        for overrides, path, what in cases:
            with self.assertRaises(flexbond.Error, msg=what) as caught:
                flexbond.Scenario(path, overrides=overrides)
            self.assertEqual(caught.exception.status, "FB_EINVAL")
            self.assertIn(what, caught.exception.message)
            self.assertIn("NUL", caught.exception.message)

    def test_data_file_field_is_an_excerpt(self):
        """A data file's failing field is Error.excerpt, never in the message
        (which may go into an output file); str(error) shows it."""
        with open(os.path.join(SRC, "examples", "apc6x6_shock_table.yaml"),
                  encoding="utf-8") as f:
            text = f.read().replace("shock_front.csv", "py_bad_table.csv")
        with open("py_table.yaml", "w", encoding="utf-8") as f:
            f.write(text)
        for name in ("shock_rear.csv",):
            with open(os.path.join(SRC, "examples", name), encoding="utf-8") as src, \
                    open(name, "w", encoding="utf-8") as dst:
                dst.write(src.read())
        with open("py_bad_table.csv", "w", encoding="utf-8") as f:
            f.write("v,F\n0,0\n1,SECRET\n")
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario("py_table.yaml")
        e = caught.exception
        self.assertEqual(e.excerpt, "SECRET")
        self.assertNotIn("SECRET", e.message)
        self.assertTrue(e.message.endswith("py_bad_table.csv:3: column 'F': not a number"),
                        e.message)
        self.assertTrue(str(e).endswith("(read: 'SECRET')"), str(e))

    def test_implausible_value(self):
        """A tire of 1 N/m is legal but implausible: a PlausibilityWarning at
        its file:line:col, kept in warnings; strict=True raises Error."""
        import warnings
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            s = flexbond.Scenario(APC, overrides={"tire_k": 1})
        self.assertTrue(s.warnings and all("implausible" in w for w in s.warnings))
        self.assertEqual([str(w.message) for w in caught], s.warnings)
        self.assertTrue(all(w.category is flexbond.PlausibilityWarning for w in caught))
        self.assertIn(":%d:" % line_of(APC, "tire_k"), s.warnings[0])
        with self.assertRaises(flexbond.Error) as raised:
            flexbond.Scenario(APC, overrides={"tire_k": 1}, strict=True)
        self.assertEqual(raised.exception.key, "wheel.tire_k")
        self.assertEqual(raised.exception.status, "FB_EINVAL")
        self.assertIn("1 N/m is implausible", raised.exception.message)
        self.assertIn("strict=True refuses implausible values: 2", str(raised.exception))
        self.assertEqual(flexbond.Scenario(APC, strict=True).warnings, [])

    def test_error_in_file(self):
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario(apc_with_speed("-10", "bad.yaml"))
        e = caught.exception
        self.assertEqual((e.file, e.line, e.key), ("bad.yaml", line_of("bad.yaml", "speed_kmh"),
                                                   "road.speed_kmh"))
        self.assertIsNone(e.source_text)

    def test_missing_file_and_unknown_key(self):
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario("no-such-file.yaml")
        self.assertEqual(caught.exception.status, "FB_EIO")
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario(APC, overrides={"no_such_key": 1})
        self.assertIn("no_such_key", caught.exception.message)

    def test_model_file_is_named(self):
        """A model file where a scenario is expected is named as one, at its
        model key (the loader's check, shared with every command)."""
        path = os.path.join(SRC, "examples", "quarter_car.yaml")
        with self.assertRaises(flexbond.Error) as caught:
            flexbond.Scenario(path)
        e = caught.exception
        self.assertEqual((e.key, e.line, e.column), ("model", line_of(path, "model"), 1))
        self.assertIn("this is a model file", e.message)

    def test_bad_system(self):
        with self.assertRaises(ValueError):
            flexbond.Scenario(APC).run("stiff")


class ReadmeTest(unittest.TestCase):
    def test_readme_example_runs(self):
        """The README's Python example, run from the source directory."""
        with open(os.path.join(SRC, "README.md"), encoding="utf-8") as f:
            section = f.read().split("\n## Python", 1)[1].split("\n## ", 1)[0]
        blocks = re.findall(r"```python\n(.*?)```", section, re.S)
        self.assertEqual(len(blocks), 1)
        self.assertLessEqual(len(blocks[0].strip().splitlines()), 10)
        done = subprocess.run([sys.executable, "-c", blocks[0]], cwd=SRC, check=False,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertTrue(done.stdout.strip())


    def test_optimisation_loop_runs(self):
        """docs/python.md's optimisation loop, run from the source directory:
        it ends within the travel limit with a smaller a_w than it started
        from (COBYLA keeps the best point it evaluated)."""
        with open(os.path.join(SRC, "docs", "python.md"), encoding="utf-8") as f:
            section = f.read().split("\n## An optimisation loop", 1)[1].split("\n## ", 1)[0]
        blocks = re.findall(r"```python\n(.*?)```", section, re.S)
        self.assertEqual(len(blocks), 1)
        done = subprocess.run([sys.executable, "-c", blocks[0]], cwd=SRC, check=False,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        found = re.search(r"driver a_w: ([\d.]+) m/s\^2 \(was ([\d.]+)\)", done.stdout)
        self.assertIsNotNone(found, done.stdout)
        self.assertLess(float(found.group(1)), float(found.group(2)))
        left = re.search(r"travel left: (-?[\d.]+) m", done.stdout)
        self.assertIsNotNone(left, done.stdout)
        self.assertGreaterEqual(float(left.group(1)), -1e-4)

if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
