"""The history file: append keyed by revision (a rerun replaces), series per planner and wall, the
first revision where a series moved, and plots that name it."""
import csv
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import history  # noqa: E402


def write_counts(path, counts):
    with open(path, "w", encoding="utf-8") as f:
        f.write("# GNU 12.2.0 Release\ncase,instructions\n")
        for k, v in counts.items():
            f.write(f"{k},{v}\n")


def write_quality(path, overlap):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(["dataset", "wall", "planner", "planner_version", "status", "valid", "coverage_reachable",
                    "coverage_wall", "overlap", "length_total", "turns", "waypoints"])
        w.writerow(["seed-cases", "seed_1x1_empty", "zigzag", "1", "ok", "true", "1", "0.9", overlap, "10", "4", "5"])


class History(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="coverbench-history-test-")
        self.file = os.path.join(self.dir, "history.jsonl")

    def add(self, rev, zigzag, spiral, overlap):
        write_counts(os.path.join(self.dir, "c.csv"), {"zigzag/seed_1x1_empty": zigzag, "spiral/seed_1x1_empty": spiral})
        write_quality(os.path.join(self.dir, "q.csv"), overlap)
        return history.append(self.file, rev, os.path.join(self.dir, "c.csv"), os.path.join(self.dir, "q.csv"))

    def test_append_is_keyed_by_revision(self):
        self.assertEqual(self.add("aaa", 100, 200, "0.1"), 1)
        self.assertEqual(self.add("bbb", 100, 200, "0.1"), 2)
        self.assertEqual(self.add("aaa", 150, 200, "0.1"), 2)  # a rerun of aaa replaces it, now last
        entries = history.read_history(self.file)
        self.assertEqual([e["revision"] for e in entries], ["bbb", "aaa"])
        self.assertEqual(entries[1]["cost"]["zigzag/seed_1x1_empty"], 150)
        self.assertEqual(entries[1]["quality"]["seed-cases:seed_1x1_empty/zigzag"]["overlap"], 0.1)

    def test_the_first_change_is_the_revision_that_moved_the_series(self):
        self.assertEqual(history.first_change(["a", "b", "c", "d"], [5, 5, 7, 9]), ("c", 5, 7))
        self.assertEqual(history.first_change(["a", "b", "c"], [None, 5, 5]), None)
        self.assertEqual(history.first_change(["a", "b", "c"], [5, None, 6]), ("c", 5, 6))
        # counts: a move is more than the tolerance; a few instructions of layout are not
        self.assertEqual(history.first_change(["a", "b", "c"], [1000, 1004, 1020], 0.01), ("c", 1004, 1020))
        self.assertEqual(history.first_change(["a", "b"], [1000, 1010], 0.01), None)

    def test_plot_draws_each_planner_and_names_the_first_moving_revision(self):
        self.add("r1", 100, 200, "0.1")
        self.add("r2", 100, 200, "0.1")
        self.add("r3", 130, 200, "0.1")
        self.add("r4", 130, 200, "0.2")
        out = os.path.join(self.dir, "plots")
        self.assertEqual(history.plot(self.file, out), 2)
        self.assertEqual(sorted(os.listdir(out)), ["cost_spiral.svg", "cost_zigzag.svg", "first_changes.md",
                                                    "quality_zigzag.svg"])
        with open(os.path.join(out, "first_changes.md"), encoding="utf-8") as f:
            table = f.read()
        self.assertIn("| instructions (callgrind): zigzag / seed_1x1_empty | r3 | 100 | 130 |", table)
        self.assertIn("| overlap: zigzag / seed-cases:seed_1x1_empty | r4 | 0.1 | 0.2 |", table)
        self.assertNotIn("spiral", table)
        with open(os.path.join(out, "cost_zigzag.svg"), encoding="utf-8") as f:
            svg = f.read()
        self.assertIn("r3", svg)
        before = svg
        history.plot(self.file, out)  # same history, same bytes
        with open(os.path.join(out, "cost_zigzag.svg"), encoding="utf-8") as f:
            self.assertEqual(f.read(), before)


if __name__ == "__main__":
    unittest.main()
