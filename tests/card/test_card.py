"""`coverbench conformance`, the report card, can fail (issue 61, acceptance 1): five broken
planners (broken/*.json: a command that cannot start, an import of a module no interpreter has, a
segfault, a loop that never answers, a path through an obstacle) each get a card whose rows fail
naming the cause, and the command exits 1; every in-tree planner and both shipped example planners
still pass. ctest runs it as `conformance_card` (COVERBENCH_BINARY, COVERBENCH_BUILD_DIR).
"""
import json
import os
import re
import subprocess
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BINARY = os.environ.get("COVERBENCH_BINARY", os.path.join(ROOT, "build", "coverbench"))
WALLS = os.path.join(HERE, "walls")  # one wall (a window in the middle) at two tools: two rows


def card(planner, *args, env=None):
    """(exit code, JSON card, Markdown card, stderr) of `coverbench conformance PLANNER ARGS`."""
    with tempfile.TemporaryDirectory() as d:
        md, js = os.path.join(d, "card.md"), os.path.join(d, "card.json")
        first = subprocess.run([BINARY, "conformance", planner, *args, "--format", "json", "--out", js], env=env,
                               capture_output=True, text=True)
        second = subprocess.run([BINARY, "conformance", planner, *args, "--out", md], capture_output=True, text=True,
                                env=env)
        if first.returncode not in (0, 1) or not os.path.exists(js) or not os.path.exists(md):
            raise AssertionError(f"conformance {planner} gave no card (exit {first.returncode}): {first.stderr}")
        with open(js, encoding="utf-8") as f:
            j = json.load(f)
        with open(md, encoding="utf-8") as f:
            m = f.read()
    assert first.returncode == second.returncode, (first.returncode, second.returncode)
    return first.returncode, j, m, first.stderr


class BrokenPlannersFailTheirCards(unittest.TestCase):
    def check(self, name, status, *cause, time_limit="5", env=None):
        code, j, md, err = card(os.path.join(HERE, "broken", name + ".json"), "--walls", WALLS, "--time-limit", time_limit,
                                env=env)
        self.assertEqual(code, 1, err)
        self.assertEqual((j["checked"], j["passed"]), (2, 0), json.dumps(j, indent=1))
        self.assertIn(f"card-{name}: 0 of 2 passed", err)
        self.assertIn("0 of 2 passed.", md)
        failed = md[md.index("## Failed rows"):]
        for row in j["walls"]:
            self.assertFalse(row["passed"])
            self.assertEqual(row["expected"], "ok")  # F is one piece around the window
            self.assertEqual(row["status"], status, row)
            self.assertTrue(row["cause"].startswith(status + " ("), row["cause"])
            for text in cause:
                self.assertIn(text, row["reason"])
                self.assertIn(text, row["cause"])
            # The Markdown card lists the failed row with the same cause.
            line = f"- card-window (window.json, s={row['tool_width']:g} m, c={row['clearance']:g} m): "
            self.assertIn(line + row["cause"].replace("|", "\\|").replace("\n", " "), failed)
        return j

    def test_a_command_that_cannot_start(self):
        self.check("cannot-start", "crash", "could not be started: coverbench-card-no-such-program")

    def test_a_python_planner_that_imports_a_missing_module_quotes_the_import_error(self):
        self.check("missing-module", "crash", "exited with code 1",
                   "ModuleNotFoundError: No module named 'coverbench_card_no_such_module'")

    def test_a_planner_that_segfaults(self):
        self.check("segfault", "crash", "died of signal 11")

    def test_a_planner_that_exits_while_its_child_keeps_the_output_open(self):
        # A crash with its exit code at once (it read "timeout" at the limit); no child is left.
        # This run's processes carry a mark of their own in their environment (another copy of
        # the suite may run the same planner meanwhile).
        mark = f"COVERBENCH_CARD_TEST_RUN={os.getpid()}-{time.monotonic_ns()}"
        self.check("forks-and-exits", "crash", "exited with code 4", "kept its output open", time_limit="30",
                   env=dict(os.environ, COVERBENCH_CARD_TEST_RUN=mark.split("=", 1)[1]))

        def marked():
            found = []
            for pid in filter(str.isdigit, os.listdir("/proc")):
                try:
                    with open(f"/proc/{pid}/environ", "rb") as f:
                        if mark.encode() in f.read().split(b"\0"):
                            found.append(pid)
                except OSError:
                    pass
            return found
        for _ in range(50):  # the card's end kills the tree; give the kernel a moment to reap it
            left = marked()
            if not left:
                break
            time.sleep(0.1)
        self.assertEqual(left, [])

    def test_a_planner_that_never_answers(self):
        # A second of time limit: the row fails at the limit (no second plan is asked after a failure).
        self.check("loops", "timeout", "did not answer within the time limit", time_limit="1")

    def test_a_planner_whose_path_crosses_an_obstacle(self):
        j = self.check("through-obstacle", "invalid_output", "segments violate the wall or the clearance")
        for row in j["walls"]:
            self.assertFalse(row["valid"])

    def test_a_reason_that_is_not_utf8_is_kept_as_text(self):
        # A raw 0xFF ended the JSON card ("internal error: type_error.316", no card); a NUL cut
        # the reason short.
        code, j, md, err = card(os.path.join(HERE, "broken", "bad-reason.json"), "--walls", WALLS, "--time-limit", "5")
        self.assertEqual(code, 1, err)
        first, second = j["walls"]
        # An answer that is not UTF-8 is no answer; the reason quotes it as text.
        self.assertEqual(first["status"], "invalid_output")
        self.assertIn('"reason": "bad \ufffd', first["reason"])  # its first 60 bytes
        self.assertIn("is not valid UTF-8 text", first["reason"])
        # A NUL the JSON spells is kept as U+FFFD, with what follows it.
        self.assertEqual((second["status"], second["reason"]), ("error", "before \ufffd after"))
        self.assertIn("before \ufffd after", md)

    def test_endless_stderr_that_nobody_reads_holds_no_plan_past_its_limit(self):
        # The card's stderr is a pipe no one reads: the planner's flood is passed on only while
        # the pipe takes it at once (and 1 MiB a plan at most), so each row still ends at its
        # 1 s limit. It ran 75 s at a 5 s limit, until the pipe was read.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "card.json")
            r, w = os.pipe()
            p = subprocess.Popen([BINARY, "conformance", os.path.join(HERE, "broken", "endless-stderr.json"), "--walls",
                                  WALLS, "--time-limit", "1", "--format", "json", "--out", out], stderr=w,
                                 stdout=subprocess.DEVNULL)
            os.close(w)
            try:
                # The card is written (two rows of 1 s each) while no one reads its stderr; before,
                # the host waited on the full pipe and no row ended.
                for _ in range(600):
                    if os.path.exists(out) or p.poll() is not None:
                        break
                    time.sleep(0.1)
                self.assertTrue(os.path.exists(out), "no card while the stderr pipe was not read")
            finally:
                # Now read: the card's own last line goes to stderr, and it ends.
                drained = b""
                while True:
                    chunk = os.read(r, 1 << 16)
                    if not chunk:
                        break
                    drained += chunk[-200:]
                os.close(r)
                code = p.wait(timeout=60)
            self.assertEqual(code, 1)
            with open(out, encoding="utf-8") as f:
                j = json.load(f)
            self.assertEqual([row["status"] for row in j["walls"]], ["timeout", "timeout"])


def registered_planners():
    """The registry's planners, as `coverbench planners` lists them (a name and its summary per line),
    before the transit planners it lists after a blank line."""
    out = subprocess.run([BINARY, "planners"], capture_output=True, text=True, check=True).stdout
    return re.findall(r"^([a-z0-9_-]+): ", out.split("\n\n")[0], flags=re.M)


class WorkingPlannersPassTheirCards(unittest.TestCase):
    def assertPasses(self, planner, *args):
        code, j, md, err = card(planner, *args)
        failed = [f"{r['file']} s={r['tool_width']}: {r['cause']}" for r in j["walls"] if not r["passed"]]
        self.assertEqual(failed, [], planner)
        self.assertEqual(code, 0, err)
        self.assertEqual(j["passed"], j["checked"])
        self.assertNotIn("## Failed rows", md)
        return j

    def test_every_in_tree_planner_passes_on_every_conformance_wall(self):
        names = registered_planners()
        self.assertIn("zigzag", names)
        self.assertNotIn("visibility", names)
        for name in names:
            with self.subTest(planner=name):
                j = self.assertPasses(name)
                self.assertEqual(j["checked"], 40)  # 20 walls (datasets/canonical and datasets/conformance) at two tools

    def test_the_shipped_example_planners_pass(self):
        # run.sh finds the C++ example where CoverBench's build made it (COVERBENCH_BUILD_DIR).
        for manifest in ("python_planner/grid_sweep.json", "cpp_planner/column_sweep.json"):
            with self.subTest(planner=manifest):
                j = self.assertPasses(os.path.join(ROOT, "examples", manifest), "--walls",
                                      os.path.join(ROOT, "datasets", "conformance"))
                self.assertEqual(j["checked"], 20)


if __name__ == "__main__":
    unittest.main()
