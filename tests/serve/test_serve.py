"""`coverbench serve` as a client and a user see it: the JSON API on a small experiment (filters
and sorting against the runs themselves, the run's picture and playback data, and every refusal
as a one-line JSON error), then the page in headless Chromium: filter to one planner, open a
run, play it at 0.25x and 20x (progress 80x apart within 10 %); pick two planners' runs on one
wall and play them in step; no console error. Screenshots in ARTIFACTS (env
COVERBENCH_ARTIFACTS)."""
import http.client
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.error
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
from check_page import errors, opened, play  # noqa: E402

BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SHOTS = os.environ.get("COVERBENCH_ARTIFACTS", tempfile.gettempdir())

CONFIG = """name: serve-check
output: out
datasets:
  - family: residential
    count: 3
    seed: 2
planners: [zigzag, spiral, boustrophedon]
"""


class Serve(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-serve-")
        with open(os.path.join(cls.work, "c.yaml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], check=True,
                       stdout=subprocess.DEVNULL)
        cls.db = os.path.join(cls.work, "out", "results.sqlite")
        cls.server = subprocess.Popen([BIN, "serve", cls.db, "--port", "0"], stdout=subprocess.PIPE, text=True)
        line = cls.server.stdout.readline()
        m = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not m:
            cls.server.kill()
            raise RuntimeError("serve printed: " + line)
        cls.port = int(m.group(1))
        cls.base = f"http://127.0.0.1:{cls.port}"
        cls.exp = cls.get("/api/experiments")["experiments"][0]

    @classmethod
    def tearDownClass(cls):
        cls.server.kill()
        cls.server.wait()
        cls.server.stdout.close()
        shutil.rmtree(cls.work, ignore_errors=True)

    @classmethod
    def get(cls, path):
        with urllib.request.urlopen(cls.base + path, timeout=60) as r:
            return json.load(r)

    def refused(self, method, path, body=None):
        """Status and JSON body of a request that must fail (sent as is: no client normalising)."""
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=60)
        c.request(method, path, body=body)
        r = c.getresponse()
        text = r.read().decode()
        self.assertEqual(r.getheader("Content-Type"), "application/json", text)
        msg = json.loads(text)
        self.assertEqual(list(msg), ["error"])
        self.assertEqual(len(msg["error"].splitlines()), 1)
        return r.status, msg["error"]

    def runs(self, query=""):
        return self.get(f"/api/experiments/{self.exp['db']}/{self.exp['id']}/runs?{query}")

    def test_experiments_and_runs(self):
        self.assertEqual(self.exp["name"], "serve-check")
        self.assertEqual(self.exp["runs"], 9)
        every = self.runs()
        self.assertEqual(every["total"], 9)
        self.assertEqual(sorted(every["facets"]["planner"]), ["boustrophedon", "spiral", "zigzag"])
        zig = self.runs("planner=zigzag")
        self.assertEqual(zig["total"], 3)
        self.assertTrue(all(r["planner"] == "zigzag" for r in zig["runs"]))
        cov = [r["metrics"]["coverage_reachable"] for r in self.runs("sort=coverage_reachable&order=desc")["runs"]]
        self.assertEqual(cov, sorted(cov, reverse=True))
        self.assertEqual(len(self.runs("limit=4&offset=7")["runs"]), 2)

    def test_a_runs_picture_and_playback(self):
        key = self.runs("planner=spiral&limit=1")["runs"][0]["key"]
        base = f"{self.base}/api/experiments/{self.exp['db']}/{self.exp['id']}/runs/{key}"
        with urllib.request.urlopen(base + "/picture.svg") as r:
            self.assertTrue(r.read().startswith(b"<svg"))
        with urllib.request.urlopen(base + "/playback.js") as r:
            text = r.read().decode()
        self.assertTrue(text.startswith("coverbenchPlayback({"))
        self.assertIn('"model":"v 0.3 m/s, a 0.5 m/s2, stops at turns over 30 degrees"', text)

    def test_refusals_are_json(self):
        e = f"/api/experiments/{self.exp['db']}/{self.exp['id']}"
        self.assertEqual(self.refused("GET", "/../../etc/passwd")[0], 404)  # nothing outside what it serves
        self.assertEqual(self.refused("GET", "/%2e%2e/%2e%2e/etc/passwd")[0], 404)
        self.assertEqual(self.refused("GET", "/reports/web/index.html")[0], 404)
        self.assertEqual(self.refused("GET", f"/api/experiments/7/{self.exp['id']}/runs"), (404, "no database 7 (serving 1)"))
        self.assertEqual(self.refused("GET", f"/api/experiments/{self.exp['db']}/999/runs")[0], 404)
        self.assertEqual(self.refused("GET", e + "/runs?sort=nonsense"),
                         (400, "sort: unknown column 'nonsense' (a metric, wall_name, planner, dataset, status or tool)"))
        self.assertEqual(self.refused("GET", e + "/runs?limit=5000"),
                         (400, "limit: must be a whole number from 0 to 1000, got '5000'"))
        self.assertEqual(self.refused("GET", e + "/runs/" + "0" * 64 + "/picture.svg")[0], 404)
        self.assertEqual(self.refused("POST", "/api/experiments", body=b"x" * (2 << 20)),
                         (413, "request body: over 1048576 bytes"))

    def test_what_it_cannot_serve_is_one_line_and_exit_2(self):
        for args, message in ((["/nonexistent.sqlite"], "coverbench: /nonexistent.sqlite: (file): does not exist\n"),
                              ([self.db, "--port", "70000"], "coverbench: --port: port: must be from 0 to 65535, got 70000\n")):
            r = subprocess.run([BIN, "serve", *args], capture_output=True, text=True, timeout=60)
            self.assertEqual((r.returncode, r.stderr, r.stdout), (2, message, ""))

    def test_the_page_filters_opens_and_plays_a_run(self):
        with opened(self.base + "/") as page:
            ready = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                for (let k = 0; k < 400 && !document.body.dataset.ready; ++k) await sleep(25);
                const planner = document.getElementById('planner');
                planner.value = 'zigzag';
                planner.dispatchEvent(new Event('change'));
                const rows = () => [...document.querySelectorAll('#runs tbody tr')];
                for (let k = 0; k < 400 && rows().some(r => r.cells[2].textContent !== 'zigzag'); ++k) await sleep(25);
                const planners = rows().map(r => r.cells[2].textContent);
                rows()[0].click();
                return {ready: document.body.dataset.ready, planners};
            })()""")
            self.assertEqual(ready["ready"], "1")
            self.assertEqual(ready["planners"], ["zigzag"] * 3)
            problems = play(page, os.path.join(SHOTS, "serve"))
            problems += errors(page.events)
            self.assertEqual(problems, [])

    def test_two_planners_on_one_wall_play_in_step(self):
        with opened(self.base + "/") as page:
            r = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                for (let k = 0; k < 400 && !document.body.dataset.ready; ++k) await sleep(25);
                const rows = [...document.querySelectorAll('#runs tbody tr')];
                const wall = rows[0].cells[1].textContent;
                const same = rows.filter(r => r.cells[1].textContent === wall);
                const button = document.getElementById('compare');
                const before = button.disabled;
                for (const row of same.slice(0, 2)) row.querySelector('input.pick').click();
                const enabled = !button.disabled;
                button.click();
                const viewer = document.getElementById('viewer');
                for (let k = 0; k < 400 && !viewer.coverbenchCompare; ++k) await sleep(25);
                const all = viewer.coverbenchCompare;
                all.setSpeed(20); all.seek(0); all.play();
                await sleep(1000);
                const times = all.times();
                all.pause();
                all.seek(Math.min(...all.players.map(p => p.duration())) / 2);
                viewer.scrollIntoView();
                return {before, enabled, planners: same.slice(0, 2).map(r => r.cells[2].textContent),
                        figures: viewer.querySelectorAll('figure canvas.player-canvas').length, times};
            })()""")
            self.assertTrue(r["before"], "compare is off until two runs on one wall are picked")
            self.assertTrue(r["enabled"])
            self.assertEqual(len(set(r["planners"])), 2)
            self.assertEqual(r["figures"], 2)
            # One clock: after a second at 20x both are about 20 s in, within a frame of each other.
            self.assertGreater(min(r["times"]), 15.0)
            self.assertLess(max(r["times"]) - min(r["times"]), 0.5)
            time.sleep(0.3)
            page.screenshot(os.path.join(SHOTS, "serve-compare.png"))
            self.assertEqual(errors(page.events), [])


if __name__ == "__main__":
    unittest.main()
