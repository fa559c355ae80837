"""`coverbench export-ompl` against OMPL's own log parser and a strict reading of its format.

A small experiment (a suite with partial runs, and a family) is run, exported, and:
- every log is read by a strict parser of the format OMPL documents (benchmark.html, "The
  benchmark logfile format"): every count line matches what follows, every run line has exactly
  one value per property, and each value parses as its declared type;
- OMPL's ompl_benchmark_statistics (Debian's ompl-demos) loads the logs into its database and
  plots them; the database holds one experiment per dataset, one planner entry per planner
  configuration, and each run's figures equal CoverBench's own, run key by run key.

COVERBENCH: the coverbench binary (set by CTest).
"""
import math
import os
import shutil
import sqlite3
import subprocess
import tempfile
import unittest

OMPL_STATISTICS = "/usr/bin/ompl_benchmark_statistics"
CONFIG = """name: ompl-export
output: out
datasets:
  - suite: seed-cases
  - family: residential
    count: 3
    seed: 2
planners:
  - zigzag
  - name: spiral
    params:
      overlap: [0, 0.25]
tool:
  width: 0.1
  clearance: 0.02
limits:
  time_s: 30
  memory_mb: 1024
seed: 5
"""
TYPES = {"REAL", "INTEGER", "BOOLEAN", "STRING", "ENUM"}


def parse_strict(text):
    """The log as a dict, or an AssertionError naming the line that breaks the format."""
    lines = text.split("\n")
    assert lines[-1] == "", "the log ends with a newline"
    pos = 0

    def take():
        nonlocal pos
        assert pos < len(lines) - 1, "the log ends early"
        pos += 1
        return lines[pos - 1]

    def count(line, *suffix):
        words = line.split()
        assert words[1:] == list(suffix), f"line {pos}: expected 'N {' '.join(suffix)}', got {line!r}"
        return int(words[0])

    def multiline():
        assert take() == "<<<|", f"line {pos}: expected <<<|"
        body = []
        while (line := take()) != "|>>>":
            body.append(line)
        return "\n".join(body)

    log = {}
    first = take().split()
    assert first[1] == "version" and len(first) == 3, "line 1: LIBRARY version X"
    experiment = take().split()
    assert experiment[0] == "Experiment" and len(experiment) == 2, "line 2: Experiment NAME (one word)"
    log["name"] = experiment[1]
    props = {}
    for _ in range(count(take(), "experiment", "properties")):
        key, value = take().split(" = ", 1)
        name, typ = key.rsplit(" ", 1)
        assert typ in TYPES, f"line {pos}: type {typ}"
        props[name] = value
    log["properties"] = props
    running = take().split()
    assert running[:2] == ["Running", "on"] and len(running) == 3, f"line {pos}: Running on HOST"
    assert take().startswith("Starting at "), f"line {pos}: Starting at DATE"
    log["setup"] = multiline()
    log["cpuinfo"] = multiline()
    log["seed"] = count(take(), "is", "the", "random", "seed")
    log["time_limit"] = float(take().split()[0])
    assert lines[pos - 1].endswith(" seconds per run")
    log["memory_limit"] = float(take().split()[0])
    assert lines[pos - 1].endswith(" MB per run")
    if lines[pos].endswith(" runs per planner"):
        log["runs_per_planner"] = count(take(), "runs", "per", "planner")
    assert take().endswith(" seconds spent to collect the data")
    enums = {}
    for _ in range(count(take(), "enum", "types")):
        name, *values = take().split("|")
        enums[name] = values
    log["enums"] = enums
    planners = {}
    for _ in range(count(take(), "planners")):
        name = take()
        settings = [take() for _ in range(count(take(), "common", "properties"))]
        properties = []
        for _ in range(count(take(), "properties", "for", "each", "run")):
            *words, typ = take().split()
            assert typ in TYPES, f"line {pos}: type {typ}"
            properties.append(("_".join(words), typ))
        runs = []
        for _ in range(count(take(), "runs")):
            line = take()
            assert line.endswith("; "), f"line {pos}: a run line ends with '; '"
            values = line[:-2].split("; ")
            assert len(values) == len(properties), f"line {pos}: {len(values)} values, {len(properties)} properties"
            run = {}
            for (name_, typ), v in zip(properties, values):
                if typ == "REAL":
                    run[name_] = float(v)  # "nan" included
                elif typ in ("INTEGER", "ENUM"):
                    run[name_] = None if v == "nan" else int(v)
                    if typ == "ENUM" and run[name_] is not None:
                        assert 0 <= run[name_] < len(enums[name_]), f"line {pos}: enum {name_} value {v}"
                elif typ == "BOOLEAN":
                    assert v in ("0", "1"), f"line {pos}: boolean {name_} = {v!r}"
                    run[name_] = v == "1"
                else:
                    run[name_] = v
            runs.append(run)
        assert take() == ".", f"line {pos}: a planner's runs end with '.' (no progress data)"
        planners[name] = {"settings": settings, "runs": runs}
    log["planners"] = planners
    assert pos == len(lines) - 1, f"line {pos}: text after the last planner"
    return log


class OmplExport(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.coverbench = os.environ["COVERBENCH"]
        cls.dir = tempfile.mkdtemp(prefix="coverbench-ompl-")
        with open(os.path.join(cls.dir, "exp.yaml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([cls.coverbench, "run", os.path.join(cls.dir, "exp.yaml"), "--no-report"], check=True,
                       capture_output=True)
        cls.results = os.path.join(cls.dir, "out", "results.sqlite")
        cls.logs = os.path.join(cls.dir, "ompl")
        subprocess.run([cls.coverbench, "export-ompl", cls.results, "--out", cls.logs], check=True, capture_output=True)
        cls.ours = sqlite3.connect(cls.results)

    @classmethod
    def tearDownClass(cls):
        cls.ours.close()
        shutil.rmtree(cls.dir)

    def log_files(self):
        return sorted(os.path.join(self.logs, f) for f in os.listdir(self.logs))

    def test_every_log_follows_the_documented_format_strictly(self):
        files = self.log_files()
        self.assertEqual([os.path.basename(f) for f in files],
                         ["ompl-export.residential.log", "ompl-export.seed-cases.log"])
        statuses = dict(self.ours.execute("SELECT key, status FROM runs"))
        for path in files:
            with open(path) as f:
                log = parse_strict(f.read())
            self.assertEqual(log["seed"], 5)
            self.assertEqual(log["time_limit"], 30.0)
            self.assertEqual(log["memory_limit"], 1024.0)
            self.assertIn("name: ompl-export", log["setup"])
            self.assertEqual(list(log["planners"]), ["zigzag", "spiral(overlap=0)", "spiral(overlap=0.25)"])
            walls = int(log["properties"]["walls"])
            self.assertEqual(log["runs_per_planner"], walls)
            for planner in log["planners"].values():
                self.assertEqual(len(planner["runs"]), walls)
                for run in planner["runs"]:
                    status = log["enums"]["run_status"][run["run_status"]]
                    self.assertEqual(status, statuses[run["run_key"]])
                    self.assertEqual(run["solved"], status in ("ok", "partial") and run["valid"])
                    self.assertEqual(run["approximate_solution"], status == "partial")
        with open(files[1]) as f:
            seed = parse_strict(f.read())
        self.assertTrue(any(r["approximate_solution"] for p in seed["planners"].values() for r in p["runs"]),
                        "the seed cases have partial runs")

    def test_ompl_loads_the_logs_and_holds_our_figures(self):
        self.assertTrue(os.path.exists(OMPL_STATISTICS), "install Debian's ompl-demos (scripts/setup.sh does)")
        db = os.path.join(self.dir, "benchmark.db")
        out = subprocess.run([OMPL_STATISTICS, *self.log_files(), "-d", db, "-p", "-v"], capture_output=True, text=True,
                             cwd=self.dir)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertGreater(os.path.getsize(os.path.join(self.dir, "benchmark.pdf")), 10000, "OMPL plotted the runs")
        ompl = sqlite3.connect(db)
        experiments = ompl.execute("SELECT name, runcount, timelimit, memorylimit, seed, dataset FROM experiments "
                                   "ORDER BY name").fetchall()
        self.assertEqual(experiments, [("ompl-export.residential", 3, 30.0, 1024.0, "5", "residential"),
                                       ("ompl-export.seed-cases", 9, 30.0, 1024.0, "5", "seed-cases")])
        self.assertEqual(sorted(n for (n,) in ompl.execute("SELECT DISTINCT name FROM plannerConfigs")),
                         ["spiral(overlap=0)", "spiral(overlap=0.25)", "zigzag"])
        ours = {row[0]: row[1:] for row in self.ours.execute(
            "SELECT r.key, r.plan_time_ms, r.status, "
            "(SELECT value FROM metrics m WHERE m.run_key = r.key AND m.name = 'coverage_reachable'), "
            "(SELECT value FROM metrics m WHERE m.run_key = r.key AND m.name = 'length_total') FROM runs r")}
        theirs = ompl.execute("SELECT r.run_key, r.time, e.description, r.coverage_reachable, r.length_total FROM runs r "
                              "JOIN enums e ON e.name = 'run_status' AND e.value = r.run_status").fetchall()
        self.assertEqual(len(theirs), len(ours))
        for key, time_s, status, coverage, length in theirs:
            plan_ms, our_status, our_coverage, our_length = ours[key]
            self.assertEqual(status, our_status, key)
            self.assertTrue(math.isclose(time_s, plan_ms / 1000, rel_tol=1e-12), key)
            if our_coverage is None:
                self.assertIsNone(coverage)
            else:
                self.assertEqual(coverage, our_coverage, key)  # printed exactly, read back exactly
                self.assertEqual(length, our_length, key)


HOSTILE = """name: "hostile
|>>> name"
output: out
datasets:
  - suite: seed-cases
    label: a = b
planners:
  - zigzag
seed: 3
"""


class HostileText(unittest.TestCase):
    """A config line that starts with OMPL's block end and a label with OMPL's ' = ' separator."""

    def test_ompl_reads_the_whole_log(self):
        coverbench = os.environ["COVERBENCH"]
        folder = tempfile.mkdtemp(prefix="coverbench-ompl-hostile-")
        try:
            with open(os.path.join(folder, "exp.yaml"), "w") as f:
                f.write(HOSTILE)
            subprocess.run([coverbench, "run", os.path.join(folder, "exp.yaml"), "--no-report"], check=True,
                           capture_output=True)
            logs = os.path.join(folder, "ompl")
            subprocess.run([coverbench, "export-ompl", os.path.join(folder, "out", "results.sqlite"), "--out", logs],
                           check=True, capture_output=True)
            [name] = os.listdir(logs)
            with open(os.path.join(logs, name)) as f:
                log = parse_strict(f.read())
            self.assertIn("\n |>>> name", log["setup"], "the line is kept, a space before it")
            self.assertEqual(log["seed"], 3)
            db = os.path.join(folder, "benchmark.db")
            out = subprocess.run([OMPL_STATISTICS, os.path.join(logs, name), "-d", db], capture_output=True, text=True,
                                 cwd=folder)
            self.assertEqual(out.returncode, 0, out.stderr)
            ompl = sqlite3.connect(db)
            self.assertEqual(ompl.execute("SELECT dataset, coverbench_experiment, seed FROM experiments").fetchall(),
                             [("a=b", "hostile |>>> name", "3")])
            self.assertEqual(ompl.execute("SELECT COUNT(*) FROM runs").fetchone(), (9,))
            ompl.close()
        finally:
            shutil.rmtree(folder)


if __name__ == "__main__":
    unittest.main()
