"""The allanlab Python module against the allanlab command (the same numbers on the same record)
and against closed forms on records numpy draws (a generator apart from sim/).

Usage: allanlab_module_test.py ALLANLAB_BINARY (PYTHONPATH must reach build/python)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import allanlab

BINARY = sys.argv.pop(1) if len(sys.argv) > 1 else "build/allanlab"
RATE_HZ = 100.0


def run(*args):
    done = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(f"allanlab {' '.join(args)}: exit {done.returncode}: {done.stderr}")
    return done


def write_csv(path, rate_deg_s):
    """time_s and the rate with 17 significant digits: the command reads the same doubles."""
    t = np.arange(rate_deg_s.size) / RATE_HZ
    np.savetxt(path, np.column_stack([t, rate_deg_s]), fmt="%.17g", delimiter=",", header="time_s,rate_deg_s",
               comments="")


class ModuleAgainstCommand(unittest.TestCase):
    """Same record, module vs `allanlab ... --json`: equal to the last bit (one route each)."""

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        rng = np.random.default_rng(7)
        n = 20000
        # White rate noise plus a rate random walk, deg/s.
        cls.x = 0.05 * rng.standard_normal(n) + np.cumsum(2e-4 * rng.standard_normal(n))
        cls.csv = os.path.join(cls.dir.name, "rec.csv")
        write_csv(cls.csv, cls.x)

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def cli_json(self, *args):
        out = os.path.join(self.dir.name, "out.json")
        run(*args, "--json", out)
        with open(out) as f:
            return json.load(f)

    def test_every_estimator_and_interval_equals_the_command(self):
        for estimator in ["overlapping", "nonoverlapping", "modified", "hadamard", "hadamard_nonoverlapping", "total",
                          "time"]:
            for ci in ["auto", "gr", "simple"]:
                with self.subTest(estimator=estimator, ci=ci):
                    j = self.cli_json("avar", self.csv, "--units", "deg/s", "--out-units", "deg/s", "--estimator",
                                      estimator, "--ci", ci, "--taus", "decade")
                    r = allanlab.avar(self.x, rate_hz=RATE_HZ, units="deg/s", estimator=estimator, ci=ci,
                                      taus="decade")
                    self.assertEqual(r.statistic, j["estimator"]["statistic"])
                    self.assertEqual(r.units, j["units"]["dev"])
                    p = j["points"]
                    self.assertGreater(len(p), 3)
                    np.testing.assert_array_equal(r.tau_s, [q["tau_s"] for q in p])
                    np.testing.assert_array_equal(r.dev, [q["dev"] for q in p])
                    np.testing.assert_array_equal(r.edf, [q["edf"] for q in p])
                    np.testing.assert_array_equal(r.dev_low, [np.nan if q["dev_low"] is None else q["dev_low"] for q in p])
                    np.testing.assert_array_equal(r.dev_high, [np.nan if q["dev_high"] is None else q["dev_high"] for q in p])

    def test_fit_equals_the_command(self):
        j = self.cli_json("fit", self.csv, "--units", "deg/s")
        r = allanlab.fit(self.x, rate_hz=RATE_HZ, units="deg/s")
        self.assertEqual(set(r.coefficients), {k for k, e in j["coefficients"].items() if "unit" in e})
        for name, c in r.coefficients.items():
            e = j["coefficients"][name]
            self.assertEqual((c.value, c.sigma, c.unit), (e.get("value"), e.get("sigma"), e["unit"]), name)
        self.assertEqual((r.chi2, r.dof, r.poor_fit), (j["fit"]["chi2"], j["fit"]["dof"], j["fit"]["poor_fit"]))

    def test_diagnose_equals_the_command(self):
        j = self.cli_json("diagnose", self.csv, "--units", "deg/s", "--trials", "4", "--seed", "3")
        r = allanlab.diagnose(self.x, rate_hz=RATE_HZ, units="deg/s", trials=4, seed=3)
        self.assertEqual(r.verdict, j["verdict"]["effect"])
        self.assertEqual(r.significant, j["gap"]["significant"])
        self.assertEqual(r.json["candidates"], j["candidates"])

    def test_diagnose_reads_an_accelerometer_axis_as_the_command(self):
        # White acceleration noise of 2 mg at 100 Hz, in g: VRW N = sigma / sqrt(fs), m/s/sqrt(h) x 60.
        sigma_g = 2e-3
        a = -1.0 + sigma_g * np.random.default_rng(5).standard_normal(20000)
        path = os.path.join(self.dir.name, "accel.csv")
        t = np.arange(a.size) / RATE_HZ
        np.savetxt(path, np.column_stack([t, a]), fmt="%.17g", delimiter=",", header="time_s,Accel_X_g", comments="")
        j = self.cli_json("diagnose", path, "--column", "Accel_X_g", "--trials", "4", "--seed", "3")["columns"][0]
        r = allanlab.diagnose(a, rate_hz=RATE_HZ, units="g", trials=4, seed=3)
        self.assertEqual(r.verdict, j["verdict"]["effect"])
        self.assertEqual(r.json["candidates"], j["candidates"])
        self.assertEqual(r.json["baseline"], j["baseline"])
        n = r.json["baseline"]["coefficients"]["N"]
        self.assertEqual(n["unit"], "m/s/sqrt(h)")
        vrw = sigma_g * 9.80665 / np.sqrt(RATE_HZ) * 60.0
        # The AVAR at tau0 alone has a relative sd of ~1 % on 20000 samples: 5 % is 5 sd.
        self.assertAlmostEqual(n["value"], vrw, delta=0.05 * vrw)
        # The same samples in mg and m/s^2: the same diagnosis.
        for units, scale in [("mg", 1e3), ("m/s^2", 9.80665)]:
            other = allanlab.diagnose(a * scale, rate_hz=RATE_HZ, units=units, trials=4, seed=3)
            self.assertEqual(other.verdict, r.verdict, units)
            self.assertAlmostEqual(other.json["baseline"]["coefficients"]["N"]["value"], n["value"],
                                   delta=1e-9 * n["value"], msg=units)

    def test_simulate_equals_the_command(self):
        out = os.path.join(self.dir.name, "sim.f64")
        run("simulate", "--preset", "mg25_mems", "--duration", "60", "--seed", "11", "--trial", "2", "--units",
            "rad/s", "--format", "f64", "-o", out)
        rec = allanlab.simulate("mg25_mems", duration_s=60, seed=11, trial=2)
        np.testing.assert_array_equal(rec.rate, np.fromfile(out, dtype="<f8"))
        self.assertEqual(rec.time_s[1], 1.0 / rec.sample_rate_hz)


class ModuleAgainstClosedForms(unittest.TestCase):
    """White rate noise of standard deviation sigma drawn by numpy: E[AVAR(tau)] = sigma^2 / m
    for the overlapping, modified (m = 1 only: MVAR = AVAR) and Hadamard (sigma^2/m as well)
    estimators, N = sigma / sqrt(fs), and an ARW-only sensor's exact OAVAR N^2 / tau."""

    def test_white_noise_curve(self):
        sigma, n = 0.1, 1 << 16
        x = sigma * np.random.default_rng(2024).standard_normal(n)
        for estimator in ["overlapping", "hadamard", "total"]:
            r = allanlab.avar(x, rate_hz=RATE_HZ, units="deg/s", out_units="deg/s", estimator=estimator)
            expected = sigma**2 / r.m
            # Each point within 5 of its own relative standard deviation sqrt(2 / edf), edf as the
            # command reports it (false-fail rate about 1e-5 over the ~13 taus of 3 estimators).
            z = (r.var / expected - 1.0) / np.sqrt(2.0 / r.edf)
            self.assertLess(np.max(np.abs(z)), 5.0, f"{estimator}: z = {z}")

    def test_white_noise_fit(self):
        sigma, n = 0.1, 1 << 16  # deg/s
        x = sigma * np.random.default_rng(99).standard_normal(n)
        f = allanlab.fit(x, rate_hz=RATE_HZ, units="deg/s")
        truth = sigma / np.sqrt(RATE_HZ) * 60.0  # deg/sqrt(h)
        # The white-noise level from 65536 samples: standard error ~0.3 %; 3 % is > 5 of it.
        self.assertAlmostEqual(f.coefficients["N"].value / truth, 1.0, delta=0.03)
        self.assertEqual(f.coefficients["N"].unit, "deg/sqrt(h)")

    def test_expected_avar_of_an_arw_sensor(self):
        with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as f:
            f.write("name: white\nsample_rate: 50 Hz\nterms:\n  - {type: arw, N: 0.01 deg/s/sqrt(Hz)}\n")
        try:
            rec = allanlab.simulate(sensor=f.name, duration_s=100, seed=1)
            m = np.array([1, 2, 4, 8, 16])
            n_rad = np.deg2rad(0.01)
            np.testing.assert_allclose(rec.expected_avar(m), n_rad**2 / (m / 50.0), rtol=1e-12)
        finally:
            os.unlink(f.name)


class ModuleInputs(unittest.TestCase):
    def test_columns_give_a_result_each(self):
        x = np.random.default_rng(1).standard_normal((4096, 3))
        results = allanlab.avar(x, rate_hz=RATE_HZ, units="rad/s")
        self.assertEqual(len(results), 3)
        np.testing.assert_array_equal(results[1].dev, allanlab.avar(x[:, 1].copy(), rate_hz=RATE_HZ, units="rad/s").dev)

    def test_bad_inputs_raise_one_clear_error(self):
        x = np.random.default_rng(1).standard_normal(1000)
        y = x.copy()
        y[10] = np.nan
        with self.assertRaisesRegex(RuntimeError, "sample 10 is not finite"):
            allanlab.avar(y, rate_hz=RATE_HZ, units="rad/s")
        with self.assertRaisesRegex(ValueError, "^estimator: unknown 'alan'"):
            allanlab.avar(x, rate_hz=RATE_HZ, units="rad/s", estimator="alan")
        with self.assertRaisesRegex(ValueError, "^rate_hz must be"):
            allanlab.avar(x, rate_hz=-1.0, units="rad/s")
        with self.assertRaisesRegex(ValueError, "^units: unknown rate unit 'furlongs'"):
            allanlab.avar(x, rate_hz=RATE_HZ, units="furlongs")
        with self.assertRaisesRegex(RuntimeError, "^values: 2 samples; at least"):
            allanlab.avar(x[:2], rate_hz=RATE_HZ, units="rad/s")
        with self.assertRaisesRegex(ValueError, "unknown preset"):
            allanlab.simulate("nope", duration_s=10)

    def test_errors_name_the_python_arguments(self):
        """Messages come from the command line's checks; they name the keyword arguments, not
        the options (min_tau_s, not --min-tau)."""
        x = np.random.default_rng(1).standard_normal(1000)
        cases = [
            (lambda: allanlab.avar(x, RATE_HZ, "rad/s", out_units="m/s"), "^out_units: unknown"),
            (lambda: allanlab.avar(x, RATE_HZ, "rad/s", taus="blah"), "^taus: "),
            (lambda: allanlab.avar(x, RATE_HZ, "rad/s", ci="blah"), "^ci: unknown"),
            (lambda: allanlab.avar(x, RATE_HZ, "rad/s", confidence=2.0), "^confidence must be"),
            (lambda: allanlab.fit(x, RATE_HZ, "rad/s", band_limit="blah"), "^band_limit: unknown"),
            (lambda: allanlab.fit(x, RATE_HZ, "rad/s", min_tau_s=10.0, max_tau_s=1.0),
             "^min_tau_s must be below max_tau_s$"),
            (lambda: allanlab.diagnose(x, RATE_HZ, "rad/s", float_terms="N"),
             "^float_terms needs sensor or preset$"),
            (lambda: allanlab.diagnose(x, RATE_HZ, "g", preset="tg100"),
             "^units g make the values an accelerometer axis; preset and sensor describe a gyro"),
            (lambda: allanlab.diagnose(x, RATE_HZ, "mg", type="angle"), "^type: an accelerometer axis"),
            (lambda: allanlab.simulate(duration_s=10), "^give exactly one of preset or sensor$"),
            (lambda: allanlab.simulate("mg25_mems", duration_s=-1.0), "^duration_s must be"),
        ]
        for call, pattern in cases:
            with self.assertRaisesRegex(ValueError, pattern) as raised:
                call()
            self.assertNotIn("--", str(raised.exception))

if __name__ == "__main__":
    unittest.main(verbosity=1)
