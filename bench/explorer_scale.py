#!/usr/bin/env python3
"""How fast `coverbench serve` answers on an experiment of 10^5 runs.

Builds a synthetic database: a copy of a results database whose latest experiment's runs are
repeated COPIES times under new keys (the run rows, their options and metrics; not their paths,
so the copies have no picture). Then starts `coverbench serve` on it and times the runs API:
the first query (which reads the experiment), then filters, sorts by metrics and pages, each
asked five times: the first (which reads a metric column and sorts) and the median of the rest.

  python3 bench/explorer_scale.py --coverbench build/coverbench --db results/default/results.sqlite
"""
import argparse
import json
import os
import shutil
import sqlite3
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request


def synthesise(source, target, copies):
    shutil.copyfile(source, target)
    con = sqlite3.connect(target)
    (experiment,) = con.execute("SELECT MAX(id) FROM experiments").fetchone()
    keys = [k for (k,) in con.execute("SELECT run_key FROM experiment_runs WHERE experiment_id = ?", (experiment,))]
    con.execute("CREATE TEMP TABLE originals (key TEXT PRIMARY KEY)")
    con.executemany("INSERT INTO originals VALUES (?)", [(k,) for k in keys])

    def columns(table):
        return [row[1] for row in con.execute(f"PRAGMA table_info({table})")]

    def copy(table, key_column):
        cols = columns(table)
        select = ", ".join(f"printf('%04x', ?1) || substr({c}, 1, 60)" if c == key_column else c for c in cols)
        con.execute(f"INSERT INTO {table} ({', '.join(cols)}) SELECT {select} FROM {table} "
                    f"WHERE {key_column} IN (SELECT key FROM originals)", (i,))

    for i in range(1, copies):
        for table, key_column in [("runs", "key"), ("metrics", "run_key"), ("run_options", "run_key"),
                                  ("run_car", "run_key"), ("planner_stats", "run_key")]:
            copy(table, key_column)
        con.execute("INSERT INTO experiment_runs SELECT ?1, printf('%04x', ?2) || substr(key, 1, 60) FROM originals",
                    (experiment, i))
    con.commit()
    (runs,) = con.execute("SELECT COUNT(*) FROM experiment_runs WHERE experiment_id = ?", (experiment,)).fetchone()
    con.close()
    return experiment, runs


def get(url):
    start = time.perf_counter()
    with urllib.request.urlopen(url) as r:
        body = json.load(r)
    return time.perf_counter() - start, body


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--coverbench", required=True)
    ap.add_argument("--db", required=True, help="a results database whose latest experiment is repeated")
    ap.add_argument("--runs", type=int, default=100000, help="at least this many runs (default 100000)")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        target = os.path.join(tmp, "scale.sqlite")
        con = sqlite3.connect(args.db)
        (n,) = con.execute("SELECT COUNT(*) FROM experiment_runs WHERE experiment_id = (SELECT MAX(id) FROM experiments)").fetchone()
        con.close()
        copies = -(-args.runs // n)
        t0 = time.perf_counter()
        experiment, runs = synthesise(args.db, target, copies)
        print(f"synthetic experiment: {runs} runs ({copies} copies of {n}), built in {time.perf_counter() - t0:.1f} s")
        server = subprocess.Popen([args.coverbench, "serve", target, "--port", "0"], stdout=subprocess.PIPE, text=True)
        try:
            base = server.stdout.readline().split()[2].rstrip("/")
            runs_url = f"{base}/api/experiments/0/{experiment}/runs"
            first, body = get(runs_url + "?limit=100")
            print(f"first query (reads the experiment): {first * 1000:.0f} ms, total {body['total']}")
            planner = body["facets"]["planner"][0]
            queries = {
                "page 1, no sort": "?limit=500",
                "sort by coverage_reachable": "?limit=500&sort=coverage_reachable",
                "sort by overlap, descending": "?limit=500&sort=overlap&order=desc",
                "sort by wall_name": "?limit=500&sort=wall_name",
                f"filter planner={planner}, sort by length_ratio": f"?limit=500&planner={urllib.parse.quote(planner)}&sort=length_ratio",
                "filter status=partial, page 20": "?limit=500&status=partial&offset=10000",
                "last page": f"?limit=1000&offset={runs - 1000}",
            }
            for name, q in queries.items():
                times = []
                for _ in range(5):
                    t, body = get(runs_url + q)
                    times.append(t)
                print(f"{name}: first {times[0] * 1000:.1f} ms, then median {statistics.median(times[1:]) * 1000:.1f} ms "
                      f"(max {max(times[1:]) * 1000:.1f}), {body['total']} match, {len(body['runs'])} returned")
        finally:
            server.terminate()
            server.wait()


if __name__ == "__main__":
    import urllib.parse
    sys.exit(main())
