"""The explorer's Plots tab (issue 64) against SQLite itself, in headless Chromium:

- GET .../values gives each selected run's metric values, wall, configuration and usability as
  SQLite holds them, and refuses bad parameters with one JSON 400 naming the parameter;
- each plot kind of length_total on the residential walls (the table's dataset filter) draws the
  expected marks: one box per configuration, whose median tick stands at SQLite's median; one
  empirical CDF per configuration with one step per usable run; one performance profile per
  configuration equal to the report's (coverbench_report.stats.performance_profile on SQLite's
  costs, failures infinite); the zigzag sweep over sweep_angle, one point per configuration at
  SQLite's median; one scatter point per usable run with both metrics;
- a table filter redraws the plot over the new selection;
- the plot's controls are in the page's address: a copied address draws the same plot, back and
  forward return to each earlier choice;
- the SVG download parses as SVG with the legend, the PNG download is a PNG of twice its size;
- without the charting library the tab says in one line how to install it.

Three runs are made failures in SQLite first (two crashes, one ok run whose path is not valid),
so the failure rules are checked. Screenshots in ARTIFACTS (env COVERBENCH_ARTIFACTS)."""
import base64
import json
import os
import sqlite3
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import unittest
import urllib.error
import urllib.request
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "reports", "python"))
sys.path.insert(0, HERE)
from check_page import errors, opened  # noqa: E402
from test_table import Served, start_server  # noqa: E402

BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SHOTS = os.environ.get("COVERBENCH_ARTIFACTS", tempfile.gettempdir())
os.makedirs(SHOTS, exist_ok=True)

CONFIG = """name: plots-check
output: out
datasets:
  - family: residential
    count: 4
    seed: 2
  - family: facade
    count: 3
    seed: 2
planners:
  - name: zigzag
    params: {sweep_angle: [0, 45, 90]}
  - spiral
  - boustrophedon
"""
METRIC, VERSUS, DATASET = "length_total", "coverage_reachable", "residential"

# In the page: waits with generous deadlines (no timed assertion) and the plot's marks.
HELPERS = """
const sleep = ms => new Promise(r => setTimeout(r, ms));
const $ = id => document.getElementById(id);
const until = async (f, what) => { for (let k = 0; k < 2400; ++k) { if (f()) return; await sleep(25); } throw new Error('waited for ' + what); };
const P = () => window.coverbenchPlots;
const plotted = kind => until(() => document.body.dataset.ready && $('plots-kind') && !$('plots').dataset.loading
                                    && P().drawn() && P().drawn().kind === kind, 'the ' + kind + ' plot');
const choose = (id, value) => { $(id).value = value; $(id).dispatchEvent(new Event('change')); };
const main = () => { const f = P().figure(); return f.tagName.toLowerCase() === 'svg' ? f : f.querySelector(':scope > svg'); };
const marks = (label, tag) => [...main().querySelectorAll(`g[aria-label="${label}"] ${tag}`)];
// An element's transform into the plot's own coordinates (those of its scales), whatever size the page shows it at.
const ctm = el => main().getScreenCTM().inverse().multiply(el.getScreenCTM());
const yOf = el => { const m = ctm(el); return m.f + m.d * el.y1.baseVal.value; };
"""


class Plots(Served):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-plots-")
        with open(os.path.join(cls.work, "c.yaml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], cwd=cls.work, check=True, capture_output=True)
        cls.db = os.path.join(cls.work, "out", "results.sqlite")
        con = sqlite3.connect(cls.db)
        (cls.exp_id,) = con.execute("SELECT MAX(id) FROM experiments").fetchone()
        runs = cls.stored(con, METRIC)
        spiral = sorted(k for k, r in runs.items() if r["config"] == "spiral")[:2]
        boustrophedon = sorted(k for k, r in runs.items() if r["config"] == "boustrophedon")[:1]
        con.executemany("UPDATE runs SET status = 'crash', valid = 0 WHERE key = ?", [(k,) for k in spiral])
        con.executemany("UPDATE runs SET valid = 0 WHERE key = ?", [(k,) for k in boustrophedon])
        con.executemany("UPDATE metrics SET value = 0 WHERE name = 'valid' AND run_key = ?", [(k,) for k in spiral + boustrophedon])
        con.commit()
        con.close()
        cls.server, cls.base = start_server(cls.db)
        exp = cls.get("/api/experiments")["experiments"][-1]
        cls.exp = f"{exp['db']}/{exp['id']}"
        cls.values_path = f"/api/experiments/{exp['db']}/{exp['id']}/values"


    @classmethod
    def stored(cls, con, metric, dataset=DATASET):
        """The experiment's runs on `dataset` as SQLite holds them: key -> wall, configuration,
        usable (ok or partial with a valid path) and the metric's value (None when it has none)."""
        rows = con.execute(
            "SELECT r.key, r.wall_hash, p.label, r.status, v.value, m.value FROM experiment_runs e JOIN runs r ON r.key = e.run_key "
            "JOIN experiment_planners p ON p.experiment_id = e.experiment_id AND p.config_id = r.config_id "
            "JOIN experiment_walls w ON w.experiment_id = e.experiment_id AND w.wall_hash = r.wall_hash "
            "LEFT JOIN metrics v ON v.run_key = r.key AND v.name = 'valid' LEFT JOIN metrics m ON m.run_key = r.key AND m.name = ? "
            "WHERE e.experiment_id = ? AND w.dataset = ?", (metric, cls.exp_id, dataset)).fetchall()
        return {k: {"wall": w, "config": c, "usable": s in ("ok", "partial") and v == 1, "value": x} for k, w, c, s, v, x in rows}

    def sql_runs(self, metric, dataset=DATASET):
        con = sqlite3.connect(f"file:{self.db}?mode=ro", uri=True)
        try:
            return self.stored(con, metric, dataset)
        finally:
            con.close()

    def usable_values(self, metric):
        """configuration -> its usable runs' values (as the report's box plots summarise)."""
        out = {}
        for r in self.sql_runs(metric).values():
            if r["usable"] and r["value"] is not None:
                out.setdefault(r["config"], []).append(r["value"])
        return out

    def in_page(self, body, kind, address=None):
        """Runs `body` on the Plots tab once the `kind` plot is drawn; saves a screenshot."""
        with opened(self.base + (address or f"/?exp={self.exp}&tab=plots&dataset={DATASET}")) as page:
            r = page.evaluate("(async () => {" + HELPERS + f"""
                await until(() => document.body.dataset.ready && $('plots-kind') && P().drawn(), 'the first plot');
                choose('plots-metric', '{METRIC}');
                choose('plots-kind', '{kind}');
                await plotted('{kind}');
                """ + body + "})()")
            self.assertEqual(errors(page.events), [])
            page.screenshot(os.path.join(SHOTS, f"plots-{kind}.png"))
        return r

    # --- the API --------------------------------------------------------------------------------

    def test_values_are_sqlites(self):
        data = self.get(f"{self.values_path}?metric={METRIC}&versus={VERSUS}&dataset={DATASET}")
        first, second = self.sql_runs(METRIC), self.sql_runs(VERSUS)
        r = data["runs"]
        self.assertEqual(data["total"], len(first))
        got = sorted((data["walls"][r["wall"][i]], data["configurations"][r["configuration"][i]], r["usable"][i], r["value"][i], r["versus"][i])
                     for i in range(data["total"]))
        want = sorted((x["wall"], x["config"], x["usable"], x["value"], second[k]["value"]) for k, x in first.items())
        self.assertEqual(got, want)
        self.assertEqual(sum(1 for x in first.values() if not x["usable"]), 3)
        self.assertEqual({data["families"][i] for i, c in enumerate(data["configurations"]) if c.startswith("zigzag")}, {"zigzag"})

    def test_bad_parameters_are_one_line_400s_naming_them(self):
        for query, name in [("", "metric"), ("metric=nope", "metric"), (f"metric={METRIC}&versus=%00x", "versus"),
                            (f"metric={METRIC}&metric=overlap", "metric"), (f"metric={METRIC}&limit=5", "limit"),
                            (f"metric={METRIC}&min.overlap=inf", "min.overlap"), (f"metric={METRIC}&colour=red", "colour")]:
            with self.assertRaises(urllib.error.HTTPError, msg=query) as e:
                urllib.request.urlopen(f"{self.base}{self.values_path}?{query}", timeout=60)
            body = json.loads(e.exception.read())
            self.assertEqual(e.exception.code, 400, query)
            self.assertEqual(list(body), ["error"])
            self.assertEqual(len(body["error"].splitlines()), 1)
            self.assertTrue(body["error"].startswith(name + ":"), body["error"])

    # --- the plots ------------------------------------------------------------------------------

    def test_box_plot_medians_are_sqlites_and_follow_the_filters(self):
        r = self.in_page("""
            const fig = P().figure(), x = fig.scale('x'), y = fig.scale('y');
            const boxes = marks('bar', 'rect').length, medians = {};
            for (const c of x.domain) {
                const mid = x.apply(c) + x.bandwidth / 2;
                const tick = marks('tick', 'line').find(l => {
                    const m = ctm(l);
                    return Math.abs(m.e + m.a * (l.x1.baseVal.value + l.x2.baseVal.value) / 2 - mid) < x.bandwidth / 4;
                });
                medians[c] = yOf(tick);
            }
            const scale = {domain: y.domain, range: y.range};
            choose('planner', 'spiral');
            await until(() => P().drawn() && P().drawn().series.length === 1 && !$('plots').dataset.loading, 'the filtered plot');
            return {boxes, medians, domain: x.domain, filtered: marks('bar', 'rect').length, scale};
        """, "box")
        values = self.usable_values(METRIC)
        self.assertEqual(r["boxes"], len(values))
        self.assertEqual(sorted(r["domain"]), sorted(values))
        (d0, d1), (r0, r1) = r["scale"]["domain"], r["scale"]["range"]
        for c, drawn in r["medians"].items():
            want = r0 + (statistics.median(values[c]) - d0) / (d1 - d0) * (r1 - r0)
            self.assertLessEqual(abs(drawn - want), 0.51, c)  # a tick is drawn half a pixel down, for a crisp line
        self.assertEqual(r["filtered"], 1)

    def test_ecdf_has_one_step_per_usable_run(self):
        r = self.in_page("""
            const color = P().figure().scale('color');
            return marks('line', 'path').map(p => {
                const c = color.domain.find(d => color.apply(d) === p.getAttribute('stroke'));
                return {config: c, vertices: (p.getAttribute('d').match(/[ML]/g) || []).length};
            });
        """, "ecdf")
        values = self.usable_values(METRIC)
        self.assertEqual(sorted(x["config"] for x in r), sorted(values))
        for x in r:  # a rise from 0, then one riser and one tread per run
            self.assertEqual(x["vertices"], 2 * len(values[x["config"]]) + 1, x["config"])

    def test_performance_profile_is_the_reports(self):
        from coverbench_report import stats
        r = self.in_page("return {drawn: P().drawn(), lines: marks('line', 'path').length};", "profile")
        runs = self.sql_runs(METRIC)
        configs = [s["config"] for s in r["drawn"]["series"]]
        walls = sorted({x["wall"] for x in runs.values()})
        cost = {(x["wall"], x["config"]): (x["value"] if x["usable"] and x["value"] is not None else float("inf")) for x in runs.values()}
        costs = [[cost[(w, c)] for c in configs] for w in walls if all((w, c) in cost for c in configs)]
        self.assertEqual(r["drawn"]["walls"], len(costs))
        self.assertEqual(r["lines"], len(configs))
        rho, _ = stats.performance_profile(costs, r["drawn"]["taus"])
        for j, s in enumerate(r["drawn"]["series"]):
            self.assertEqual(s["rho"], [float(v) for v in rho[j]], s["config"])
        # Two spiral runs crashed: spiral never reaches those walls at any tau.
        spiral = r["drawn"]["series"][configs.index("spiral")]["rho"]
        self.assertLessEqual(spiral[-1], (len(costs) - 2) / len(costs))

    def test_sweep_medians_are_sqlites(self):
        r = self.in_page("""
            choose('plots-param', 'sweep_angle');
            await until(() => P().drawn().param === 'sweep_angle', 'the sweep');
            return {drawn: P().drawn(), dots: marks('dot', 'circle').length, lines: marks('line', 'path').length};
        """, "sweep")
        values = self.usable_values(METRIC)
        zigzag = sorted(c for c in values if c.startswith("zigzag"))
        self.assertEqual(r["lines"], 1)
        self.assertEqual(r["dots"], len(zigzag))
        self.assertEqual([p["x"] for p in r["drawn"]["points"]], [0, 45, 90])
        for p in r["drawn"]["points"]:
            self.assertAlmostEqual(p["median"], statistics.median(values[p["config"]]), places=9)

    def test_scatter_has_one_point_per_usable_run_and_downloads(self):
        r = self.in_page(f"""
            choose('plots-versus', '{VERSUS}');
            await until(() => P().drawn().versus === '{VERSUS}' && !$('plots').dataset.loading, 'the scatter');
            const blob = await P().pngBlob();
            const bytes = new Uint8Array(await blob.arrayBuffer());
            let binary = '';
            for (const b of bytes) binary += String.fromCharCode(b);
            return {{points: marks('dot', 'circle').length, svg: P().svgText(), png: btoa(binary),
                     width: main().getAttribute('width')}};
        """, "scatter")
        first, second = self.sql_runs(METRIC), self.sql_runs(VERSUS)
        want = [k for k, x in first.items() if x["usable"] and x["value"] is not None and second[k]["value"] is not None]
        self.assertEqual(r["points"], len(want))
        svg = ET.fromstring(r["svg"].encode())
        self.assertEqual(svg.tag, "{http://www.w3.org/2000/svg}svg")
        texts = {t.text for t in svg.iter("{http://www.w3.org/2000/svg}text")}
        self.assertTrue({x["config"] for x in first.values()} <= texts, "the legend names every configuration")
        self.assertEqual(len(list(svg.iter("{http://www.w3.org/2000/svg}circle"))), len(want))
        with open(os.path.join(SHOTS, "plots-scatter-download.svg"), "w") as f:
            f.write(r["svg"])
        png = base64.b64decode(r["png"])
        self.assertEqual(png[:8], b"\x89PNG\r\n\x1a\n")
        self.assertEqual(struct.unpack(">I", png[16:20])[0], 2 * int(r["width"]))
        with open(os.path.join(SHOTS, "plots-scatter-download.png"), "wb") as f:
            f.write(png)

    def test_the_plots_controls_are_in_the_address(self):
        """The plot's kind, metrics, dataset and tool in the address: a copied address opened in a
        fresh browser shows the same controls and draws the same marks; back and forward return to
        each earlier choice and what it drew."""
        controls = "(() => Object.fromEntries(['kind', 'metric', 'versus', 'param', 'dataset', 'tool'].map(k => [k, $('plots-' + k).value])))()"
        drawn_with = """const drawnWith = (want, what) => until(() => !$('plots').dataset.loading && P().drawn()
                            && Object.entries(want).every(([k, v]) => P().drawn()[k] === v), what);
            const seen = () => ({drawn: P().drawn(), controls: """ + controls + """, dots: main().querySelectorAll('circle').length,
                                 query: Object.fromEntries([...new URLSearchParams(location.search)].filter(([k]) => k.startsWith('plot')))});"""
        with opened(f"{self.base}/?exp={self.exp}&tab=plots") as page:
            r = page.evaluate("(async () => {" + HELPERS + drawn_with + f"""
                await until(() => document.body.dataset.ready && $('plots-kind') && P().drawn(), 'the first plot');
                const first = seen();
                choose('plots-kind', 'sweep');
                await drawnWith({{kind: 'sweep', param: 'sweep_angle'}}, 'the sweep');
                const sweep = seen();
                choose('plots-kind', 'scatter');
                await drawnWith({{kind: 'scatter'}}, 'the scatter');
                choose('plots-metric', '{VERSUS}');
                await drawnWith({{kind: 'scatter', metric: '{VERSUS}'}}, 'the scatter of {VERSUS}');
                choose('plots-versus', '{METRIC}');
                await drawnWith({{metric: '{VERSUS}', versus: '{METRIC}'}}, 'the scatter against {METRIC}');
                const residential = seen();
                // The other dataset than the one drawn first (the first is the first in the runs' order).
                const other = [...$('plots-dataset').options].map(o => o.value).find(d => d !== residential.drawn.dataset);
                choose('plots-dataset', other);
                await drawnWith({{dataset: other, versus: '{METRIC}'}}, 'the other dataset');
                const last = {{...seen(), href: location.href}};
                history.back();
                await drawnWith({{dataset: residential.drawn.dataset, versus: '{METRIC}'}}, 'back to the first dataset');
                const back = seen();
                history.go(-3);
                await drawnWith({{kind: 'sweep'}}, 'back to the sweep');
                const backToSweep = seen();
                history.back();
                await drawnWith({{kind: 'box'}}, 'back to the first plot');
                const backToFirst = seen();
                history.go(5);
                await drawnWith({{dataset: other, kind: 'scatter'}}, 'forward to the other dataset');
                return {{first, sweep, residential, other, last, back, backToSweep, backToFirst, forward: seen()}};
            }})()""")
            page.screenshot(os.path.join(SHOTS, "plots-address-forward.png"))
            self.assertEqual(errors(page.events), [])
        with opened(r["last"]["href"]) as fresh:
            again = fresh.evaluate("(async () => {" + HELPERS + drawn_with + f"""
                await until(() => document.body.dataset.ready && $('plots-kind'), 'the page');
                await drawnWith({{kind: 'scatter', dataset: '{r["other"]}', versus: '{METRIC}'}}, 'the scatter from the address');
                return seen();
            }})()""")
            fresh.screenshot(os.path.join(SHOTS, "plots-address-reopened.png"))
            self.assertEqual(errors(fresh.events), [])
        last = r["last"]
        self.assertEqual(last["query"], {"plot": "scatter", "plot.metric": VERSUS, "plot.versus": METRIC,
                                         "plot.dataset": r["other"], "plot.tool": last["controls"]["tool"]})
        self.assertEqual(last["controls"]["kind"], "scatter")
        self.assertIn(r["other"], ("facade", "residential"))
        self.assertNotEqual(r["residential"]["drawn"]["dataset"], r["other"])
        # The reopened page: the same controls, the same marks, one dot per usable run of that dataset with both values.
        self.assertEqual(again["controls"], last["controls"])
        self.assertEqual(again["drawn"], last["drawn"])
        self.assertEqual(again["query"], last["query"])
        first, second = self.sql_runs(VERSUS, r["other"]), self.sql_runs(METRIC, r["other"])
        want = [k for k, x in first.items() if x["usable"] and x["value"] is not None and second[k]["value"] is not None]
        self.assertEqual(again["dots"], len(want))
        self.assertEqual(last["dots"], len(want))
        # Back and forward: each earlier choice, drawn as it was.
        for got, was in ((r["back"], r["residential"]), (r["backToSweep"], r["sweep"]), (r["backToFirst"], r["first"]),
                         (r["forward"], last)):
            self.assertEqual(got["drawn"], was["drawn"])
            self.assertEqual(got["query"], was["query"])
            self.assertEqual({k: got["controls"][k] for k in ("kind", "metric", "dataset", "tool")},
                             {k: was["controls"][k] for k in ("kind", "metric", "dataset", "tool")})
        self.assertEqual(r["first"]["query"], {})
        self.assertEqual(r["first"]["drawn"]["kind"], "box")

    def test_an_address_of_the_plots_tab_draws_even_when_plots_js_comes_last(self):
        # plots.js held back until the experiments' list has long been answered: the page opened
        # on the Plots tab waits for it (it once failed with "Cannot read properties of undefined").
        with opened(f"{self.base}/?exp={self.exp}") as page:
            page.call("Fetch.enable", patterns=[{"urlPattern": "*/plots.js*"}])
            page.call("Page.navigate", url=f"{self.base}/?exp={self.exp}&tab=plots")
            paused = page.wait_for("Fetch.requestPaused")
            time.sleep(1.5)  # not a measurement: the order of arrival this test is about
            page.call("Fetch.continueRequest", requestId=paused["params"]["requestId"])
            r = page.evaluate("(async () => {" + HELPERS + """
                await until(() => P() && P().drawn() || $('status').textContent, 'the plot or an error');
                return {status: $('status').textContent, drawn: !!(P() && P().drawn())};
            })()""")
            self.assertEqual(errors(page.events), [])
        self.assertEqual(r, {"status": "", "drawn": True})

    def test_without_the_library_the_tab_says_how_to_install_it(self):
        with opened(f"{self.base}/?exp={self.exp}") as page:  # the Experiments tab: no plot, no library asked for
            page.call("Network.enable")
            page.call("Network.setBlockedURLs", urls=["*/vendor/*"])
            page.call("Page.navigate", url=f"{self.base}/?exp={self.exp}&tab=plots")
            note = page.evaluate("(async () => {" + HELPERS + """
                await until(() => $('plots-note') && $('plots-note').textContent, 'the note');
                return $('plots-note').textContent;
            })()""")
            page.screenshot(os.path.join(SHOTS, "plots-no-library.png"))
        self.assertIn("bash scripts/setup.sh", note)
        self.assertEqual(len(note.splitlines()), 1)


if __name__ == "__main__":
    unittest.main()
