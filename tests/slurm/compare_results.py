#!/usr/bin/python3
"""Compares the latest experiment of two CoverBench results databases run key by run key.

    compare_results.py A.sqlite B.sqlite

Everything a run computes must be equal: the set of run keys, and for each key its status, reason,
validity, uncovered reachable area, every metric, the planner's statistics, and the stored path
(byte for byte); also the experiment's walls, datasets and planner configurations. What is
measured anew at every run (plan times, CPU time, memory, when it finished, on which host) is
not compared. Exit 0 when equal, 1 with the first differences otherwise.
"""
import sqlite3
import sys

RUN_QUERIES = {
    "run": "SELECT status, reason, valid, quote(uncovered_reachable_m2), base_key, wall_hash, config_id, "
           "planner_version, code_sha256, quote(tool_width), quote(clearance), seed FROM runs WHERE key = ?",
    "metrics": "SELECT name, quote(value) FROM metrics WHERE run_key = ? ORDER BY name",
    "planner_stats": "SELECT name, quote(value) FROM planner_stats WHERE run_key = ? ORDER BY name",
    "path": "SELECT encoding, waypoints, hex(data) FROM paths WHERE run_key = ?",
}
EXPERIMENT_QUERIES = {
    "datasets": "SELECT position, label, source, walls, sha256 FROM experiment_datasets WHERE experiment_id = ? "
                "ORDER BY position",
    "walls": "SELECT w.hash, w.name, w.content, e.dataset FROM experiment_walls e JOIN walls w ON w.hash = e.wall_hash "
             "WHERE e.experiment_id = ? ORDER BY w.hash",
    "planners": "SELECT e.position, e.label, p.planner, p.params FROM experiment_planners e "
                "JOIN planner_configs p ON p.id = e.config_id WHERE e.experiment_id = ? ORDER BY e.position",
    "config": "SELECT config_hash, baseline, compiler, build_type, build_flags FROM experiments WHERE id = ?",
}


def latest(db):
    row = db.execute("SELECT MAX(id) FROM experiments").fetchone()
    if row is None or row[0] is None:
        raise SystemExit("compare_results: a database has no experiment")
    return row[0]


def compare(path_a, path_b, out=sys.stdout):
    a = sqlite3.connect(f"file:{path_a}?mode=ro", uri=True)
    b = sqlite3.connect(f"file:{path_b}?mode=ro", uri=True)
    ea, eb = latest(a), latest(b)
    differences = []
    for name, sql in EXPERIMENT_QUERIES.items():
        if a.execute(sql, (ea,)).fetchall() != b.execute(sql, (eb,)).fetchall():
            differences.append(f"experiment {name} differ")
    keys_sql = "SELECT run_key FROM experiment_runs WHERE experiment_id = ? ORDER BY run_key"
    keys_a = [k for (k,) in a.execute(keys_sql, (ea,))]
    keys_b = [k for (k,) in b.execute(keys_sql, (eb,))]
    only_a, only_b = sorted(set(keys_a) - set(keys_b)), sorted(set(keys_b) - set(keys_a))
    if only_a:
        differences.append(f"{len(only_a)} run keys only in {path_a}, e.g. {only_a[0][:12]}")
    if only_b:
        differences.append(f"{len(only_b)} run keys only in {path_b}, e.g. {only_b[0][:12]}")
    compared = 0
    for key in sorted(set(keys_a) & set(keys_b)):
        compared += 1
        for name, sql in RUN_QUERIES.items():
            ra, rb = a.execute(sql, (key,)).fetchall(), b.execute(sql, (key,)).fetchall()
            if ra != rb:
                differences.append(f"run {key[:12]}: {name} differ ({str(ra)[:120]} vs {str(rb)[:120]})")
    for table in ("runs",):
        for db, path in ((a, path_a), (b, path_b)):
            n, distinct = db.execute(f"SELECT COUNT(*), COUNT(DISTINCT key) FROM {table}").fetchone()
            if n != distinct:
                differences.append(f"{path}: {n - distinct} duplicate run keys")
    if differences:
        print(f"DIFFERENT: {len(differences)} differences between {path_a} and {path_b}", file=out)
        for d in differences[:20]:
            print("  " + d, file=out)
        return 1
    print(f"EQUAL: {compared} runs, run key by run key (status, metrics, statistics, paths), and the "
          f"experiment's walls, datasets and planners", file=out)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    sys.exit(compare(sys.argv[1], sys.argv[2]))
