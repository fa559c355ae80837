"""A tool's flux profile from Python (docs/deposition.md): read and checked by the command line's
code (the same messages), and the five coat metrics it adds, against a hand value."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))

import coverbench  # noqa: E402

WALL = os.path.join(ROOT, "datasets", "canonical", "living_room_north.json")
BINARY = os.environ.get("COVERBENCH_BINARY", os.path.join(ROOT, "build", "coverbench"))
COAT = ["thickness_mean", "thickness_cv", "even_share", "thin_share", "thick_share"]
# A 3 x 1 m wall without obstacles.
STRIP = {"name": "strip", "boundary": [[0, 0], [3, 0], [3, 1], [0, 1]]}


class Profile(unittest.TestCase):
    def test_one_uniform_pass_lays_the_rate_over_width_times_speed(self):
        # One straight pass at y = 0.5 with the default time model (0.3 m/s, ramps of 0.5 m/s^2 at
        # both ends), s = 0.2 m, Q = 1e-6 m^3/s. A pass 1 m longer has the same ramps and 1 m more
        # at cruise, where a uniform fan lays Q / (s v) across its width s (docs/deposition.md):
        # the mean over R grows by Q / (s v) * (s * 1 m) / area(R).
        s, q, v = 0.2, 1e-6, 0.3
        short = coverbench.score(STRIP, [[0.5, 0.5], [1.5, 0.5]], [True], tool_width=s, profile="uniform")
        long = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s, profile={"kind": "uniform"})
        for m in (short, long):
            for name in COAT:
                self.assertIsInstance(m[name], float, name)
            self.assertAlmostEqual(m["even_share"] + m["thin_share"] + m["thick_share"], 1.0, places=12)
        self.assertEqual(short["reachable_area"], long["reachable_area"])
        cruise_um = (long["thickness_mean"] - short["thickness_mean"]) * long["reachable_area"] / (s * 1.0)
        self.assertAlmostEqual(cruise_um / (q / (s * v) * 1e6), 1.0, delta=1e-4)  # 16.667 µm (measured 1.1e-5 off)
        # Everything else is conserved too: the mean is Q times the driving time over R's area.
        self.assertAlmostEqual(long["thickness_mean"] / (q * long["duration_s"] / long["reachable_area"] * 1e6), 1.0,
                               delta=1e-4)
        # Twice the rate, twice the coat; the shares are of the mean and do not change.
        double = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s,
                                  profile={"kind": "uniform", "rate": 2e-6})
        self.assertAlmostEqual(double["thickness_mean"] / long["thickness_mean"], 2.0, places=12)
        self.assertEqual(double["even_share"], long["even_share"])
        # A target thickness (micrometres): the shares are of it. The pass's coat at cruise is
        # Q / (s v); against that target its swath at cruise is even, against twice it thin; the
        # mean and the CV do not change, and the shares still add up to 1.
        coat_um = q / (s * v) * 1e6
        aimed = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s,
                                 profile={"kind": "uniform", "target": coat_um})
        twice = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s,
                                 profile={"kind": "uniform", "target": 2 * coat_um})
        for m in (aimed, twice):
            self.assertEqual(m["thickness_mean"], long["thickness_mean"])
            self.assertEqual(m["thickness_cv"], long["thickness_cv"])
            self.assertAlmostEqual(m["even_share"] + m["thin_share"] + m["thick_share"], 1.0, places=12)
        # The swath at cruise (1.82 m of the 2 m pass, ramps of 0.09 m) is 0.2 x 1.82 m of R's area.
        self.assertGreaterEqual(aimed["even_share"], 0.2 * 1.82 / long["reachable_area"] - 0.01)
        self.assertLess(twice["even_share"], aimed["even_share"])
        # A gun whose flow follows the speed lays the cruise coat on the ramps too (docs/deposition.md):
        # the same mean as the 2 m at cruise would give, more of the swath even, and a lower CV.
        following = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s,
                                     profile={"kind": "uniform", "target": coat_um, "flow": "speed"})
        self.assertGreater(following["even_share"], aimed["even_share"])
        self.assertLess(following["thickness_cv"], aimed["thickness_cv"])
        self.assertLess(following["thickness_mean"], aimed["thickness_mean"])
        self.assertGreater(twice["thin_share"], aimed["thin_share"] + 0.2 * 1.82 / long["reachable_area"] - 0.01)
        self.assertGreater(long["thick_share"], aimed["thick_share"])  # the swath is over 1.1 times the mean
        # Without a profile (None, or kind none) there are no coat metrics.
        for none in (None, "none", {}):
            plain = coverbench.score(STRIP, [[0.5, 0.5], [2.5, 0.5]], [True], tool_width=s, profile=none)
            self.assertFalse(set(COAT) & set(plain), none)

    def test_a_plan_with_a_profile_is_scored_as_the_command_scores_it(self):
        profile = {"kind": "beta", "beta": 2.5}
        ours = coverbench.plan(WALL, "boustrophedon", {"coat_ripple": 0.05}, tool_width=0.3, profile=profile)
        self.assertEqual((ours["status"], ours["valid"]), ("ok", True))
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "p.json")
            subprocess.run([BINARY, "plan", "--wall", WALL, "--planner", "boustrophedon", "--tool-width", "0.3",
                            "--profile", "beta", "--beta", "2.5", "--param", "coat_ripple=0.05", "--out", out],
                           capture_output=True, check=True)
            with open(out, encoding="utf-8") as f:
                theirs = json.load(f)
            # `metrics` scores the plan file with the profile it carries.
            metrics = json.loads(subprocess.run([BINARY, "metrics", "--wall", WALL, "--plan", out, "--tool-width", "0.3"],
                                                capture_output=True, text=True, check=True).stdout)
        self.assertEqual(ours["waypoints"].tolist(), theirs["waypoints"])  # rows spaced for the same profile
        for name in COAT:
            self.assertEqual(ours[name], metrics[name], name)
        # Rows spaced for the profile (coat_ripple) are closer than without it.
        self.assertNotEqual(len(ours["tool_on"]), len(coverbench.plan(WALL, "boustrophedon", tool_width=0.3)["tool_on"]))
        self.assertFalse(set(COAT) & set(coverbench.plan(WALL, "zigzag")))

    def test_runs_carry_the_tools_profile(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "c.yaml"), "w", encoding="utf-8") as f:
                f.write("name: py\noutput: out\ndatasets:\n  - suite: seed-cases\n  - family: field\n    count: 1\n"
                        "    seed: 3\nplanners: [zigzag]\n"
                        "tool:\n  width: 0.3\n  profile: {kind: gaussian, sigma: 0.02}\n")
            subprocess.run([BINARY, "run", os.path.join(d, "c.yaml"), "--no-report"], capture_output=True, check=True)
            rows = coverbench.runs(os.path.join(d, "out", "results.sqlite"))
        self.assertTrue(rows)
        for r in rows:
            self.assertEqual(r["profile"], "gaussian 0.02 m")
            self.assertEqual(list(r)[9], "profile")  # after tool_width and clearance
            if r["status"] != "ok":
                continue
            if "the coat's metrics are not scored" in r["reason"]:  # a wall past the coat raster's cap
                self.assertIsNone(r["thickness_mean"])
            else:
                self.assertGreater(r["thickness_mean"], 0.0)
        # Both kinds occur at sigma 2 cm: the seed cases are scored, the field of 2.8 ha is not (cells
        # of 4 mm: 9.9e9 samples, past kMaxCoatSamples).
        self.assertTrue(any(r["thickness_mean"] is not None for r in rows))
        self.assertTrue(any(r["thickness_mean"] is None for r in rows))

    def cli_problem(self, *flags):
        r = subprocess.run([BINARY, "metrics", "--wall", WALL, "--plan", self.plan_file, *flags],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 2, r.stderr)
        return r.stderr.strip().split(": ", 3)[3]  # coverbench: SOURCE: FIELD: PROBLEM

    def test_a_bad_profile_is_the_command_lines_one_line_message(self):
        with tempfile.TemporaryDirectory() as d:
            self.plan_file = os.path.join(d, "p.json")
            subprocess.run([BINARY, "plan", "--wall", WALL, "--planner", "zigzag", "--out", self.plan_file],
                           capture_output=True, check=True)
            cases = [  # Python's profile, its message, the same problem on the command line
                ({"kind": "beta", "beta": 0.5}, "profile: beta: must be in [1, 100], got 0.5", ["--profile", "beta", "--beta", "0.5"]),
                ({"kind": "gaussian", "sigma": 0.001}, "profile: sigma: must be in [s/50, 100] m (s/50 = 0.002 m), got 0.001",
                 ["--profile", "gaussian", "--sigma", "0.001"]),
                ({"kind": "uniform", "rate": 0}, "profile: rate: must be in (0, 1] m3/s, got 0", ["--profile", "uniform", "--rate", "0"]),
                ({"kind": "uniform", "depth": 0.5}, "profile: depth: must be in [s/1000, s] m (or 0: s/10; s = 0.1 m), got 0.5",
                 ["--profile", "uniform", "--fan-depth", "0.5"]),
                ({"kind": "gaussian"}, "profile: sigma: is missing: a gaussian profile's standard deviation, m",
                 ["--profile", "gaussian"]),
                ({"kind": "cone"}, "profile: kind: must be none, uniform, gaussian or beta, got 'cone'", ["--profile", "cone"]),
                ({"kind": "uniform", "target": 0}, "profile: target: must be in (0, 1e+06] um, got 0",
                 ["--profile", "uniform", "--target", "0"]),
                ({"kind": "uniform", "target": -25}, "profile: target: must be in (0, 1e+06] um, got -25",
                 ["--profile", "uniform", "--target", "-25"]),
            ]
            for profile, message, flags in cases:
                with self.assertRaises(ValueError) as caught:
                    coverbench.score(WALL, [[0.2, 0.2], [1.0, 0.2]], [True], profile=profile)
                self.assertEqual(str(caught.exception), message)
                with self.assertRaises(ValueError) as caught:
                    coverbench.plan(WALL, "zigzag", profile=profile)
                self.assertEqual(str(caught.exception), message)
                self.assertEqual(self.cli_problem(*flags), message.split(": ", 2)[2], flags)
        # What belongs to another kind, or is not a value of a profile, spelled for Python.
        for profile, message in [
                ({"kind": "uniform", "rate": float("nan")}, "profile: rate: must be in (0, 1] m3/s, got nan"),
                ({"kind": "uniform", "sigma": 0.02}, "profile: sigma: belongs to kind gaussian"),
                ({"kind": "gaussian", "sigma": 0.02, "beta": 2}, "profile: beta: belongs to kind beta"),
                ({"sigma": 0.02}, "profile: kind: sigma, beta, rate, depth, target and flow need kind"),
                ({"kind": "uniform", "flow": "fast"}, "profile: flow: must be constant or speed, got 'fast'"),
                ({"kind": "uniform", "flow": 1}, "profile: flow: must be a string: constant or speed"),
                ({"kind": "uniform", "flow": "sp\udcffed"}, "profile: flow: is not valid text (a lone surrogate)"),
                ({"kind": "be\udcffta"}, "profile: kind: is not valid text (a lone surrogate)"),
                ({"kind": "uniform", "rate": "1e-6"}, "profile: rate: must be a number"),
                ({"kind": "uniform", "target": float("nan")}, "profile: target: must be in (0, 1e+06] um, got nan"),
                ({"kind": "uniform", "target": "25"}, "profile: target: must be a number"),
                ({"kind": "uniform", "rate": True}, "profile: rate: must be a number"),
                ({"kind": 3}, "profile: kind: must be a string: none, uniform, gaussian or beta"),
                ({"kind": "uniform", "width": 1}, "profile: width: is not a profile key (kind, sigma, beta, rate, depth, target, flow)")]:
            with self.assertRaises(ValueError) as caught:
                coverbench.score(WALL, [[0.2, 0.2], [1.0, 0.2]], [True], profile=profile)
            self.assertEqual(str(caught.exception), message)


if __name__ == "__main__":
    unittest.main()
