"""The workbench's page as a researcher uses it (issue 64), in headless Chromium over the DevTools
protocol, against `coverbench serve` with the workbench alone (a new walls database, no
experiment): the plan button stays off while the wall is invalid, with the reason beside it; the
check's error line is on screen when it appears; a blank name is not saved; a cleared number
field is marked and draws no NaN; a plan is marked stale the moment its wall or parameters
change; the layout holds from 800 x 600 to 2560 x 1440. Every wait is for a condition, with a
deadline of minutes (a busy machine is slow, not wrong); no assertion is on a time. Screenshots in
ARTIFACTS (env COVERBENCH_ARTIFACTS), named workbench-*.png."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
from check_page import errors, opened  # noqa: E402

BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SOURCE = os.path.join(HERE, "..", "..")
SHOTS = os.environ.get("COVERBENCH_ARTIFACTS", tempfile.gettempdir())
os.makedirs(SHOTS, exist_ok=True)

# Helpers for the page's scripts: `until` waits for a condition (false at its deadline, which the
# assertions after it then show); `ready` waits for the new wall's check and an enabled plan button.
JS = """
const sleep = ms => new Promise(r => setTimeout(r, ms));
const $ = id => document.getElementById(id);
const until = async (f, seconds = 180) => {
  for (const end = performance.now() + seconds * 1000; !f(); await sleep(25)) if (performance.now() > end) return false;
  return true;
};
const set = (el, value) => { el.value = value; el.dispatchEvent(new Event(el.tagName === 'SELECT' ? 'change' : 'input')); };
const firstX = () => document.querySelector('table.wb-obstacles tbody input[type=number]');
const ready = () => until(() => document.body.dataset.workbench && $('wb-check').className === 'ok' && !$('wb-plan').disabled);
const plan = async () => {
  const before = document.body.dataset.planned;
  await ready();
  $('wb-plan').click();
  await until(() => document.body.dataset.planned !== before || ($('wb-outcome') && $('wb-outcome').className === 'error'));
};
const box = el => { const r = el.getBoundingClientRect(); return {left: r.left, top: r.top, right: r.right, bottom: r.bottom}; };
"""


def run(page, body):
    return page.evaluate("(async () => {" + JS + body + "})()")


class WorkbenchPage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-workbench-")
        cls.walls_db = os.path.join(cls.work, "saved.sqlite")
        cls.server = subprocess.Popen([BIN, "serve", "--port", "0", "--walls-db", cls.walls_db, "--plan-time-limit", "20"],
                                      stdout=subprocess.PIPE, text=True)
        m = re.search(r"http://127\.0\.0\.1:(\d+)/", cls.server.stdout.readline())
        if not m:
            cls.server.kill()
            raise RuntimeError("coverbench serve did not print its address")
        cls.base = f"http://127.0.0.1:{m.group(1)}"

    @classmethod
    def tearDownClass(cls):
        cls.server.kill()
        cls.server.wait()
        cls.server.stdout.close()
        shutil.rmtree(cls.work, ignore_errors=True)

    def shot(self, page, name):
        page.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")
        page.screenshot(os.path.join(SHOTS, f"workbench-{name}.png"))

    def test_plan_stays_off_while_the_wall_is_invalid(self):
        # A plan that runs into its 1 s time limit (spiral on the 100 m field at a 5 cm tool), and
        # while it runs the form moves a window off the wall: when the plan has ended, the button
        # must be off with the check's message beside it.
        with open(os.path.join(SOURCE, "bench", "walls", "field_100m_15_buildings.json")) as f:
            wall = json.load(f)
        wall["obstacles"].append({"type": "rect", "x": 2, "y": 2, "width": 2, "height": 2, "label": "window"})
        with opened(self.base + "/", 1400, 1000) as page:
            r = run(page, """
                await ready();
                set($('wb-planner'), 'spiral');
                set($('wb-tool'), '0.05'); set($('wb-clearance'), '0'); set($('wb-time'), '1');
                set($('wb-text'), %s);
                await ready();
                $('wb-plan').click();
                const xs = document.querySelectorAll('table.wb-obstacles tbody input[type=number]');
                set(xs[xs.length - 4], '500');
                await until(() => $('wb-outcome') && $('wb-check').className === 'error');
                await sleep(0);
                return {disabled: $('wb-plan').disabled, check: $('wb-check').textContent,
                        reason: $('wb-plan-reason') ? $('wb-plan-reason').textContent : null};
            """ % json.dumps(json.dumps(wall)))
            self.shot(page, "plan-off")
            self.assertEqual(r["check"], "wall: obstacles[15]: lies entirely outside the wall", r)
            self.assertTrue(r["disabled"], r)
            self.assertEqual(r["reason"], r["check"])
            # The plan's 504 is logged by the browser as a failed load; nothing else may be.
            self.assertEqual([e for e in errors(page.events) if "status of 504" not in e], [])

    def test_the_error_line_is_on_screen(self):
        # At 800 x 600, a wall of six obstacles with its table at the top of the window: an error
        # from the table is seen; so is one from a planner's parameter at the top of the window.
        with opened(self.base + "/", 800, 600) as page:
            r = run(page, """
                await ready();
                for (let k = 0; k < 5; ++k) $('wb-add').click();
                await ready();
                const seen = async (field, value) => {
                    field.scrollIntoView({block: 'start'});
                    set(field, value);
                    await until(() => $('wb-check').className === 'error');
                    return {check: $('wb-check').textContent, at: box($('wb-check')), field: box(field)};
                };
                const first = $('wb-params').querySelector('input[type=number]'), was = first.value;
                const param = await seen(first, '-5');
                set(first, was);
                await ready();
                const table = await seen(firstX(), '500');
                return {table, param, height: innerHeight};
            """)
            self.shot(page, "error-line")
        self.assertEqual(r["table"]["check"], "wall: obstacles[0]: lies entirely outside the wall")
        self.assertTrue(r["param"]["check"].startswith("params: "), r["param"])
        for what in ("table", "param"):
            at, field = r[what]["at"], r[what]["field"]
            self.assertTrue(0 <= at["top"] and at["bottom"] <= r["height"], (what, "the error line is off screen", at))
            self.assertTrue(-1 < field["top"] and field["bottom"] <= r["height"], (what, "the field typed in is still on screen", field))

    def test_a_blank_name_is_not_saved(self):
        with opened(self.base + "/", 1400, 1000) as page:
            r = run(page, """
                await ready();
                set($('wb-name'), '   ');
                await ready();
                $('wb-save').click();
                await until(() => $('wb-saved').textContent !== '');
                const walls = await (await fetch('/api/walls')).json();
                return {saved: $('wb-saved').textContent, cls: $('wb-saved').className,
                        marked: $('wb-name').getAttribute('aria-invalid'), walls: walls.walls};
            """)
            self.shot(page, "blank-name")
            self.assertEqual(errors(page.events), [])
        self.assertEqual(r["walls"], [], "nothing was saved")
        self.assertEqual(r["cls"], "error")
        self.assertTrue(r["saved"].startswith("name: "), r["saved"])
        self.assertEqual(r["marked"], "true")

    def test_a_cleared_field_is_marked_and_draws_no_nan(self):
        with opened(self.base + "/", 1400, 1000) as page:
            r = run(page, """
                await ready();
                set(firstX(), '');
                await until(() => $('wb-check').className === 'error');
                const attrs = [...$('wb-drawing').querySelectorAll('*')].flatMap(e => [...e.attributes].map(a => a.value));
                return {check: $('wb-check').textContent, marked: firstX().getAttribute('aria-invalid'),
                        nan: attrs.filter(v => /NaN/.test(v)), disabled: $('wb-plan').disabled};
            """)
            self.shot(page, "cleared-field")
            self.assertEqual(errors(page.events), [])
        self.assertEqual(r["check"], "wall: obstacles[0].x: must be a number, got null")
        self.assertEqual(r["marked"], "true")
        self.assertEqual(r["nan"], [])
        self.assertTrue(r["disabled"])

    def test_a_plan_is_marked_stale_when_its_wall_or_parameters_change(self):
        with opened(self.base + "/", 1400, 1000) as page:
            r = run(page, """
                const seen = () => ({stale: $('wb-result').classList.contains('stale'),
                                     note: $('wb-stale') && !$('wb-stale').hidden ? $('wb-stale').textContent : '',
                                     opacity: Number(getComputedStyle($('wb-result')).opacity)});
                await plan();
                const fresh = seen();
                set(firstX(), '1.6');
                const wall = seen();
                await plan();
                const replanned = seen();
                set($('wb-params').querySelector('input[type=number]'), '45');
                const params = seen();
                const img = $('wb-result').querySelector('img');
                await until(() => img.complete);
                return {fresh, wall, replanned, params};
            """)
            self.shot(page, "stale")
            self.assertEqual(errors(page.events), [])
        for when in ("fresh", "replanned"):
            self.assertEqual(r[when], {"stale": False, "note": "", "opacity": 1}, when)
        self.assertEqual((r["wall"]["stale"], r["wall"]["note"]), (True, "stale: the wall changed since this plan"))
        self.assertEqual((r["params"]["stale"], r["params"]["note"]), (True, "stale: the parameters changed since this plan"))
        self.assertLess(r["wall"]["opacity"], 1)

    def test_the_layout_holds_from_800x600_to_2560x1440(self):
        measure = """
            await ready();
            return {scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth,
                    params: box($('wb-params')), table: box(document.querySelector('table.wb-obstacles')),
                    rows: document.querySelectorAll('table.wb-obstacles tbody tr').length};
        """
        seen = {}
        with opened(self.base + "/", 800, 600) as page:
            run(page, "await ready(); $('wb-add').click(); $('wb-add').click();")
            for w, h in ((800, 600), (2560, 1440)):
                page.call("Emulation.setDeviceMetricsOverride", width=w, height=h, deviceScaleFactor=1, mobile=False)
                seen[w] = run(page, measure)
                self.shot(page, f"layout-{w}x{h}")
            self.assertEqual(errors(page.events), [])
        for w, m in seen.items():
            self.assertEqual(m["rows"], 3)
            self.assertLessEqual(m["scroll"], m["client"], (w, "no sideways scroll"))
            p, t = m["params"], m["table"]
            overlap = min(p["right"], t["right"]) > max(p["left"], t["left"]) and min(p["bottom"], t["bottom"]) > max(p["top"], t["top"])
            self.assertFalse(overlap, (w, "the parameters and the obstacle table overlap", p, t))


if __name__ == "__main__":
    unittest.main()
