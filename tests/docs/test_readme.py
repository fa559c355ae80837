"""README.md is for users: its first screen says what CoverBench is and gives the two commands;
it holds no commit hash, issue number or version history; every file it links exists."""
import os
import re
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def readme():
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        return f.read()


class Readme(unittest.TestCase):
    def test_first_screen_says_what_it_is_and_gives_the_two_commands(self):
        first = "\n".join(readme().splitlines()[:24])  # a screen of a terminal or a repository page
        self.assertIn("coverage path planners", first)
        for command in ("bash scripts/run_main.sh", "bash scripts/test.sh"):
            self.assertRegex(first, r"(?m)^" + re.escape(command) + r"\b", command)
            self.assertTrue(os.path.exists(os.path.join(ROOT, command.split()[1])), command)

    def test_no_commit_hash_issue_number_or_history(self):
        text = readme()
        for word in re.findall(r"\b[0-9a-f]{7,40}\b", text):
            self.assertFalse(re.search(r"[0-9]", word), f"a commit hash? {word}")
        self.assertNotRegex(text, r"(?i)\bissues? #?\d+")
        self.assertNotRegex(text, r"(?i)\b(session|version history|changelog|before and after)\b")

    def test_every_linked_file_exists(self):
        for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", readme()):
            if "://" in target:
                continue
            self.assertTrue(os.path.exists(os.path.join(ROOT, target)), target)


if __name__ == "__main__":
    unittest.main()
