"""The explorer's runs table as a researcher trusts it (issue 64), checked against SQLite itself:

- the API: every metric sorts both ways in SQLite's order (runs without the metric last, ties in
  key order); metric ranges, planner parameters and the wall filter select exactly SQLite's runs;
  the CSV holds the selection in the table's order with every metric; each new parameter's bad
  values are one-line 400s naming it;
- in headless Chromium: (a) two filter changes 50 ms apart (and a sort, then a filter) whose
  first answer is held back end with the table matching both controls; (c) a sort by a metric
  the table could not sort by before, in SQLite's order, each value formatted as the report's
  tables format it (reports/python/coverbench_report/tables.py); (d) a copied address opened in
  a fresh browser shows the same run at the same playback time; (e) back returns to the previous
  filter and forward to the next; (b) an experiment of 10^5 runs pages to its last row, whose key
  and count are SQLite's.

The experiment of 10^5 runs is made cheaply: a small experiment's run rows repeated under new
keys in a copy of its database (the runs and their options; not their metrics or paths, which a
page of the table reads for its own rows only). Screenshots in ARTIFACTS (env
COVERBENCH_ARTIFACTS)."""
import csv
import io
import json
import os
import re
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import unittest
import urllib.error
import urllib.parse
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "reports", "python"))
from check_page import errors, opened  # noqa: E402
from coverbench_report import tables  # noqa: E402

BIN = os.environ.get("COVERBENCH_BINARY", "build/coverbench")
SHOTS = os.environ.get("COVERBENCH_ARTIFACTS", tempfile.gettempdir())
os.makedirs(SHOTS, exist_ok=True)

CONFIG = """name: table-check
output: out
datasets:
  - family: residential
    count: 3
    seed: 2
  - family: facade
    count: 2
    seed: 2
planners: [zigzag, spiral, boustrophedon]
"""

# In the page: waits (generous deadlines, no timed assertion) and the table as shown.
HELPERS = """
const sleep = ms => new Promise(r => setTimeout(r, ms));
const $ = id => document.getElementById(id);
const until = async (f, what) => { for (let k = 0; k < 2400; ++k) { if (f()) return; await sleep(25); } throw new Error('waited for ' + what); };
const ready = () => until(() => document.body.dataset.ready && !$('runs').dataset.loading, 'the page');
const shownQuery = () => new URLSearchParams(($('runs').dataset.shown || '?').split('?')[1]);
const settled = (want, what) => until(() => !$('runs').dataset.loading && want(shownQuery()), what);
const rows = () => [...document.querySelectorAll('#runs tbody tr')];
const column = name => [...$('runs').tHead.rows[0].cells].findIndex(c => c.dataset.column === name);
const table = () => ({count: $('count').textContent, keys: rows().map(r => r.dataset.key),
                      planners: rows().map(r => r.cells[column('planner')].textContent),
                      datasets: rows().map(r => r.cells[column('dataset')].textContent),
                      planner: $('planner').value, dataset: $('dataset').value, sort: $('sort').value, order: $('order').value,
                      shown: $('runs').dataset.shown, address: location.search});
const choose = (id, value) => { $(id).value = value; $(id).dispatchEvent(new Event('change')); };
"""


def start_server(db):
    p = subprocess.Popen([BIN, "serve", db, "--port", "0"], stdout=subprocess.PIPE, text=True)
    m = re.search(r"http://127\.0\.0\.1:(\d+)/", p.stdout.readline())
    if not m:
        p.kill()
        raise RuntimeError("serve did not start")
    return p, f"http://127.0.0.1:{m.group(1)}"


def stop_server(p):
    p.kill()
    p.wait()
    p.stdout.close()


def synthesise(source, target, runs):
    """A copy of `source` whose latest experiment has at least `runs` runs: its run rows (and run
    options) repeated under new keys (five hex digits of the copy's number, then the original key's
    rest; not the copy whose number is the key's own first five digits, which would be the key
    itself). Returns the experiment's id."""
    shutil.copyfile(source, target)
    con = sqlite3.connect(target)
    con.execute("PRAGMA journal_mode = DELETE")
    con.execute("PRAGMA synchronous = OFF")
    (experiment,) = con.execute("SELECT MAX(id) FROM experiments").fetchone()
    (n,) = con.execute("SELECT COUNT(*) FROM experiment_runs WHERE experiment_id = ?", (experiment,)).fetchone()
    con.execute("CREATE TEMP TABLE copies (i INTEGER PRIMARY KEY)")
    con.execute("WITH RECURSIVE c(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM c WHERE i < ?) INSERT INTO copies SELECT i FROM c",
                (-(-runs // n),))
    for table, key in (("runs", "key"), ("run_options", "run_key")):
        cols = [r[1] for r in con.execute(f"PRAGMA table_info({table})")]
        select = ", ".join(f"printf('%05x', copies.i) || substr({c}, 6)" if c == key else f"{table}.{c}" for c in cols)
        con.execute(f"INSERT INTO {table} ({', '.join(cols)}) SELECT {select} FROM copies, {table} "
                    f"WHERE {table}.{key} IN (SELECT run_key FROM experiment_runs WHERE experiment_id = ?) "
                    f"AND printf('%05x', copies.i) != substr({table}.{key}, 1, 5)", (experiment,))
    con.execute("INSERT INTO experiment_runs SELECT ?1, printf('%05x', copies.i) || substr(run_key, 6) FROM copies, experiment_runs "
                "WHERE experiment_id = ?1 AND printf('%05x', copies.i) != substr(run_key, 1, 5)", (experiment,))
    con.commit()
    con.close()
    return experiment


class Served(unittest.TestCase):
    """A test class over one experiment served by `coverbench serve`: its setUpClass sets cls.work (a
    temporary folder), cls.server and cls.base (start_server); this stops both and reads the API."""

    @classmethod
    def tearDownClass(cls):
        stop_server(cls.server)
        shutil.rmtree(cls.work, ignore_errors=True)

    @classmethod
    def get(cls, path):
        with urllib.request.urlopen(cls.base + path, timeout=60) as r:
            return json.load(r)


class Table(Served):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-table-")
        with open(os.path.join(cls.work, "c.yaml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], check=True, capture_output=True)
        cls.db = os.path.join(cls.work, "out", "results.sqlite")
        cls.server, cls.base = start_server(cls.db)
        cls.exp = cls.get("/api/experiments")["experiments"][-1]
        cls.runs_path = f"/api/experiments/{cls.exp['db']}/{cls.exp['id']}/runs"
        cls.specs = {s["name"]: s for s in cls.get("/api/metrics")["metrics"]}


    def sql(self, query, *args):
        con = sqlite3.connect(f"file:{self.db}?mode=ro", uri=True)
        try:
            return con.execute(query, args).fetchall()
        finally:
            con.close()

    def sql_order(self, metric, desc, where=""):
        """The experiment's run keys by `metric` as SQLite orders them: runs without it last, ties by key."""
        return [k for (k,) in self.sql(
            "SELECT e.run_key FROM experiment_runs e LEFT JOIN metrics m ON m.run_key = e.run_key AND m.name = ?1 "
            f"WHERE e.experiment_id = ?2 {where} ORDER BY m.value IS NULL, m.value {'DESC' if desc else 'ASC'}, e.run_key",
            metric, self.exp["id"])]

    def keys(self, query):
        return [r["key"] for r in self.get(f"{self.runs_path}?limit=1000&{query}")["runs"]]

    def error(self, query, path=None):
        try:
            urllib.request.urlopen(self.base + (path or self.runs_path) + "?" + query, timeout=60)
        except urllib.error.HTTPError as e:
            body = json.loads(e.read())
            self.assertEqual(list(body), ["error"])
            self.assertEqual(len(body["error"].splitlines()), 1)
            return e.code, body["error"]
        self.fail(f"{query} was answered")

    def test_the_api_sorts_and_filters_by_every_column_as_sqlite_does(self):
        every = self.get(self.runs_path + "?limit=0")
        self.assertEqual(every["total"], 15)
        self.assertEqual(len(every["metrics"]), len(set(every["metrics"])))
        for metric in every["metrics"]:
            if metric in ("plan_time_ms", "peak_memory_bytes"):
                continue  # columns of the runs table, not the metrics table (sorted the same way)
            for desc in (False, True):
                self.assertEqual(self.keys(f"sort={metric}&order={'desc' if desc else 'asc'}"), self.sql_order(metric, desc), metric)
        # Ranges: inclusive, runs without the metric excluded.
        self.assertEqual(self.keys("min.overlap=0.02&max.overlap=0.2&sort=overlap"),
                         self.sql_order("overlap", False, "AND m.value BETWEEN 0.02 AND 0.2"))
        # Planner parameters: the runs of the planners whose parameter has that value.
        labels = {label: json.loads(params) for label, params in self.sql(
            "SELECT p.label, c.params FROM experiment_planners p JOIN planner_configs c ON c.id = p.config_id WHERE p.experiment_id = ?",
            self.exp["id"])}
        self.assertEqual(every["params"]["sweep_angle"], ["0.0"])
        with_angle = {label for label, params in labels.items() if "sweep_angle" in params}
        self.assertEqual({"zigzag", "boustrophedon"}, with_angle)
        runs = self.get(self.runs_path + "?limit=1000&param.sweep_angle=0.0")["runs"]
        self.assertEqual(sorted(r["planner"] for r in runs), sorted(["zigzag"] * 5 + ["boustrophedon"] * 5))
        self.assertEqual(self.get(self.runs_path + "?param.sweep_angle=90")["total"], 0)
        # The wall filter: every planner's run on that wall.
        wall = runs[0]["wall_name"]
        on_wall = self.get(self.runs_path + "?wall=" + urllib.parse.quote(wall))["runs"]
        self.assertEqual(sorted(r["planner"] for r in on_wall), ["boustrophedon", "spiral", "zigzag"])
        # The CSV: the selection in the table's order, every metric, full precision.
        query = "planner=zigzag&sort=turning_angle&order=desc"
        with urllib.request.urlopen(f"{self.base}{self.runs_path}.csv?{query}", timeout=60) as r:
            self.assertEqual(r.getheader("Content-Type"), "text/csv; charset=utf-8")
            rows = list(csv.DictReader(io.StringIO(r.read().decode())))
        self.assertEqual([row["key"] for row in rows], self.keys(query))
        stored = dict(self.sql("SELECT name, value FROM metrics WHERE run_key = ?", rows[0]["key"]))
        self.assertEqual({k: float(rows[0][k]) for k in stored if stored[k] is not None}, {k: v for k, v in stored.items() if v is not None})
        self.assertEqual(json.loads(rows[0]["params"]), labels["zigzag"])
        # The tool as the tool filter names it (a line tool's shape and a flux profile would be in it).
        self.assertEqual({row["tool"] for row in rows}, {"s=0.1 m, c=0.02 m"})

    def test_bad_values_of_the_new_parameters_are_one_line_400s(self):
        for query, message in (
                ("min.overlap=abc", "min.overlap: must be a finite number, got 'abc'"),
                ("max.overlap=nan", "max.overlap: must be a finite number, got 'nan'"),
                ("min.nonsense=1", "min.nonsense: this experiment has no metric 'nonsense'"),
                ("param.nonsense=1", "param.nonsense: no planner of this experiment has a parameter 'nonsense'"),
                ("planner=a&planner=b", "planner: given twice (each parameter is given once)"),
                ("plannr=zigzag", "plannr: not a parameter of the runs (they take planner, dataset, status, tool, wall, key, "
                                  "param.NAME, min.METRIC, max.METRIC, sort, order, offset, limit)"),
                ("order=%0A", "order: must be asc or desc, got '\\x0a'"),
                ("offset=-1", "offset: must be a whole number from 0 to 1073741824, got '-1'"),
                ("limit=1001", "limit: must be a whole number from 0 to 1000, got '1001'")):
            self.assertEqual(self.error(query), (400, message), query)
        self.assertEqual(self.error("limit=5", self.runs_path + ".csv"), (400, "limit: runs.csv holds every run the filters pass (no paging)"))
        # Past the last run: an empty page that still says how many there are.
        past = self.get(self.runs_path + "?offset=1000000&limit=1000")
        self.assertEqual((past["total"], past["runs"]), (15, []))

    def test_a_filter_race_ends_with_the_latest_answer(self):
        """(a) The first of two changes 50 ms apart has its answer held back 600 ms (a slow
        answer): it comes after the second's and must not be shown."""
        with opened(self.base + "/") as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                const real = window.fetch;
                let n = 0, late = 0;
                window.fetch = async (url, options) => {
                    const runs = String(url).includes('/runs?'), first = runs && ++n === 1;
                    const res = await real(url, runs ? {} : options);  // no abort signal: a late answer does arrive
                    if (first) { await sleep(600); late = 1; }
                    return res;
                };
                choose('planner', 'zigzag');
                await sleep(50);
                choose('dataset', 'facade');
                await settled(q => q.get('planner') === 'zigzag' && q.get('dataset') === 'facade', 'both filters');
                await until(() => late, 'the late answer');
                await sleep(300);
                const filters = table();
                // Sort, then filter: the sort's answer held back.
                choose('dataset', '');
                await settled(q => !q.has('dataset'), 'every dataset');
                n = 0; late = 0;
                $('runs').tHead.rows[0].cells[column('overlap')].click();
                await sleep(50);
                choose('planner', 'spiral');
                await settled(q => q.get('planner') === 'spiral' && q.get('sort') === 'overlap', 'sort and filter');
                await until(() => late, 'the late answer');
                await sleep(300);
                return {filters, sorted: table()};
            })()""")
            self.assertEqual(errors(page.events), [])
            page.screenshot(os.path.join(SHOTS, "table-race.png"))
        f = r["filters"]
        expected = self.keys("planner=zigzag&dataset=facade")
        self.assertEqual((f["planner"], f["dataset"]), ("zigzag", "facade"))
        self.assertEqual(f["keys"], expected)
        self.assertEqual(set(f["planners"]) | set(f["datasets"]), {"zigzag", "facade"})
        self.assertEqual(f["count"], f"rows 1\u2013{len(expected)} of {len(expected)}")
        s = r["sorted"]
        self.assertEqual((s["planner"], s["sort"], s["order"]), ("spiral", "overlap", "asc"))
        self.assertEqual(len(s["keys"]), 5)
        self.assertEqual(s["keys"], self.keys("planner=spiral&sort=overlap&order=asc"))
        self.assertEqual(s["keys"], self.sql_order("overlap", False, "AND e.run_key IN (SELECT key FROM runs r JOIN experiment_planners p "
                                                                      "ON p.config_id = r.config_id AND p.label = 'spiral')"))

    def test_a_metric_not_sortable_before_sorts_in_sqlites_order_with_units(self):
        """(c) turning_angle (not a column of the table before) by the sort control, descending;
        each shown value as the report's tables write it."""
        with opened(self.base + "/") as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                choose('sort', 'turning_angle');
                choose('order', 'desc');
                await settled(q => q.get('sort') === 'turning_angle' && q.get('order') === 'desc', 'the sort');
                const cells = {};
                for (const m of ['turning_angle', 'coverage_reachable', 'peak_memory_bytes', 'turns_30'])
                    cells[m] = rows().map(r => r.cells[column(m)].textContent);
                const heading = $('runs').tHead.rows[0].cells[column('turning_angle')].textContent;
                return {...table(), cells, heading};
            })()""")
            self.assertEqual(errors(page.events), [])
            page.screenshot(os.path.join(SHOTS, "table-sorted.png"))
        order = self.sql_order("turning_angle", True)
        self.assertEqual(r["keys"], order)
        self.assertEqual(r["heading"], "turning_angle (rad) \u25bc")
        for metric, cells in r["cells"].items():
            if metric == "peak_memory_bytes":
                stored = dict(self.sql("SELECT key, peak_memory_bytes FROM runs"))
            else:
                stored = dict(self.sql("SELECT run_key, value FROM metrics WHERE name = ?", metric))
            expected = [tables.value(self.specs[metric], stored.get(k)) for k in order]
            self.assertEqual(cells, expected, metric)
        self.assertTrue(all(c.endswith(" %") for c in r["cells"]["coverage_reachable"]))
        self.assertTrue(all(c.endswith(" rad") for c in r["cells"]["turning_angle"]))

    def test_a_copied_address_shows_the_same_run_at_the_same_time(self):
        """(d) A spiral run held at 37 % of its path: its address, opened in a fresh browser,
        shows that run at that time (within one frame: 1/60 s), under the same filters."""
        with opened(self.base + "/") as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                choose('planner', 'spiral');
                choose('status-filter', 'ok');
                await settled(q => q.get('planner') === 'spiral' && q.get('status') === 'ok', 'the filters');
                rows()[1].click();
                const fig = () => document.querySelector('#viewer figure[data-playback]');
                await until(() => fig(), 'the run');
                fig().querySelector('.player-start').click();
                await until(() => fig().coverbenchPlayer, 'the player');
                const p = fig().coverbenchPlayer;
                p.pause();
                const t = p.duration() * 0.37;
                p.seek(t);
                await until(() => new URLSearchParams(location.search).get('t') === t.toFixed(3), 'the time in the address');
                const img = fig().querySelector('img');
                await until(() => img.complete && img.naturalWidth > 0, 'the picture');
                return {href: location.href, key: rows()[1].dataset.key, t: p.time(), shown: $('runs').dataset.shown};
            })()""")
            page.screenshot(os.path.join(SHOTS, "table-address-before.png"))
            self.assertEqual(errors(page.events), [])
        query = urllib.parse.parse_qs(urllib.parse.urlsplit(r["href"]).query)
        self.assertEqual((query["run"], query["planner"], query["status"]), ([r["key"]], ["spiral"], ["ok"]))
        with opened(r["href"]) as fresh:
            s = fresh.evaluate("(async () => {" + HELPERS + """
                await ready();
                const fig = () => document.querySelector('#viewer figure[data-playback]');
                await until(() => fig() && fig().dataset.restored, 'the player held at the address time');
                const img = fig().querySelector('img');
                await until(() => img.complete && img.naturalWidth > 0, 'the picture');
                const chosen = document.querySelector('#runs tbody tr.chosen');
                return {t: fig().coverbenchPlayer.time(), playhead: fig().dataset.playhead, caption: fig().querySelector('figcaption').textContent,
                        chosen: chosen && chosen.dataset.key, shown: $('runs').dataset.shown, planner: $('planner').value};
            })()""")
            fresh.screenshot(os.path.join(SHOTS, "table-address-after.png"))
            self.assertEqual(errors(fresh.events), [])
        self.assertEqual((s["chosen"], s["shown"], s["planner"]), (r["key"], r["shown"], "spiral"))
        self.assertLessEqual(abs(s["t"] - r["t"]), 1 / 60)
        self.assertTrue(s["caption"].endswith("/ spiral: ok"), s["caption"])

    def test_back_returns_to_the_previous_filter(self):
        """(e) zigzag, then spiral: back shows zigzag's runs, forward spiral's again."""
        with opened(self.base + "/") as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                choose('planner', 'zigzag');
                await settled(q => q.get('planner') === 'zigzag', 'zigzag');
                choose('planner', 'spiral');
                await settled(q => q.get('planner') === 'spiral', 'spiral');
                history.back();
                await settled(q => q.get('planner') === 'zigzag', 'back to zigzag');
                const back = table();
                history.forward();
                await settled(q => q.get('planner') === 'spiral', 'forward to spiral');
                return {back, forward: table()};
            })()""")
            self.assertEqual(errors(page.events), [])
        for view, planner in ((r["back"], "zigzag"), (r["forward"], "spiral")):
            self.assertEqual(view["planner"], planner)
            self.assertEqual(set(view["planners"]), {planner})
            self.assertEqual(view["keys"], self.keys(f"planner={planner}"))
            self.assertIn(f"planner={planner}", view["address"])


class Large(unittest.TestCase):
    """(b) 10^5 runs: the last page's last row is SQLite's last key, and the count is SQLite's."""

    def test_a_large_experiment_pages_to_its_last_row(self):
        with tempfile.TemporaryDirectory(prefix="coverbench-table-large-") as work:
            with open(os.path.join(work, "c.yaml"), "w") as f:
                f.write(CONFIG)
            subprocess.run([BIN, "run", os.path.join(work, "c.yaml"), "--no-report"], check=True, capture_output=True)
            db = os.path.join(work, "large.sqlite")
            experiment = synthesise(os.path.join(work, "out", "results.sqlite"), db, 100000)
            con = sqlite3.connect(db)
            (count, last) = con.execute("SELECT COUNT(*), MAX(run_key) FROM experiment_runs WHERE experiment_id = ?", (experiment,)).fetchone()
            con.close()
            self.assertGreaterEqual(count, 100000)
            server, base = start_server(db)
            try:
                with opened(f"{base}/?exp=0/{experiment}&limit=1000") as page:
                    r = page.evaluate("(async () => {" + HELPERS + """
                        await ready();
                        const first = $('count').textContent;
                        $('last').click();
                        await settled(q => q.get('offset'), 'the last page');
                        const last = rows().at(-1);
                        last.scrollIntoView();
                        return {first, count: $('count').textContent, last: last.dataset.key, rows: rows().length,
                                next: $('next').disabled, address: location.search};
                    })()""")
                    self.assertEqual(errors(page.events), [])
                    page.screenshot(os.path.join(SHOTS, "table-large-last-page.png"))
            finally:
                stop_server(server)
        start = (count - 1) // 1000 * 1000
        self.assertEqual(r["first"], f"rows 1\u20131000 of {count}")
        self.assertEqual(r["count"], f"rows {start + 1}\u2013{count} of {count}")
        self.assertEqual((r["last"], r["rows"], r["next"]), (last, count - start, True))
        self.assertIn(f"offset={start}", r["address"])


if __name__ == "__main__":
    unittest.main()
