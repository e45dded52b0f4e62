# SPDX-License-Identifier: BSD-3-Clause
"""The Python package against the flexbond commands on model files and on
a scenario's hull mesh and graph: flexbond sim (ModelFile.simulate),
flexbond mesh (Scenario.hull_mesh, Scenario.hull_matrices), flexbond eig
(ModelFile.eigenvalues, Scenario.eigenvalues) and flexbond fmu
(Scenario.export_fmu: the same archive, byte for byte). Run by CTest with the system
python3:

    py_api_files.py FLEXBOND_EXECUTABLE SOURCE_DIR

FLEXBOND_LIBRARY names the built shared library and PYTHONPATH holds
python/; the working directory is a scratch directory of this test.

Both sides call the same library functions on the same file (fb_model_sim:
the same diagram, initial state and solver settings; fb_fe_hull_mass_props
and fb_fe_hull_section_totals for the hull, fb_bd_eigen_new for the
eigenvalues), so they compute the same doubles and every difference is the
command's printing: probes.csv writes 10 significant digits (%.10g: a
relative 5e-10 of each value is its rounding), flexbond mesh %.6g for a
mass, an inertia and a section's mass (5e-6) and %.4g for a centre of
mass, a product of inertia and a section's area (5e-4), flexbond eig %.8g
for an eigenvalue's parts (5e-8), %.6g for a natural frequency, %.4g for
a damping ratio and %.3g for the zero tolerance."""

import csv
import json
import os
import re
import shutil
import sys
import unittest
import zipfile

import numpy

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
        # The same run, step for step: stats.json's solver counts exactly.
        with open(os.path.join(out, "stats.json"), encoding="utf-8") as f:
            stats = json.load(f)
        counts = [key for key in stats if key in result.stats and key != "wall_seconds"]
        self.assertGreaterEqual(len(counts), 8)
        for key in counts:
            self.assertEqual(result.stats[key], stats[key], key)
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


def printed_near(value, text, digits):
    """value as %.{digits}g prints it (text): within half a unit of its
    last significant digit."""
    printed = float(text)
    return abs(value - printed) <= 0.5 * 10.0 ** (1 - digits) * abs(printed) * (1 + 1e-12)


def truck_with_sections():
    """examples/truck4x4.yaml with a thicker floor and heavier sides (as
    tests/cli_run.sh makes it), in the working directory beside its
    tables."""
    with open(os.path.join(EXAMPLES, "truck4x4.yaml"), encoding="utf-8") as f:
        text = f.read()
    edited = re.sub(r"^  edges:  ", "  sections:\n    - {set: FLOOR, thickness: 0.020}\n"
                    "    - {set: sides, thickness: 0.0085, nonstructural_mass: 10}\n  edges:  ",
                    text, count=1, flags=re.M)
    assert edited != text, "no '  edges:' in truck4x4.yaml"
    for name in os.listdir(EXAMPLES):
        if name.endswith(".csv"):
            shutil.copy(os.path.join(EXAMPLES, name), name)
    with open("truck_sections.yaml", "w", encoding="utf-8") as f:
        f.write(edited)
    return "truck_sections.yaml"


class HullMeshTest(unittest.TestCase):
    def assertMass(self, props, mass_line, inertia_line):
        mass = re.search(r"mass (\S+) kg, centre of mass \((\S+), (\S+), (\S+)\) m", mass_line)
        self.assertTrue(printed_near(props.mass, mass.group(1), 6), (props.mass, mass_line))
        for x, text in zip(props.cg, mass.groups()[1:]):
            self.assertTrue(printed_near(x, text, 4), (props.cg, mass_line))
        inertia = re.search(r"Ixx (\S+), Iyy (\S+), Izz (\S+), Ixz (\S+) kg m\^2", inertia_line)
        for (i, j, digits), text in zip(((0, 0, 6), (1, 1, 6), (2, 2, 6), (0, 2, 4)),
                                        inertia.groups()):
            self.assertTrue(printed_near(props.inertia[i, j], text, digits),
                            (props.inertia, inertia_line))

    def check(self, path):
        """flexbond mesh's lines against Scenario.hull_mesh."""
        lines = run_cli(CLI, "mesh", path).splitlines()
        with flexbond.Scenario(path) as scenario:
            hull = scenario.hull_mesh()
        counts = re.match(r"hull mesh: (\d+) nodes, (\d+) S3 \+ (\d+) S4 elements", lines[0])
        self.assertEqual((hull.nodes, hull.tri3, hull.quad4), tuple(map(int, counts.groups())))
        sections = [re.match(r"  (\S+) +(\d+) elements, +(\S+) m\^2, .*: (\S+) kg$", line)
                    for line in lines[1:]]
        sections = [m for m in sections if m]
        self.assertEqual(list(hull.sections), [m.group(1) for m in sections])
        for m in sections:
            totals = hull.sections[m.group(1)]
            self.assertEqual(totals.nelements, int(m.group(2)))
            self.assertTrue(printed_near(totals.area, m.group(3), 4), (totals, m.group(0)))
            self.assertTrue(printed_near(totals.mass, m.group(4), 6), (totals, m.group(0)))
        first = next(i for i, line in enumerate(lines) if line.startswith("mass "))
        self.assertMass(hull.structure, lines[first], lines[first + 1])
        built = [i for i, line in enumerate(lines) if line.startswith("with its ")]
        self.assertEqual(hull.as_built is None, not built)
        if built:
            self.assertMass(hull.as_built, lines[built[0]], lines[built[0] + 1])
            self.assertGreater(hull.as_built.mass, hull.structure.mass)
        return hull

    def test_generated_hull(self):
        self.check(os.path.join(EXAMPLES, "apc6x6.yaml"))

    def test_matrices(self):
        """Scenario.hull_matrices against --export-matrices's K.mtx and
        M.mtx, written with %.17g: the same doubles, bit for bit."""
        import scipy.io  # python3-scipy, as the exported model's tests
        path = os.path.join(EXAMPLES, "truck4x4.yaml")
        run_cli(CLI, "mesh", path, "--export-matrices", "hull_matrices")
        with flexbond.Scenario(path) as scenario:
            K, M = scenario.hull_matrices()
            nodes = scenario.hull_mesh().nodes
        for mine, name in ((K, "K.mtx"), (M, "M.mtx")):
            theirs = scipy.io.mmread(os.path.join("hull_matrices", name)).tocsc()
            self.assertEqual(mine.shape, theirs.shape)
            self.assertEqual(abs(mine - theirs).max(), 0.0, name)
            self.assertGreater(mine.nnz, 0)
        self.assertEqual(K.shape[0], 6 * nodes)

    def test_hull_with_masses(self):
        """truck4x4.yaml declares a hull mass: the hull as built too."""
        self.assertIsNotNone(self.check(os.path.join(EXAMPLES, "truck4x4.yaml")).as_built)

    def test_file_frame(self):
        """truck4x4.yaml's positions are from its front axle at floor level
        (frame.origin): the corners come back as the file wrote them (axles
        at x = 0 and -3.4 m, y = +-0.95 m; 1e-12 m: the round-off of the
        move to the centre of mass and back), and the structure's centre of
        mass is behind the front axle and above the floor, where the
        generated plates between x = -4.6 and 1.6 m, z = 0 and 1.6 m put it."""
        with flexbond.Scenario(os.path.join(EXAMPLES, "truck4x4.yaml")) as scenario:
            corners = {c.name: (c.x, c.y) for c in scenario.corners}
            cg = scenario.hull_mesh().structure.cg
        expected = {"LF": (0.0, 0.95), "RF": (0.0, -0.95), "LR": (-3.4, 0.95),
                    "RR": (-3.4, -0.95)}
        self.assertEqual(set(corners), set(expected))
        for name, (x, y) in expected.items():
            self.assertAlmostEqual(corners[name][0], x, delta=1e-12, msg=name)
            self.assertAlmostEqual(corners[name][1], y, delta=1e-12, msg=name)
        self.assertTrue(-4.6 < cg[0] < 0.0 and 0.0 < cg[2] < 1.6, cg)
        self.assertAlmostEqual(cg[1], 0.0, delta=1e-12)

    def test_sections(self):
        """Sections: each one's elements, area and mass; their masses add
        up to the structure's."""
        hull = self.check(truck_with_sections())
        self.assertEqual(set(hull.sections), {"hull.material", "FLOOR", "SIDES"})
        total = sum(s.mass for s in hull.sections.values())
        self.assertAlmostEqual(total / hull.structure.mass, 1.0, delta=1e-9)


class HullStressTest(unittest.TestCase):
    def test_against_run(self):
        """Scenario.hull_stress_peaks against flexbond run's stress_peaks.csv
        on the APC shortened to 3 s (a 0.5 m bump at 1 s): the same
        elements, centroids, peaks, times, surfaces and ranges, to the
        CSV's 10 digits (the same library calls; OpenBLAS on one thread in
        both, so the same doubles)."""
        with open(os.path.join(EXAMPLES, "apc6x6.yaml"), encoding="utf-8") as f:
            text = f.read()
        text = re.sub(r"(?m)^  t_end: 15 ", "  t_end: 3.0 ", text)
        text = text.replace("first_contact: 5.0", "first_contact: 1.0")
        text = text.replace("length: 3.70 ", "length: 0.5 ")
        with open("apc_short.yaml", "w", encoding="utf-8") as f:
            f.write(text)
        shutil.rmtree("stress_run", ignore_errors=True)
        run_cli(CLI, "run", "apc_short.yaml", "-o", "stress_run", "-q", "--no-figures",
                "--system", "flexible")
        with open("stress_run/stress_peaks.csv", newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        p = flexbond.Scenario("apc_short.yaml").hull_stress_peaks()
        self.assertEqual(len(rows), len(p.element_id))
        self.assertEqual([int(r["element_id"]) for r in rows], list(p.element_id))
        self.assertTrue((p.von_mises > 0).all() and (p.time >= p.t_from).all())
        for col, got in (("von_mises_peak [Pa]", p.von_mises), ("time [s]", p.time),
                         ("range [Pa]", p.range), ("x [m]", p.centroid[:, 0]),
                         ("y [m]", p.centroid[:, 1]), ("z [m]", p.centroid[:, 2])):
            want = numpy.array([float(r[col]) for r in rows])
            # %.10g: half a unit in the tenth digit; 1e-9 m for a centroid near 0.
            numpy.testing.assert_allclose(got, want, rtol=5e-10, atol=1e-9, err_msg=col)
        self.assertEqual([r["surface"] for r in rows], list(p.surface))
        self.assertEqual([r["range_surface"] for r in rows], list(p.range_surface))


class FmuTest(unittest.TestCase):
    """Scenario.export_fmu against flexbond fmu: the same library call, so
    the same FMU, member for member (the archive's dates are fixed)."""

    def test_against_the_command(self):
        apc = os.path.join(EXAMPLES, "apc6x6.yaml")
        spring = "suspensions.axles[0].spring_k"
        run_cli(CLI, "fmu", apc, "--system", "rigid", "--road", "inputs",
                "--parameters", spring, "-q", "-o", "cli.fmu")
        with flexbond.Scenario(apc) as s:
            info = s.export_fmu("py.fmu", "rigid", road="inputs", parameters=[spring])
        with open("cli.fmu", "rb") as a, open("py.fmu", "rb") as b:
            self.assertEqual(a.read(), b.read())
        # System 1: 28 states; the load force and each of the six wheels'
        # road height and rate; the scenario's 7 outputs and 6 tire forces.
        self.assertEqual((info["nstates"], info["ninputs"], info["noutputs"],
                          info["nparameters"], info["model_identifier"]),
                         (28, 13, 13, 1, "apc6x6"))
        self.assertEqual(info["bytes"], os.path.getsize("py.fmu"))

    def test_override_is_the_start_value(self):
        apc = os.path.join(EXAMPLES, "apc6x6.yaml")
        with flexbond.Scenario(apc, overrides={"speed_kmh": 25}) as s:
            s.export_fmu("fast.fmu", "rigid", parameters=["road.speed_kmh"])
        with zipfile.ZipFile("fast.fmu") as z:
            md = z.read("modelDescription.xml").decode()
            choices = z.read("resources/flexbond-fmu.txt").decode()
        self.assertRegex(md, r'name="road.speed_kmh"[^>]*start="25"')
        self.assertNotIn("set ", choices)  # the override became the start value

    def test_errors(self):
        apc = os.path.join(EXAMPLES, "apc6x6.yaml")
        with flexbond.Scenario(apc) as s:
            with self.assertRaises(flexbond.Error):
                s.export_fmu("bad.fmu", "rigid", parameters=["no_such_key"])
            with self.assertRaises(ValueError):
                s.export_fmu("bad.fmu", "rigid", road="nowhere")
        self.assertFalse(os.path.exists("bad.fmu"))


class EigTest(unittest.TestCase):
    def check(self, printed, eig):
        """flexbond eig's table against Eigenvalues eig: the counts, the
        zero tolerance and every row (a complex pair once, its upper
        member)."""
        head = re.match(r"\S+: (\d+) states, (\d+) real eigenvalues, (\d+) complex pairs "
                        r"\(at t = (\S+) s", printed)
        values = eig.values
        upper = [v for v in values if v.imag >= 0]
        self.assertEqual(int(head.group(1)), eig.nstates)
        self.assertEqual(int(head.group(2)), sum(v.imag == 0 for v in values))
        self.assertEqual(int(head.group(3)), sum(v.imag > 0 for v in values))
        self.assertEqual(float(head.group(4)), eig.t)
        zeros = re.search(r"(\d+) zero eigenvalues? \(\|lambda\| <= (\S+) =", printed)
        self.assertEqual(int(zeros.group(1)) if zeros else 0, eig.nstates - len(values))
        if zeros:
            self.assertTrue(printed_near(eig.zero_tol, zeros.group(2), 3))
        rows = re.findall(r"^\s+\d+\s+(\S+)\s+(?:\+/-\s+(\S+)\s+(\S+)\s+(\S+)|0)$", printed,
                          re.M)
        self.assertEqual(len(rows), len(upper))
        for v, (re_text, im_text, fn_text, zeta_text) in zip(upper, rows):
            self.assertTrue(printed_near(v.real, re_text, 8), (v, re_text))
            if not im_text:
                self.assertEqual(v.imag, 0.0)
                continue
            self.assertTrue(printed_near(v.imag, im_text, 8), (v, im_text))
            self.assertTrue(printed_near(abs(v) / (2 * numpy.pi), fn_text, 6), (v, fn_text))
            self.assertTrue(printed_near(-v.real / abs(v), zeta_text, 4), (v, zeta_text))

    def test_model_file(self):
        for name in ("quarter_car", "two_dof_fields"):
            path = os.path.join(EXAMPLES, name + ".yaml")
            with flexbond.ModelFile(path) as model:
                self.check(run_cli(CLI, "eig", path), model.eigenvalues())

    def test_scenario(self):
        """Both systems of apc6x6.yaml: System 1's zero eigenvalues (a
        statically indeterminate support) are counted alike."""
        path = os.path.join(EXAMPLES, "apc6x6.yaml")
        with flexbond.Scenario(path) as scenario:
            for system in ("rigid", "flexible"):
                eig = scenario.eigenvalues(system)
                self.check(run_cli(CLI, "eig", path, "--system", system), eig)
            self.assertGreater(scenario.eigenvalues("rigid").nstates,
                               len(scenario.eigenvalues("rigid").values))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
