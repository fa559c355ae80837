"""Planner protocols 1 and 2 against their JSON Schemas (docs/schemas): the example manifest, a request as
the coverbench binary writes it (recorded by a planner that saves what it reads), and the answers
of coverbench.serve, including a planner that raises and one that prints."""
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

import jsonschema

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.join(ROOT, "examples", "python_planner"))

from coverbench import serve  # noqa: E402
import grid_sweep  # noqa: E402


def schema(name):
    with open(os.path.join(ROOT, "docs", "schemas", name), encoding="utf-8") as f:
        return json.load(f)


MANIFEST = schema("planner-manifest.schema.json")
PROTOCOL = schema("planner-protocol.schema.json")
REQUEST = {"$ref": "#/$defs/request", "$defs": PROTOCOL["$defs"]}
ANSWER = {"$ref": "#/$defs/answer", "$defs": PROTOCOL["$defs"]}
WALL = {"name": "w", "boundary": [[0, 0], [2, 0], [2, 1], [0, 1]],
        "obstacles": [{"type": "polygon", "points": [[0.8, 0.3], [1.2, 0.3], [1.2, 0.6], [0.8, 0.6]]},
                      {"type": "circle", "x": 1.6, "y": 0.5, "radius": 0.1}]}


def request(params=None, rid=1):
    return {"protocol": 1, "id": rid,
            "problem": {"wall": WALL, "tool": {"width": 0.1, "clearance": 0.02}, "vehicle": {"model": "holonomic"},
                        "params": params or {"overlap": 0.0}, "seed": 0, "time_limit_s": 60}}


def served(planner, *requests):
    out = io.StringIO()
    serve.serve(planner, io.StringIO("".join(json.dumps(r) + "\n" for r in requests)), out)
    sys.stdout = sys.__stdout__
    return [json.loads(line) for line in out.getvalue().splitlines()]


class Protocol(unittest.TestCase):
    def test_the_example_manifest_is_valid(self):
        with open(os.path.join(ROOT, "examples", "python_planner", "grid_sweep.json"), encoding="utf-8") as f:
            jsonschema.validate(json.load(f), MANIFEST)
        with self.assertRaises(jsonschema.ValidationError):
            jsonschema.validate({"coverbench_planner": 1, "name": "Bad Name"}, MANIFEST)

    def test_the_example_answers_valid_plans_one_line_each(self):
        answers = served(grid_sweep.GridSweep(), request(rid=1), request({"overlap": 0.2}, rid=2))
        self.assertEqual([a["id"] for a in answers], [1, 2])
        for a in answers:
            jsonschema.validate(a, ANSWER)
            self.assertIn(a["status"], ("ok", "partial"))
            self.assertEqual(len(a["tool_on"]), len(a["waypoints"]) - 1)
        self.assertGreater(answers[1]["stats"]["rows"], answers[0]["stats"]["rows"])  # overlap: more rows

    def test_an_exception_is_an_error_with_its_message_and_prints_go_to_stderr(self):
        class Raises:
            def plan(self, problem):
                print("debugging output")
                raise ValueError("no luck on " + problem.wall["name"])
        [a] = served(Raises(), request())
        jsonschema.validate(a, ANSWER)
        self.assertEqual((a["status"], a["reason"]), ("error", "ValueError: no luck on w"))

    def test_an_answer_json_cannot_hold_is_an_error_and_serving_goes_on(self):
        class Unwritable:
            def __init__(self):
                self.calls = 0

            def plan(self, problem):
                self.calls += 1
                if self.calls == 1:
                    return {"status": "ok", "waypoints": [[float("nan"), 0.1], [1.0, 0.1]], "tool_on": [True]}
                if self.calls == 2:
                    return {"status": "ok", "waypoints": [[0.1, 0.1], [1.0, 0.1]], "tool_on": [True], "stats": {"x": object()}}
                return {"status": "ok", "waypoints": [[0.1, 0.1], [1.0, 0.1]], "tool_on": [True]}
        answers = served(Unwritable(), request(rid=1), request(rid=2), request(rid=3))
        self.assertEqual([a["id"] for a in answers], [1, 2, 3])
        for a in answers:
            jsonschema.validate(a, ANSWER)
        self.assertEqual([a["status"] for a in answers], ["error", "error", "ok"])
        self.assertIn("cannot be written as JSON", answers[0]["reason"])

    def test_the_binary_writes_requests_the_schema_accepts(self):
        binary = os.environ.get("COVERBENCH_BINARY", os.path.join(ROOT, "build", "coverbench"))
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "record.py"), "w", encoding="utf-8") as f:
                f.write("import json, sys\nline = sys.stdin.readline()\nopen('request.json', 'w').write(line)\n"
                        "print(json.dumps({'protocol': 1, 'id': json.loads(line)['id'], 'status': 'error', "
                        "'reason': 'recorded'}), flush=True)\n")
            with open(os.path.join(d, "record.json"), "w", encoding="utf-8") as f:
                json.dump({"coverbench_planner": 1, "name": "record", "version": "1", "summary": "s", "reference": "r",
                           "command": [sys.executable, "record.py"], "files": ["record.py"],
                           "params": [{"name": "k", "type": "choice", "default": "a", "choices": ["a", "b"],
                                       "description": "d"}]}, f)
            jsonschema.validate(json.load(open(os.path.join(d, "record.json"), encoding="utf-8")), MANIFEST)
            wall = os.path.join(ROOT, "datasets", "canonical", "living_room_north.json")
            r = subprocess.run([binary, "plan", "--wall", wall, "--planner", os.path.join(d, "record.json"),
                                "--param", "k=b", "--out", os.path.join(d, "plan.json")], capture_output=True, text=True)
            self.assertIn("recorded", r.stdout + r.stderr)
            with open(os.path.join(d, "request.json"), encoding="utf-8") as f:
                req = json.loads(f.read())
            jsonschema.validate(req, REQUEST)
            self.assertEqual(req["problem"]["params"], {"k": "b"})
            self.assertEqual(req["problem"]["tool"], {"width": 0.1, "clearance": 0.02})

    def test_protocol_2_carries_the_tools_shape_and_profile_and_answers_repeat_the_version(self):
        class Echo:
            def plan(self, problem):
                return {"status": "error", "reason": json.dumps([problem.tool_shape, problem.profile])}
        profile = {"kind": "gaussian", "sigma": 0.02, "rate": 1e-6, "depth": 0.01}
        v2 = request(rid=1)
        v2["protocol"] = 2
        v2["problem"]["tool"].update({"shape": "disk", "profile": profile})
        plain = request(rid=2)
        plain["protocol"] = 2
        plain["problem"]["tool"].update({"shape": "disk", "profile": None})
        for r in (v2, plain, request(rid=3)):
            jsonschema.validate(r, REQUEST)
        answers = served(Echo(), v2, plain, request(rid=3), dict(request(rid=4), protocol=3))
        for a in answers:
            jsonschema.validate(a, ANSWER)
        self.assertEqual([a["protocol"] for a in answers], [2, 2, 1, 2])
        self.assertEqual([json.loads(a["reason"]) for a in answers[:3]],
                         [["disk", profile], ["disk", None], ["disk", None]])
        self.assertEqual(answers[3]["reason"], "this planner speaks protocol 1 or 2, not 3")
        for shape in ("line", "rectangle"):
            jsonschema.validate(dict(v2, problem=dict(v2["problem"], tool=dict(v2["problem"]["tool"], shape=shape))),
                                REQUEST)
        with self.assertRaises(jsonschema.ValidationError):  # a shape no tool has
            jsonschema.validate(dict(v2, problem=dict(v2["problem"], tool=dict(v2["problem"]["tool"], shape="square"))),
                                REQUEST)

    def test_the_binary_writes_protocol_2_requests_the_schema_accepts(self):
        binary = os.environ.get("COVERBENCH_BINARY", os.path.join(ROOT, "build", "coverbench"))
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "record.py"), "w", encoding="utf-8") as f:
                f.write("import json, sys\nline = sys.stdin.readline()\nopen('request.json', 'w').write(line)\n"
                        "print(json.dumps({'protocol': 2, 'id': json.loads(line)['id'], 'status': 'error', "
                        "'reason': 'recorded'}), flush=True)\n")
            manifest = {"coverbench_planner": 2, "name": "record", "version": "1", "summary": "s", "reference": "r",
                        "command": [sys.executable, "record.py"], "files": ["record.py"]}
            jsonschema.validate(manifest, MANIFEST)
            with open(os.path.join(d, "record.json"), "w", encoding="utf-8") as f:
                json.dump(manifest, f)
            wall = os.path.join(ROOT, "datasets", "canonical", "living_room_north.json")
            r = subprocess.run([binary, "plan", "--wall", wall, "--planner", os.path.join(d, "record.json"),
                                "--tool-width", "0.2", "--profile", "beta", "--beta", "2", "--out", os.path.join(d, "p.json")],
                               capture_output=True, text=True)
            self.assertIn("recorded", r.stdout + r.stderr)
            with open(os.path.join(d, "request.json"), encoding="utf-8") as f:
                req = json.loads(f.read())
            jsonschema.validate(req, REQUEST)
            self.assertEqual(req["protocol"], 2)
            self.assertEqual(req["problem"]["tool"], {"width": 0.2, "clearance": 0.02, "shape": "disk",
                                                      "profile": {"kind": "beta", "beta": 2.0, "rate": 1e-6, "depth": 0.02}})


if __name__ == "__main__":
    unittest.main()
