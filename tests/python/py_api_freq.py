# SPDX-License-Identifier: BSD-3-Clause
"""The Python package's frequency response (Scenario.freq) and ride from a
road spectrum (Scenario.ride_psd) against flexbond freq on the same
scenarios. Run by CTest with the system python3:

    py_api_freq.py FLEXBOND_EXECUTABLE SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both sides call the same study-layer functions (fb_study_freq,
fb_study_ride_psd) with the same inputs, and both run OpenBLAS on one
thread (the command sets it; CTest sets OPENBLAS_NUM_THREADS=1 here), so
they compute the same doubles: every difference is the files' printing.
The CSV files and ride_psd.json write 10 significant digits (a relative
5e-10 of each value is its rounding), the phase 8 (5e-8), and the summary
lines %.5g, %.4g: the package's numbers are compared with those bounds,
and the summary lines by formatting the package's numbers the same way."""

import json
import os
import re
import sys
import unittest

import numpy

import flexbond
from cli_files import read_csv, run_cli

CLI = sys.argv[1]
SRC = sys.argv[2]
ISO = os.path.join(SRC, "examples", "apc6x6_iso_road.yaml")  # ISO 8608 class C, 30 km/h
APC = os.path.join(SRC, "examples", "apc6x6.yaml")  # a bump road
SYSTEMS = ("rigid", "flexible")
PRINTED = 5e-10  # %.10g's rounding, relative
PHASE_PRINTED = 5e-8  # %.8g's


def cli(*args):
    """Runs the flexbond executable; its stdout."""
    return run_cli(CLI, *args)


def close(got, want, rtol, what):
    """|got - want| within rtol of |want| (exact where want is 0)."""
    numpy.testing.assert_allclose(got, want, rtol=rtol, atol=0, err_msg=what)


class FreqTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.stdout = cli("freq", ISO, "-o", "freq_iso", "--no-figures")
        with flexbond.Scenario(ISO) as s:
            cls.fr = {name: s.freq(name) for name in SYSTEMS}

    def test_csv(self):
        """freq_systemN.csv's frequencies, |H| and phase per output and track
        are the package's to the files' printed digits."""
        for n, name in enumerate(SYSTEMS, 1):
            fr = self.fr[name]
            header, table = read_csv(os.path.join("freq_iso", "freq_system%d.csv" % n))
            self.assertEqual(table.shape[0], 301)
            close(fr.freq_hz, table[:, 0], PRINTED, "frequencies")
            col = 1
            for o, oname in enumerate(fr.names):
                for t, track in enumerate(flexbond.TRACKS):
                    self.assertTrue(header[col].startswith("%s/%s |H|" % (oname, track)))
                    close(fr.magnitude[:, o, t], table[:, col], PRINTED,
                          "%s |H| %s, %s" % (name, oname, track))
                    # A phase near 0 prints to 5e-8 of itself; 1e-12 deg covers a
                    # value printed as 0 from a rounding-sized one.
                    numpy.testing.assert_allclose(
                        fr.phase_deg[:, o, t], table[:, col + 1], rtol=PHASE_PRINTED,
                        atol=1e-12, err_msg="%s phase %s, %s" % (name, oname, track))
                    col += 2
            self.assertEqual(col, len(header))
            self.assertEqual(fr.skipped, ["shock_power_LM", "tire_power_LR"])

    def test_summary_lines(self):
        """The largest |H| the command prints, "driver_acc 401.48 (m/s^2)/m at
        11.48 Hz, left track", is the package's peaks formatted alike."""
        blocks = re.split(r"^System \d \(\w+ hull\).*$", self.stdout, flags=re.M)[1:]
        self.assertEqual(len(blocks), 2, self.stdout)
        for name, block in zip(SYSTEMS, blocks):
            fr = self.fr[name]
            for oname, (big, f, track) in fr.peaks.items():
                found = re.search(r"^  %s +(\S+) \S+ at (\S+) Hz, (\w+) track$" % oname,
                                  block, flags=re.M)
                self.assertIsNotNone(found, block)
                self.assertEqual(found.group(1), "%.5g" % big)
                self.assertEqual(found.group(2), "%.4g" % f)
                self.assertEqual(found.group(3), track)
            # The peak is the largest of the table (C's hypot and numpy's abs
            # may round |z| apart by an ulp).
            for o, oname in enumerate(fr.names):
                close(fr.peaks[oname][0], fr.magnitude[:, o, :].max(), 4e-16, oname)


class RidePSDTest(unittest.TestCase):
    def check(self, directory, stdout, rides):
        """ride_psd.json, psd_systemN.csv and the ride's summary lines
        against the package's RidePSD of each system (rides)."""
        with open(os.path.join(directory, "ride_psd.json"), encoding="utf-8") as f:
            doc = json.load(f)
        first = next(iter(rides.values()))
        road = first.road
        self.assertEqual(doc["road"]["class"], road.road_class)
        close(road.gd0, doc["road"]["gd0_m3"], PRINTED, "gd0")
        close(road.band, doc["road"]["band_cycles_per_m"], PRINTED, "band")
        close(road.speed, doc["road"]["speed_m_s"], PRINTED, "speed")
        self.assertEqual(doc["road"]["tracks"], road.tracks)
        for n, name in enumerate(SYSTEMS, 1):
            if name not in rides:
                self.assertNotIn("system%d" % n, doc)
                continue
            ride, mine = rides[name], doc["system%d" % n]
            self.assertEqual(mine["linearised"], ride.linearised)
            self.assertEqual(mine["a_w_output"], ride.a_w_output)
            close(ride.a_w, mine["a_w_rms"], PRINTED, "%s a_w" % name)
            self.assertEqual(sorted(mine["rms"]), sorted(ride.rms))
            for oname, rms in ride.rms.items():
                close(rms, mine["rms"][oname], PRINTED, "%s r.m.s. %s" % (name, oname))
            header, table = read_csv(os.path.join(directory, "psd_system%d.csv" % n))
            close(ride.freq_hz, table[:, 0], PRINTED, "band frequencies")
            close(ride.road_psd, table[:, 1], PRINTED, "road PSD")
            col = 2
            for oname, psd in ride.psd.items():
                self.assertTrue(header[col].startswith(oname + " ["), header[col])
                close(psd, table[:, col], PRINTED, "%s PSD %s" % (name, oname))
                col += 1
                if oname == ride.a_w_output:
                    close(ride.weighted, table[:, col], PRINTED, "weighted PSD")
                    col += 1
            self.assertEqual(col, len(header))
            line = re.search(r"^  System %d .*: a_w (\S+) m/s\^2 \((\w+)\); r\.m\.s\.(.*)$" % n,
                             stdout, flags=re.M)
            self.assertIsNotNone(line, stdout)
            self.assertEqual(line.group(1), "%.4g" % ride.a_w)
            self.assertEqual(line.group(2), ride.a_w_output)
            printed = dict(re.findall(r" (\w+) (\S+) \S+", line.group(3)))
            self.assertEqual(printed, {k: "%.4g" % v for k, v in ride.rms.items()})

    def test_scenario_road(self):
        """The scenario's own ISO 8608 road (class C at 30 km/h), independent
        tracks, both systems."""
        stdout = cli("freq", ISO, "-o", "psd_iso", "--no-figures")
        with flexbond.Scenario(ISO) as s:
            rides = {name: s.ride_psd(name) for name in SYSTEMS}
        self.assertEqual(rides["rigid"].road.road_class, "C")
        self.assertEqual(rides["rigid"].road.tracks, "independent")
        self.check("psd_iso", stdout, rides)
        # The flexible hull moves the driver's a_w by a few per cent.
        self.assertNotEqual(rides["rigid"].a_w, rides["flexible"].a_w)

    def test_class_named(self):
        """A class named on a bump road's scenario (--road-class b, --tracks
        identical), System 1 alone; progress heard."""
        stdout = cli("freq", APC, "-o", "psd_b", "--no-figures", "--system", "rigid",
                     "--road-class", "b", "--tracks", "identical")
        heard = []
        with flexbond.Scenario(APC) as s:
            ride = s.ride_psd("rigid", road_class="b", tracks="identical",
                              progress=lambda stage, f: heard.append(stage))
            with self.assertRaises(ValueError):
                s.ride_psd("rigid")  # the bump is no ISO 8608 road
            with self.assertRaises(ValueError):
                s.ride_psd("rigid", road_class="Z")
        self.assertEqual((ride.road.road_class, ride.road.tracks), ("B", "identical"))
        self.check("psd_b", stdout, {"rigid": ride})


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
