"""`import coverbench`: walls, planners, both judges and an experiment's runs from Python, checked
against the command line's own answers."""
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


class Package(unittest.TestCase):
    def test_planners_are_the_registry(self):
        out = subprocess.run([BINARY, "planners"], capture_output=True, text=True, check=True).stdout
        names = [p["name"] for p in coverbench.planners()]
        self.assertEqual(len(names), 6)
        for name in names:
            self.assertIn(name, out)
        zigzag = next(p for p in coverbench.planners() if p["name"] == "zigzag")
        overlap = next(s for s in zigzag["params"] if s["name"] == "overlap")
        self.assertEqual((overlap["type"], overlap["min"], overlap["max"]), ("number", 0.0, 0.9))

    def test_a_plan_is_the_commands_plan_and_both_judges_score_it(self):
        ours = coverbench.plan(WALL, "zigzag", {"overlap": 0.1})
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([BINARY, "plan", "--wall", WALL, "--planner", "zigzag", "--param", "overlap=0.1", "--out",
                            os.path.join(d, "p.json")], capture_output=True, check=True)
            with open(os.path.join(d, "p.json"), encoding="utf-8") as f:
                theirs = json.load(f)
        # Waypoints as a numpy (n, 2) array (Debian's python3 has numpy).
        import numpy
        self.assertIsInstance(ours["waypoints"], numpy.ndarray)
        self.assertEqual(ours["waypoints"].shape, (len(theirs["waypoints"]), 2))
        self.assertEqual(ours["waypoints"].tolist(), theirs["waypoints"])
        self.assertEqual(ours["tool_on"], theirs["tool_on"])
        # Where it follows F's round boundary (round the obstacles' corners) the path is arcs.
        self.assertEqual(ours["bulge"], theirs["bulge"])
        self.assertGreater(sum(b != 0 for b in ours["bulge"]), 0)
        m = coverbench.score(WALL, ours["waypoints"], ours["tool_on"], bulge=ours["bulge"], judge="exact")
        self.assertIs(m["valid"], True)  # a bool, not the metric's 1.0
        self.assertEqual((m["violations"], m["violating_segments"]), (0, []))
        self.assertIs(m["exact"]["valid"], True)
        lo, hi = m["exact"]["coverage_reachable"]
        self.assertLessEqual(lo, hi)
        self.assertGreater(m["coverage_reachable"], 0.99)
        # A path through the window: both judges say invalid.
        bad = coverbench.score(WALL, [[0.2, 1.0], [4.0, 1.0]], [True], judge="exact")
        self.assertIs(bad["valid"], False)
        self.assertEqual((bad["violations"], bad["violating_segments"]), (1, [0]))
        # What it hit, by hand: the window (obstacle 0, x 1.0 to 2.2, y 0.9 to 2.1) holds the
        # line y = 1 from x = 1.0 to 2.2, so the tool's centre is inside it: clearance 0 - r.
        (hit,) = bad["violation_details"]
        self.assertEqual((hit["segment"], hit["from"], hit["to"]), (0, [0.2, 1.0], [4.0, 1.0]))
        self.assertEqual((hit["obstacle"], hit["obstacle_label"], hit["too_close"]), (0, "window", True))
        self.assertAlmostEqual(hit["clearance"], -0.05, places=12)
        self.assertIn('segment 0 (0.2, 1)->(4, 1) enters obstacle "window"', bad["invalid_reason"])
        self.assertEqual((m["violation_details"], m["invalid_reason"]), ([], ""))
        self.assertIs(bad["exact"]["valid"], False)
        # The same from a numpy array, and the segment named among several.
        three = numpy.array([[0.2, 0.3], [0.5, 0.3], [2.5, 1.5], [2.6, 1.5]])  # the middle one crosses the window
        self.assertEqual(coverbench.score(WALL, three, [True, True, True])["violating_segments"], [1])

    def test_bad_input_is_a_value_error_with_the_one_line_message(self):
        with self.assertRaisesRegex(ValueError, "boundary: needs at least 3 distinct points"):
            coverbench.check_wall({"name": "x", "boundary": [[0, 0], [1, 0]]})
        with self.assertRaisesRegex(ValueError, "params: overlap: .*0.9"):
            coverbench.plan(WALL, "zigzag", {"overlap": 2})
        with self.assertRaisesRegex(ValueError, "unknown planner"):
            coverbench.plan(WALL, "nope")
        with self.assertRaisesRegex(ValueError, "params: "):
            coverbench.plan(WALL, "zigzag", {"overlap": float("nan")})
        with self.assertRaisesRegex(ValueError, "params: overlap: 'x' is not a finite number"):
            coverbench.plan(WALL, "zigzag", {"overlap": "x"})

    def test_params_of_any_python_type_are_read_as_their_text(self):
        # The parameter codec reads them (as it reads the server's): 0.1 and "0.1" are one value.
        a = coverbench.plan(WALL, "zigzag", {"overlap": 0.1, "boundary_passes": 2})
        b = coverbench.plan(WALL, "zigzag", {"overlap": "0.1", "boundary_passes": "2"})
        self.assertEqual(a["waypoints"].tolist() if hasattr(a["waypoints"], "tolist") else a["waypoints"],
                         b["waypoints"].tolist() if hasattr(b["waypoints"], "tolist") else b["waypoints"])
        self.assertNotEqual(len(a["tool_on"]), len(coverbench.plan(WALL, "zigzag", {"boundary_passes": 0})["tool_on"]))

    def external(self, d, name, body):
        with open(os.path.join(d, name + ".py"), "w", encoding="utf-8") as f:
            f.write("import json, subprocess, sys\nfor line in sys.stdin:\n    req = json.loads(line)\n" + body)
        with open(os.path.join(d, name + ".json"), "w", encoding="utf-8") as f:
            json.dump({"coverbench_planner": 1, "name": name, "version": "1", "summary": "s", "reference": "r",
                       "command": ["/usr/bin/python3", name + ".py"], "files": [name + ".py"]}, f)
        return os.path.join(d, name + ".json")

    def test_an_external_planners_path_is_judged_as_the_command_judges_it(self):
        # A path entirely outside the wall, which the planner calls ok: invalid_output here, as a
        # run stores it, and INVALID from `coverbench plan` (one code path judges both).
        with tempfile.TemporaryDirectory() as d:
            manifest = self.external(d, "outside", "    print(json.dumps({'protocol': 1, 'id': req['id'], 'status': 'ok', "
                                     "'waypoints': [[-5, -5], [-4, -5]], 'tool_on': [True]}), flush=True)\n")
            ours = coverbench.plan(WALL, manifest)
            r = subprocess.run([BINARY, "plan", "--wall", WALL, "--planner", manifest, "--out", os.path.join(d, "p.json")],
                               capture_output=True, text=True)
        self.assertEqual(r.returncode, 3)
        self.assertIn("INVALID", r.stdout)
        self.assertEqual(ours["status"], "invalid_output")
        self.assertEqual(ours["planner_status"], "ok")
        self.assertIs(ours["valid"], False)
        self.assertEqual(ours["violations"], 1)
        self.assertEqual(ours["violating_segments"], [0])
        self.assertIn("segments violate the wall or the clearance", ours["reason"])
        # A registered planner's valid path stays ok.
        good = coverbench.plan(WALL, "zigzag")
        self.assertEqual((good["status"], good["valid"]), ("ok", True))

    def test_an_external_planner_is_held_to_the_memory_limit_with_its_children(self):
        # Its child touches 600 MiB; memory_mb=300 holds the planner's processes together. The time
        # limit is one it cannot reach first.
        with tempfile.TemporaryDirectory() as d:
            manifest = self.external(d, "hog", "    subprocess.run(['/usr/bin/python3', '-c', 'b = bytearray(600 << 20)\\n"
                                     "for i in range(0, len(b), 4096): b[i] = 1'])\n"
                                     "    print(json.dumps({'protocol': 1, 'id': req['id'], 'status': 'error', "
                                     "'reason': 'survived'}), flush=True)\n")
            out = coverbench.plan(WALL, manifest, memory_mb=300, time_limit_s=600)
        self.assertEqual(out["status"], "memory_limit", out["reason"])
        self.assertIn("memory limit of 300 MiB", out["reason"])

    def test_an_experiments_runs_as_dicts(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "c.yaml"), "w", encoding="utf-8") as f:
                f.write("name: py\noutput: out\ndatasets:\n  - suite: seed-cases\nplanners: [zigzag, spiral]\n")
            subprocess.run([BINARY, "run", os.path.join(d, "c.yaml"), "--no-report"], capture_output=True, check=True)
            rows = coverbench.runs(os.path.join(d, "out", "results.sqlite"))
            self.assertEqual({r["planner"] for r in rows}, {"zigzag", "spiral"})
            for r in rows:
                self.assertIn(r["status"], ("ok", "partial", "no_reachable_area"))
                self.assertIn("coverage_reachable", r)
            # With pandas (Debian's python3-pandas, scripts/setup.sh): one row per run, the same columns.
            frame = coverbench.runs_dataframe(os.path.join(d, "out", "results.sqlite"))
            self.assertEqual(len(frame), len(rows))
            self.assertEqual(list(frame.columns), list(rows[0].keys()))
            self.assertEqual(sorted(frame["planner"].unique()), ["spiral", "zigzag"])
            self.assertEqual(frame["coverage_reachable"].tolist(), [r["coverage_reachable"] for r in rows])


if __name__ == "__main__":
    unittest.main()
