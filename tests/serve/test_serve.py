"""`coverbench serve` as a client and a user see it: the JSON API (filters and sorting against
the runs themselves, the run's picture and playback data, every refusal as a one-line JSON
error), the viewer's pan and zoom, the workbench's API (planners from the registry, walls checked with the command line's
messages, plans in a worker process under the time limit, walls saved and opened), then the page
in headless Chromium: filter to one planner, open a run, play it at 0.25x and 20x (progress 80x
apart within 10 %); pick two planners' runs on one wall and play them in step; open a run's wall in
the workbench, plan it, change a parameter and re-plan, draw a window and re-plan, edit the wall
into an invalid one and see the command line's message; no console error. Screenshots in
ARTIFACTS (env COVERBENCH_ARTIFACTS).

By default it runs a small experiment to serve; with COVERBENCH_SERVE_DB=results.sqlite it serves
that database instead (the main job's: `COVERBENCH_SERVE_DB=results/default/results.sqlite
python3 tests/serve/test_serve.py`)."""
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
import urllib.parse
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
from check_page import errors, opened, play  # noqa: E402

BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SOURCE = os.path.join(HERE, "..", "..")
SHOTS = os.environ.get("COVERBENCH_ARTIFACTS", tempfile.gettempdir())
os.makedirs(SHOTS, exist_ok=True)

CONFIG = """name: serve-check
output: out
datasets:
  - family: residential
    count: 3
    seed: 2
planners: [zigzag, spiral, boustrophedon]
"""


def read(path):
    with open(path) as f:
        return f.read()


class Serve(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-serve-")
        cls.small = not os.environ.get("COVERBENCH_SERVE_DB")
        if cls.small:
            with open(os.path.join(cls.work, "c.yaml"), "w") as f:
                f.write(CONFIG)
            subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], check=True,
                           stdout=subprocess.DEVNULL)
            cls.db = os.path.join(cls.work, "out", "results.sqlite")
        else:
            cls.db = os.environ["COVERBENCH_SERVE_DB"]
        cls.walls = os.path.join(cls.work, "walls")
        os.makedirs(cls.walls)
        shutil.copy(os.path.join(SOURCE, "datasets", "canonical", "seed_10x8_3obs.json"), cls.walls)
        cls.walls_db = os.path.join(cls.work, "saved.sqlite")
        cls.server = subprocess.Popen([BIN, "serve", cls.db, "--port", "0", "--walls", cls.walls, "--walls-db", cls.walls_db,
                                       "--plan-time-limit", "20"], stdout=subprocess.PIPE, text=True)
        line = cls.server.stdout.readline()
        m = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
        if not m:
            cls.server.kill()
            raise RuntimeError("serve printed: " + line)
        cls.port = int(m.group(1))
        cls.base = f"http://127.0.0.1:{cls.port}"
        cls.exp = cls.get("/api/experiments")["experiments"][-1]

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
        c.close()
        self.assertEqual(r.getheader("Content-Type"), "application/json", text)
        msg = json.loads(text)
        self.assertEqual(list(msg), ["error"])
        self.assertEqual(len(msg["error"].splitlines()), 1)
        return r.status, msg["error"]

    def runs(self, query=""):
        return self.get(f"/api/experiments/{self.exp['db']}/{self.exp['id']}/runs?{query}")

    def post(self, path, body):
        """Status and JSON answer of a POST."""
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=120)
        c.request("POST", path, body=json.dumps(body) if not isinstance(body, (bytes, str)) else body,
                  headers={"Content-Type": "application/json"})
        r = c.getresponse()
        text = r.read().decode()
        c.close()
        self.assertEqual(r.getheader("Content-Type"), "application/json", text)
        return r.status, json.loads(text)

    def test_experiments_and_runs(self):
        every = self.runs("limit=1000")
        self.assertEqual(every["total"], self.exp["runs"])
        if self.small:
            self.assertEqual((self.exp["name"], self.exp["runs"]), ("serve-check", 9))
            # In the config's order, not the order of the runs' keys.
            self.assertEqual(every["facets"]["planner"], ["zigzag", "spiral", "boustrophedon"])
            self.assertEqual(every["facets"]["tool"], ["s=0.1 m, c=0.02 m"])
        # Each filter selects exactly the runs with that value; together they hold every run.
        for facet in ("planner", "status", "tool"):
            counts = 0
            for value in every["facets"][facet]:
                some = self.runs(f"{facet}={urllib.parse.quote(value)}&limit=1000")
                self.assertTrue(all(r[facet] == value for r in some["runs"]), (facet, value))
                counts += some["total"]
            self.assertEqual(counts, every["total"], facet)
        self.assertEqual(self.runs("planner=no-such-planner")["total"], 0)
        for metric in ("coverage_reachable", "overlap"):
            for order, reverse in (("asc", False), ("desc", True)):
                rows = self.runs(f"sort={metric}&order={order}&limit=1000")["runs"]
                values = [r["metrics"][metric] for r in rows if metric in r["metrics"]]
                self.assertEqual(values, sorted(values, reverse=reverse))
                # runs without the metric (failed runs) come last in either order
                have = [metric in r["metrics"] for r in rows]
                self.assertEqual(have, sorted(have, reverse=True))
        names = [r["wall_name"] for r in self.runs("sort=wall_name&limit=1000")["runs"]]
        self.assertEqual(names, sorted(names))
        total = every["total"]
        self.assertEqual(len(self.runs(f"limit=4&offset={total - 2}")["runs"]), 2)

    def test_the_api_description_names_every_route(self):
        import yaml
        with open(os.path.join(SOURCE, "docs", "openapi.yaml")) as f:
            paths = set(yaml.safe_load(f)["paths"])
        served = {"/api/experiments", "/api/experiments/{db}/{id}/runs", "/api/experiments/{db}/{id}/runs.csv", "/api/metrics",
                  "/api/experiments/{db}/{id}/values",
                  "/api/experiments/{db}/{id}/runs/{key}/picture.svg", "/api/experiments/{db}/{id}/runs/{key}/coat.svg",
                  "/api/experiments/{db}/{id}/runs/{key}/playback.js", "/api/experiments/{db}/{id}/runs/{key}/problem",
                  "/api/experiments/{db}/{id}/runs/{key}/outcome",
                  "/api/planners", "/api/check", "/api/plan", "/api/plans/{id}/picture.svg", "/api/plans/{id}/playback.js",
                  "/api/walls", "/api/walls/folder/{i}", "/api/walls/db/{name}"}
        self.assertEqual(paths, served)

    def test_planners_come_from_the_registry(self):
        listed = subprocess.run([BIN, "planners"], capture_output=True, text=True, check=True).stdout
        names = [line.split(":")[0] for line in listed.splitlines() if line and not line.startswith(" ")]
        planners = self.get("/api/planners")["planners"]
        self.assertEqual([p["name"] for p in planners], names[:len(planners)])
        zigzag = {s["name"]: s for s in planners[0]["params"]}
        self.assertEqual({k: zigzag["sweep_angle"][k] for k in ("type", "min", "max", "unit", "default")},
                         {"type": "number", "min": 0.0, "max": 180.0, "unit": "deg", "default": 0.0})
        self.assertIn("choices", next(s for p in planners for s in p["params"] if s["type"] == "choice"))

    def test_a_wall_is_checked_with_the_command_lines_messages(self):
        good = read(os.path.join(self.walls, "seed_10x8_3obs.json"))
        ok = self.post("/api/check", {"wall": good, "planner": "zigzag", "params": {"sweep_angle": 90}})
        self.assertEqual(ok, (200, {"ok": True, "name": "seed-10x8-3obs", "obstacles": 3, "wall": ok[1]["wall"]}))
        bad = {
            "negative width": good.replace('"width": 10.0', '"width": -3'),
            "a typo": good.replace('"height": 8.0', '"heigth": 8.0'),
            "an obstacle outside": good.replace('"x": 7.0', '"x": 70.0'),
            "not JSON": good[:-5],
            "a bow-tie boundary": '{"name": "b", "boundary": [[0,0],[1,1],[1,0],[0,1]]}',
        }
        for what, text in bad.items():
            path = os.path.join(self.work, "bad.json")
            with open(path, "w") as f:
                f.write(text)
            cli = subprocess.run([BIN, "plan", "--wall", path, "--planner", "zigzag", "--out", os.path.join(self.work, "p.json")],
                                 capture_output=True, text=True)
            self.assertEqual(cli.returncode, 2, what)
            prefix = f"coverbench: {path}: "
            self.assertTrue(cli.stderr.startswith(prefix), cli.stderr)
            status, answer = self.post("/api/check", {"wall": text})
            self.assertEqual((status, answer), (200, {"ok": False, "error": "wall: " + cli.stderr[len(prefix):].rstrip("\n")}), what)
            status, answer = self.post("/api/plan", {"wall": text, "planner": "zigzag"})
            self.assertEqual((status, answer["error"]), (400, "wall: " + cli.stderr[len(prefix):].rstrip("\n")), what)
        self.assertEqual(self.post("/api/check", {"wall": good, "planner": "zigzag", "params": {"overlap": 5}})[1],
                         {"ok": False, "error": "params: overlap: 5 is out of range [0, 0.9]"})

    def test_a_plan_is_scored_as_the_command_line_scores_it(self):
        wall = os.path.join(self.walls, "seed_10x8_3obs.json")
        out = os.path.join(self.work, "plan.json")
        subprocess.run([BIN, "plan", "--wall", wall, "--planner", "boustrophedon", "--param", "overlap=0.1", "--out", out],
                       check=True, stdout=subprocess.DEVNULL)
        cli = json.loads(read(out))
        status, r = self.post("/api/plan", {"wall": read(wall), "planner": "boustrophedon", "params": {"overlap": "0.1"}})
        self.assertEqual(status, 200, r)
        self.assertEqual((r["status"], r["valid"], r["waypoints"]), (cli["status"], True, len(cli["waypoints"])))
        for k in ("coverage_reachable", "overlap", "length_total", "turns"):
            self.assertEqual(r["metrics"][k], cli["metrics"][k], k)
        with urllib.request.urlopen(self.base + r["picture"]) as p:
            self.assertTrue(p.read().startswith(b"<svg"))
        with urllib.request.urlopen(self.base + r["playback"]) as p:
            self.assertTrue(p.read().decode().startswith("coverbenchPlayback({"))

    def test_plan_requests_are_bounded_and_refused_as_json(self):
        wall = read(os.path.join(self.walls, "seed_10x8_3obs.json"))
        self.assertEqual(self.post("/api/plan", {"wall": wall, "planner": "zigzag", "time_limit_s": 100}),
                         (400, {"error": "request body: time_limit_s: must be at most 20 s (serve --plan-time-limit), got 100"}))
        # A plan that cannot finish within its time limit: spiral on a 100 m field at a 5 cm tool
        # takes about 20 s; asked for 0.5 s, the answer is a 504 within its answer deadline
        # (2 x 0.5 s + 10 s: the worker's hard deadline and the helper's reading and scoring), not
        # a 20 s wait. The bound is the server's promise (counted from the request's arrival), not a
        # speed, plus 4 s for the client's side of the request on a busy machine.
        field = read(os.path.join(SOURCE, "bench", "walls", "field_100m_15_buildings.json"))
        start = time.monotonic()
        status, answer = self.post("/api/plan", {"wall": field, "planner": "spiral", "tool_width": 0.05, "clearance": 0,
                                                 "time_limit_s": 0.5})
        self.assertLess(time.monotonic() - start, 15.0)
        self.assertEqual(status, 504, answer)
        self.assertTrue(answer["error"].startswith("time_limit_s: the plan did not finish within its time limit of 0.5 s"), answer)
        for body, message in (
                ("{", "request body: (document): malformed JSON: "),
                ({"wall": wall, "planner": "zigzag", "colour": 1}, "request body: colour: unknown key"),
                ({"wall": wall}, "request body: planner: name a planner"),
                ({"wall": wall, "planner": "zagzig"}, "planner: zagzig: unknown planner (registered: zigzag, "),
                ({"wall": wall, "planner": "zigzag", "tool_width": -1}, "tool: tool_width: "),
                ({"wall": wall, "planner": "zigzag", "params": {"colour": 1}}, "params: colour: ")):
            status, answer = self.post("/api/plan", body)
            self.assertEqual(status, 400, (body, answer))
            self.assertEqual(list(answer), ["error"])
            self.assertEqual(len(answer["error"].splitlines()), 1)
            self.assertTrue(answer["error"].startswith(message), (message, answer["error"]))

    def test_walls_are_saved_and_opened(self):
        listed = self.get("/api/walls")
        self.assertEqual(listed["walls_db"], self.walls_db)
        folder = [w for w in listed["walls"] if w["source"] == "folder"]
        self.assertEqual([w["name"] for w in folder], ["seed_10x8_3obs.json"])
        with urllib.request.urlopen(self.base + folder[0]["url"]) as r:
            text = r.read().decode()
        self.assertEqual(text, read(os.path.join(self.walls, "seed_10x8_3obs.json")))
        edited = text.replace('"seed-10x8-3obs"', '"my wall/../x"')
        status, saved = self.post("/api/walls", {"wall": edited})
        self.assertEqual((status, saved["name"], saved["file"]), (200, "my wall/../x", self.walls_db))
        names = [w["name"] for w in self.get("/api/walls")["walls"] if w["source"] == "database"]
        self.assertIn("my wall/../x", names)
        with urllib.request.urlopen(self.base + "/api/walls/db/" + urllib.parse.quote("my wall/../x", safe="")) as r:
            stored = r.read().decode()
        self.assertEqual(stored, self.post("/api/check", {"wall": edited})[1]["wall"])
        self.assertEqual(self.refused("GET", "/api/walls/folder/5"), (404, "no wall file 5 (serving 1)"))
        self.assertEqual(self.refused("GET", "/api/walls/db/nothing")[0], 404)
        self.assertEqual(self.post("/api/walls", {"wall": "{}"})[0], 400)
        # A blank name (empty, or only spaces of any kind) is refused with one error naming the field.
        for name in ("", "   ", "\u00a0\u3000 "):
            status, answer = self.post("/api/walls", {"wall": edited.replace('"my wall/../x"', json.dumps(name))})
            self.assertEqual((status, answer), (400, {"error": "request body: wall.name: a saved wall needs a name that is not blank "
                                                               "(it is how it is opened again)"}), repr(name))
        self.assertEqual([w["name"] for w in self.get("/api/walls")["walls"] if w["source"] == "database"], names)

    def test_a_runs_picture_and_playback(self):
        key = self.runs("planner=spiral&status=ok&limit=1")["runs"][0]["key"]
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
        # A long or control-laden path is quoted by its first 80 bytes, escaped (an attack found 8 kB).
        self.assertEqual(self.refused("GET", "/" + "h" * 8000),
                         (404, "/" + "h" * 79 + "... (8001 bytes): no such page or API (see docs/explorer.md)"))
        self.assertEqual(self.refused("GET", "/a%01%1b[31mb"), (404, "/a\\x01\\x1b[31mb: no such page or API (see docs/explorer.md)"))
        self.assertEqual(self.refused("GET", f"/api/experiments/7/{self.exp['id']}/runs"), (404, "no database 7 (serving 1)"))
        self.assertEqual(self.refused("GET", f"/api/experiments/{self.exp['db']}/999/runs")[0], 404)
        self.assertEqual(self.refused("GET", e + "/runs?sort=nonsense"),
                         (400, "sort: unknown column 'nonsense' (a metric, param.NAME, wall_name, planner, dataset, status or tool)"))
        self.assertEqual(self.refused("GET", e + "/runs?limit=5000"),
                         (400, "limit: must be a whole number from 0 to 1000, got '5000'"))
        self.assertEqual(self.refused("GET", e + "/runs/" + "0" * 64 + "/picture.svg")[0], 404)
        self.assertEqual(self.refused("POST", "/api/experiments", body=b"x" * (2 << 20)),
                         (413, "request body: 2097152 bytes, over the 1048576 bytes this request takes (POST /api/check takes 67108864)"))

    def test_what_it_cannot_serve_is_one_line_and_exit_2(self):
        for args, message in ((["/nonexistent.sqlite"], "coverbench: /nonexistent.sqlite: (file): does not exist\n"),
                              ([self.db, "--port", "70000"], "coverbench: --port: port: must be from 0 to 65535, got 70000\n"),
                              ([self.db, "--walls", "/nonexistent"], "coverbench: /nonexistent: --walls: is not a folder\n"),
                              ([self.db, "--walls-db", self.db],
                               f"coverbench: {self.db}: (database): is not a CoverBench walls database (its application_id)\n"),
                              ([self.db, "--plan-time-limit", "0"],
                               "coverbench: --plan-time-limit: plan_time_limit: must be in (0, 86400] s, got 0\n")):
            beside = sorted(os.listdir(os.path.dirname(os.path.abspath(self.db))))
            r = subprocess.run([BIN, "serve", *args], capture_output=True, text=True, timeout=60)
            self.assertEqual((r.returncode, r.stderr, r.stdout), (2, message, ""))
            self.assertEqual(sorted(os.listdir(os.path.dirname(os.path.abspath(self.db)))), beside, "nothing left beside it")

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
            self.assertEqual(set(ready["planners"]), {"zigzag"})
            if self.small:
                self.assertEqual(len(ready["planners"]), 3)
            problems = play(page, os.path.join(SHOTS, "serve"))
            # Pan and zoom: the picture fits its view; two clicks on + lay it out 4x as wide as the
            # view (inside its scroll bars), which keeps its height; a drag pans by as much as the
            # mouse moved.
            z = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                const fig = document.querySelector('#viewer figure');
                const img = fig.querySelector('img'), view = fig.coverbenchZoom.view;
                const w0 = img.getBoundingClientRect().width, h0 = view.getBoundingClientRect().height;
                fig.querySelector('.zoom-in').click();
                fig.querySelector('.zoom-in').click();
                await sleep(200);
                view.scrollIntoView({block: 'center'});
                await sleep(100);
                const r = view.getBoundingClientRect();
                return {ratio: img.getBoundingClientRect().width / view.clientWidth, fit: w0 / r.width, height: r.height / h0,
                        at: [r.left + r.width / 2, r.top + r.height / 2], scroll: [view.scrollLeft, view.scrollTop],
                        canvas: fig.querySelector('canvas.player-canvas').width / fig.coverbenchPlayer.waypoints() > 0};
            })()""")
            x, y = z["at"]
            page.call("Input.dispatchMouseEvent", type="mousePressed", x=x, y=y, button="left", clickCount=1)
            for k in range(1, 5):
                page.call("Input.dispatchMouseEvent", type="mouseMoved", x=x - 20 * k, y=y - 10 * k, button="left", buttons=1)
            page.call("Input.dispatchMouseEvent", type="mouseReleased", x=x - 80, y=y - 40, button="left", clickCount=1)
            after = page.evaluate("(() => { const v = document.querySelector('#viewer .zoom-view'); return [v.scrollLeft, v.scrollTop]; })()")
            self.assertAlmostEqual(z["fit"], 1.0, delta=0.01)
            self.assertAlmostEqual(z["ratio"], 4.0, delta=0.01)
            self.assertAlmostEqual(z["height"], 1.0, delta=0.01)
            self.assertEqual([round(after[0] - z["scroll"][0]), round(after[1] - z["scroll"][1])], [80, 40])
            time.sleep(0.3)
            page.screenshot(os.path.join(SHOTS, "serve-zoom.png"))
            problems += errors(page.events)
            self.assertEqual(problems, [])

    def test_two_planners_on_one_wall_play_in_step(self):
        with opened(self.base + "/") as page:
            r = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                for (let k = 0; k < 400 && !document.body.dataset.ready; ++k) await sleep(25);
                const rows = [...document.querySelectorAll('#runs tbody tr')];
                const planners = w => new Set(rows.filter(r => r.cells[1].textContent === w).map(r => r.cells[2].textContent));
                const wall = rows.map(r => r.cells[1].textContent).find(w => planners(w).size >= 2);
                const seen = new Set();
                const same = rows.filter(r => r.cells[1].textContent === wall && !seen.has(r.cells[2].textContent) && seen.add(r.cells[2].textContent));
                const button = document.getElementById('compare');
                const before = button.disabled;
                for (const row of same.slice(0, 2)) row.querySelector('input.pick').click();
                const enabled = !button.disabled;
                button.click();
                const viewer = document.getElementById('viewer');
                for (let k = 0; k < 400 && !viewer.coverbenchCompare; ++k) await sleep(25);
                const all = viewer.coverbenchCompare;
                all.setSpeed(20); all.seek(0); all.play();
                const c0 = performance.now();
                await sleep(1000);
                // The clock moves on animation frames: the next one drawn after a second, and when
                // (a busy machine draws few frames; the rate, not the time reached, is checked).
                const frame = await Promise.race([sleep(60000).then(() => null), new Promise(done => {
                    const o = new MutationObserver(() => { o.disconnect(); done({seconds: (performance.now() - c0) / 1000, time: all.time()}); });
                    o.observe(viewer, {attributes: true, attributeFilter: ['data-clock']});
                })]);
                const times = all.times();
                all.pause();
                all.seek(Math.min(...all.players.map(p => p.duration())) / 2);
                viewer.scrollIntoView();
                return {before, enabled, planners: same.slice(0, 2).map(r => r.cells[2].textContent),
                        figures: viewer.querySelectorAll('figure canvas.player-canvas').length, times, frame};
            })()""")
            self.assertTrue(r["before"], "compare is off until two runs on one wall are picked")
            self.assertTrue(r["enabled"])
            self.assertEqual(len(set(r["planners"])), 2)
            self.assertEqual(r["figures"], 2)
            # One clock at 20x: a frame drawn after a second or more shows the path 20 times as far
            # in as the page's clock moved (within 20 %: the frame's own time comes before its
            # drawing is seen), and both players at that one time.
            self.assertIsNotNone(r["frame"], "no frame was drawn in a minute of playing")
            self.assertGreaterEqual(r["frame"]["seconds"], 1.0)
            self.assertTrue(16.0 <= r["frame"]["time"] / r["frame"]["seconds"] <= 24.0, r["frame"])
            self.assertLess(max(r["times"]) - min(r["times"]), 0.5)
            time.sleep(0.3)
            page.screenshot(os.path.join(SHOTS, "serve-compare.png"))
            self.assertEqual(errors(page.events), [])

    def test_the_workbench_plans_edits_and_replans(self):
        # Waits are long (a minute for a check, two for a plan): under the sanitizers a plan's
        # worker process takes seconds to start.
        with opened(self.base + "/") as page:
            r = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                const $ = id => document.getElementById(id);
                for (let k = 0; k < 2400 && !(document.body.dataset.ready && document.body.dataset.workbench); ++k) await sleep(25);
                // zigzag on a residential wall (a rectangle: the form has its width)
                const planner = $('planner');
                planner.value = 'zigzag';
                planner.dispatchEvent(new Event('change'));
                const rows = () => [...document.querySelectorAll('#runs tbody tr')];
                for (let k = 0; k < 2400 && rows().some(r => r.cells[2].textContent !== 'zigzag'); ++k) await sleep(25);
                $('dataset').value = 'residential';
                $('dataset').dispatchEvent(new Event('change'));
                for (let k = 0; k < 2400 && rows().some(r => r.cells[3].textContent !== 'residential'); ++k) await sleep(25);
                // The wall the drag below was made for (its middle is free), when the experiment has it;
                // the table's order follows run keys, which change with the code.
                const ok = rows().filter(r => r.cells[4].textContent === 'ok');
                const row = ok.find(r => r.cells[1].textContent === 'residential-s1-0024') || ok[0];
                const wall = row.cells[1].textContent;
                row.click();
                await sleep(100);
                $('open-in-workbench').click();
                for (let k = 0; k < 2400 && !($('wb-name') && $('wb-name').value === wall); ++k) await sleep(25);
                const checked = async () => { for (let k = 0; k < 2400 && !$('wb-check').textContent.includes(wall); ++k) await sleep(25); };
                await checked();
                const plan = async () => {
                    const before = document.body.dataset.planned;
                    for (let k = 0; k < 2400 && $('wb-plan').disabled; ++k) await sleep(25);
                    $('wb-plan').click();
                    for (let k = 0; k < 4800 && document.body.dataset.planned === before && !($('wb-outcome') && $('wb-outcome').className === 'error'); ++k) await sleep(25);
                    return $('wb-outcome').textContent;
                };
                const first = await plan();
                const angle = $('wb-params').querySelector('[data-param="sweep_angle"]');
                angle.value = '90';
                angle.dispatchEvent(new Event('input'));
                await sleep(400);
                const second = await plan();
                const svg = $('wb-drawing').getBoundingClientRect();
                $('wb-drawing').scrollIntoView();
                return {wall, first, second, obstacles: JSON.parse($('wb-text').value).obstacles.length,
                        svg: [svg.left, svg.top, svg.width, svg.height, window.scrollY]};
            })()""")
            self.assertRegex(r["first"], r"^zigzag: ok, valid, \d+ waypoints")
            self.assertRegex(r["second"], r"^zigzag: ok, valid, \d+ waypoints")
            self.assertNotEqual(r["first"].split(",")[2], r["second"].split(",")[2], "a sweep at 90 degrees is another path")
            # Draw a window with the mouse: from the middle of the drawing, a tenth of it across.
            box = page.evaluate("(() => { const b = document.getElementById('wb-drawing').getBoundingClientRect();"
                                " return [b.left, b.top, b.width, b.height]; })()")
            x0, y0 = box[0] + box[2] * 0.45, box[1] + box[3] * 0.45
            x1, y1 = x0 + box[2] * 0.06, y0 + box[3] * 0.08
            page.call("Input.dispatchMouseEvent", type="mousePressed", x=x0, y=y0, button="left", clickCount=1)
            for k in range(1, 6):
                page.call("Input.dispatchMouseEvent", type="mouseMoved", x=x0 + (x1 - x0) * k / 5, y=y0 + (y1 - y0) * k / 5,
                          button="left", buttons=1)
            page.call("Input.dispatchMouseEvent", type="mouseReleased", x=x1, y=y1, button="left", clickCount=1)
            r2 = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                const $ = id => document.getElementById(id);
                const wall = JSON.parse($('wb-text').value);
                for (let k = 0; k < 2400 && $('wb-plan').disabled; ++k) await sleep(25);
                const drawn = wall.obstacles[wall.obstacles.length - 1];
                const before = document.body.dataset.planned;
                $('wb-plan').click();
                for (let k = 0; k < 4800 && document.body.dataset.planned === before && !($('wb-outcome') && $('wb-outcome').className === 'error'); ++k) await sleep(25);
                const replanned = $('wb-outcome').textContent;
                const fig = document.querySelector('#wb-result figure[data-playback]');
                fig.querySelector('.player-start').click();
                for (let k = 0; k < 200 && !fig.coverbenchPlayer; ++k) await sleep(25);
                fig.coverbenchPlayer.setSpeed(20);
                await sleep(500);
                const played = fig.coverbenchPlayer.time();
                fig.coverbenchPlayer.pause();
                // Edit the wall into an invalid one in the form: the command line's message, and no plan.
                const width = document.querySelector('#wb-form .wb-width');
                width.value = '-3';
                width.dispatchEvent(new Event('input'));
                for (let k = 0; k < 2400 && $('wb-check').className !== 'error'; ++k) await sleep(25);
                return {count: wall.obstacles.length, drawn, replanned, played, error: $('wb-check').textContent,
                        disabled: $('wb-plan').disabled, marked: $('wb-text').classList.contains('invalid')};
            })()""")
            self.assertEqual(r2["count"], r["obstacles"] + 1, "the drag drew one window")
            self.assertEqual(r2["drawn"]["type"], "rect")
            self.assertGreater(r2["drawn"]["width"], 0)
            self.assertRegex(r2["replanned"], r"^zigzag: (ok|partial)")
            self.assertGreater(r2["played"], 1.0)
            self.assertEqual(r2["error"], "wall: width: must be positive, got -3")
            self.assertTrue(r2["disabled"])
            self.assertTrue(r2["marked"])
            time.sleep(0.3)
            page.screenshot(os.path.join(SHOTS, "serve-workbench-invalid.png"))
            fixed = page.evaluate("""(async () => {
                const sleep = ms => new Promise(r => setTimeout(r, ms));
                const $ = id => document.getElementById(id);
                const width = document.querySelector('#wb-form .wb-width');
                width.value = String(Number(JSON.parse($('wb-text').value).height) * 2);
                width.dispatchEvent(new Event('input'));
                for (let k = 0; k < 2400 && $('wb-check').className !== 'ok'; ++k) await sleep(25);
                const before = document.body.dataset.planned;
                $('wb-plan').click();
                for (let k = 0; k < 4800 && document.body.dataset.planned === before; ++k) await sleep(25);
                document.querySelector('#workbench').scrollIntoView();
                return $('wb-outcome').textContent;
            })()""")
            self.assertRegex(fixed, r"^zigzag: (ok|partial)")
            time.sleep(0.5)
            page.screenshot(os.path.join(SHOTS, "serve-workbench.png"))
            print(f"workbench: {r['wall']}: {r['first']} | sweep 90: {r['second']} | a window drawn: {r2['replanned']} | "
                  f"made invalid: {r2['error']} | fixed: {fixed}")
            self.assertEqual(errors(page.events), [])


class Outcome(unittest.TestCase):
    """Issue 61: a run's outcome in words, for the run view: a planner that crashes on walls with
    holes (tests/data/crash_on_holes) has its reason and the end of its stderr served as JSON
    strings (bytes that were not UTF-8 as U+FFFD); the view shows them as text."""

    def test_a_runs_coat_is_shown_in_the_viewer(self):
        """A run of a tool with a flux profile: its view's button shows the coat under its picture
        (loaded, with the scale); a run of a tool without one has no button. Screenshot serve-coat.png."""
        opening = """(async () => {
            const sleep = ms => new Promise(r => setTimeout(r, ms));
            for (let k = 0; k < 400 && !document.body.dataset.ready; ++k) await sleep(25);
            const rows = () => [...document.querySelectorAll('#runs tbody tr')];
            for (let k = 0; k < 400 && !rows().length; ++k) await sleep(25);
            rows()[0].click();
            for (let k = 0; k < 400 && !document.getElementById('same-wall'); ++k) await sleep(25);
            const button = document.getElementById('show-coat');
            if (!button) return {button: false};
            button.click();
            const img = () => document.querySelector('#viewer figure.coat img');
            for (let k = 0; k < 800 && !(img() && img().complete && img().naturalWidth > 0); ++k) await sleep(25);
            if (!img()) return {error: 'no coat shown: ' + document.getElementById('status').textContent};
            img().scrollIntoView({block: 'center'});
            return {button: true, width: img().naturalWidth, disabled: button.disabled,
                    caption: document.querySelector('#viewer figure.coat figcaption').textContent};
        })()"""
        shown = {}
        with tempfile.TemporaryDirectory() as work:
            os.makedirs(os.path.join(work, "walls"))
            with open(os.path.join(work, "walls", "w.json"), "w") as f:
                json.dump({"name": "w", "width": 2, "height": 1.2,
                           "obstacles": [{"type": "rect", "x": 0.8, "y": 0.4, "width": 0.4, "height": 0.3}]}, f)
            for name, profile in (("coat", "  profile: {kind: beta, beta: 2.5}\n"), ("plain", "")):
                with open(os.path.join(work, name + ".yaml"), "w") as f:
                    f.write(f"name: {name}\noutput: {name}\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n"
                            "tool:\n  width: 0.3\n" + profile)
                subprocess.run([BIN, "run", name + ".yaml", "--no-report"], cwd=work, check=True, stdout=subprocess.DEVNULL)
                server = subprocess.Popen([BIN, "serve", os.path.join(work, name, "results.sqlite"), "--port", "0"],
                                          stdout=subprocess.PIPE, text=True)
                try:
                    port = re.search(r"http://127\.0\.0\.1:(\d+)/", server.stdout.readline()).group(1)
                    with opened(f"http://127.0.0.1:{port}/") as page:
                        shown[name] = page.evaluate(opening)
                        time.sleep(0.3)
                        if name == "coat":
                            page.screenshot(os.path.join(SHOTS, "serve-coat.png"))
                        shown[name]["problems"] = errors(page.events)
                finally:
                    server.kill()
                    server.wait()
                    server.stdout.close()
        coat = shown["coat"]
        self.assertNotIn("error", coat, coat)
        self.assertEqual((coat["button"], coat["disabled"], coat["problems"]), (True, True, []), coat)
        self.assertGreater(coat["width"], 100)
        self.assertIn("thickness", coat["caption"])
        self.assertEqual(shown["plain"], {"button": False, "problems": []})

    def test_a_crashed_runs_reason_and_stderr_are_served(self):
        with tempfile.TemporaryDirectory() as work:
            os.makedirs(os.path.join(work, "walls"))
            with open(os.path.join(work, "walls", "holes.json"), "w") as f:
                json.dump({"name": "holes", "width": 2, "height": 1,
                           "obstacles": [{"type": "rect", "x": 0.8, "y": 0.3, "width": 0.4, "height": 0.4}]}, f)
            manifest = os.path.abspath(os.path.join(SOURCE, "tests", "data", "crash_on_holes", "crash_on_holes.json"))
            with open(os.path.join(work, "c.yaml"), "w") as f:
                f.write(f"name: crash\noutput: out\ndatasets:\n  - folder: walls\nplanners:\n  - external: {manifest}\n"
                        "limits:\n  time_s: 600\n")
            subprocess.run([BIN, "run", "c.yaml", "--no-report"], cwd=work, check=True, stdout=subprocess.DEVNULL)
            server = subprocess.Popen([BIN, "serve", os.path.join(work, "out", "results.sqlite"), "--port", "0"],
                                      stdout=subprocess.PIPE, text=True)
            try:
                port = re.search(r"http://127\.0\.0\.1:(\d+)/", server.stdout.readline()).group(1)

                def get(path):
                    with urllib.request.urlopen(f"http://127.0.0.1:{port}{path}", timeout=60) as r:
                        return json.load(r)
                exp = get("/api/experiments")["experiments"][-1]
                runs = get(f"/api/experiments/{exp['db']}/{exp['id']}/runs")["runs"]
                self.assertEqual([r["status"] for r in runs], ["crash"])
                o = get(f"/api/experiments/{exp['db']}/{exp['id']}/runs/{runs[0]['key']}/outcome")
            finally:
                server.kill()
                server.wait()
                server.stdout.close()
        self.assertEqual((o["status"], o["wall_name"]), ("crash", "holes"))
        self.assertIn("exited with code 1", o["reason"])
        self.assertTrue(o["stderr_tail"].endswith("RuntimeError: holes are not supported: 1 obstacles on holes\n"))
        self.assertIn("not UTF-8: \ufffd\ufffd <- two bytes", o["stderr_tail"])
        self.assertTrue(o["planner"].startswith("crash-on-holes"))


if __name__ == "__main__":
    # ctest serve_main_job: the main job's database when it has been made (README's first
    # command), else skipped with the reason (exit 77).
    if os.environ.get("COVERBENCH_SERVE_DB_IF_PRESENT"):
        if not os.path.isfile(os.environ.get("COVERBENCH_SERVE_DB", "")):
            print(f"skipped: {os.environ.get('COVERBENCH_SERVE_DB')} does not exist (run the main job: bash scripts/run_main.sh)")
            sys.exit(77)
    unittest.main()
