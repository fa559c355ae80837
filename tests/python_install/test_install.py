"""The Python package as a user installs it (README.md, "From Python"): `pip install ./python` into
a fresh virtual environment and for the user, then `import coverbench` plans and scores a wall
with that interpreter alone: no PYTHONPATH, no .pth file, run from another folder. pip is given
no index (this machine reaches no PyPI): the build backend needs nothing from it. The backend
reuses the build folder (COVERBENCH_BUILD_DIR, set by ctest), so nothing is compiled again.

Interpreters: Debian's /usr/bin/python3 (venv; for the user with --break-system-packages, which
its PEP 668 marker asks for, into a temporary user base) and the `python3` first on PATH when it
is another one (pyenv's here) of the same ABI. And `python_types`: mypy on the package and the
Python examples, and on a call the stub says is wrong."""
import json
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BUILD = os.environ.get("COVERBENCH_BUILD_DIR", os.path.join(ROOT, "build"))
WALL = os.path.join(ROOT, "datasets", "canonical", "living_room_north.json")
EXAMPLE = os.path.join(ROOT, "examples", "python_api", "plan_and_score.py")

# Run by the installed interpreter from a folder outside the tree: plans and scores the wall.
CHECK = r"""
import json, sys
import coverbench
wall = sys.argv[1]
p = coverbench.plan(wall, "zigzag")
s = coverbench.score(wall, p["waypoints"], p["tool_on"], bulge=p.get("bulge"))
bad = coverbench.score(wall, [[0.2, 1.0], [4.0, 1.0]], [True])
print(json.dumps({"file": coverbench.__file__, "status": p["status"], "plan_valid": p["valid"],
                  "waypoints": type(p["waypoints"]).__module__ + "." + type(p["waypoints"]).__name__,
                  "n": len(p["waypoints"]), "valid": s["valid"], "coverage": s["coverage_reachable"],
                  "bad_valid": bad["valid"], "bad_segments": bad["violating_segments"],
                  "doc": coverbench.score.__doc__ is not None and "violating_segments" in coverbench.score.__doc__}))
"""


def interpreters():
    """Debian's python3, and python3 on PATH when it is another interpreter of the same ABI."""
    out = ["/usr/bin/python3"]
    other = shutil.which("python3", path=os.environ.get("PATH", ""))
    if other and os.path.realpath(other) != os.path.realpath(out[0]):
        suffix = subprocess.run([other, "-c", "import sysconfig; print(sysconfig.get_config_var('EXT_SUFFIX'))"],
                                capture_output=True, text=True).stdout.strip()
        if suffix == sysconfig.get_config_var("EXT_SUFFIX"):
            out.append(other)
        else:
            print(f"note: {other} ({suffix}) is not tested: the build folder is for {sys.executable}", file=sys.stderr)
    return out


def clean_env(**extra):
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_", "VIRTUAL_ENV"))}
    env.update({"PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1", "PIP_NO_CACHE_DIR": "1",
                "COVERBENCH_BUILD_DIR": BUILD})
    env.update(extra)
    return env


class Install(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="coverbench-install-")
        self.addCleanup(shutil.rmtree, self.tmp)

    def run_ok(self, cmd, env, cwd=None):
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd or self.tmp)
        self.assertEqual(r.returncode, 0, f"{' '.join(cmd)}\n{r.stdout}\n{r.stderr}")
        return r.stdout

    def check(self, python, env, where):
        out = json.loads(self.run_ok([python, "-c", CHECK, WALL], env).strip().splitlines()[-1])
        self.assertTrue(out["file"].startswith(where), out["file"])  # the installed copy, not the tree
        self.assertEqual((out["status"], out["plan_valid"], out["valid"], out["doc"]), ("ok", True, True, True))
        self.assertIs(out["valid"], True)
        self.assertGreater(out["coverage"], 0.99)
        # The path through the window: invalid, and its one segment named.
        self.assertEqual((out["bad_valid"], out["bad_segments"]), (False, [0]))
        return out

    def test_a_venv_installs_the_package_and_plans_and_scores(self):
        for k, python in enumerate(interpreters()):
            with self.subTest(python=python):
                venv = os.path.join(self.tmp, f"v{k}")
                self.run_ok([python, "-m", "venv", venv], clean_env())
                self.run_ok([os.path.join(venv, "bin", "pip"), "install", os.path.join(ROOT, "python")], clean_env())
                out = self.check(os.path.join(venv, "bin", "python"), clean_env(PYTHONNOUSERSITE="1"), venv)
                self.assertIn(out["waypoints"], ("builtins.list", "numpy.ndarray"))
                # The example of the README runs with it.
                self.run_ok([os.path.join(venv, "bin", "python"), EXAMPLE, WALL], clean_env(PYTHONNOUSERSITE="1"))

    def test_with_numpy_the_waypoints_are_an_array(self):
        # Debian's numpy, seen from a venv that sees the system's packages.
        venv = os.path.join(self.tmp, "vs")
        self.run_ok(["/usr/bin/python3", "-m", "venv", "--system-site-packages", venv], clean_env())
        self.run_ok([os.path.join(venv, "bin", "pip"), "install", os.path.join(ROOT, "python")], clean_env())
        out = self.check(os.path.join(venv, "bin", "python"), clean_env(PYTHONNOUSERSITE="1"), venv)
        self.assertEqual(out["waypoints"], "numpy.ndarray")

    def test_a_user_install_plans_and_scores(self):
        for k, python in enumerate(interpreters()):
            with self.subTest(python=python):
                base = os.path.join(self.tmp, f"user{k}")
                env = clean_env(PYTHONUSERBASE=base)
                managed = self.run_ok([python, "-c", "import os, sysconfig; print(os.path.exists(os.path.join("
                                       "sysconfig.get_path('stdlib'), 'EXTERNALLY-MANAGED')))"], env).strip() == "True"
                extra = ["--break-system-packages"] if managed else []
                self.run_ok([python, "-m", "pip", "install", "--user", *extra, os.path.join(ROOT, "python")], env)
                self.check(python, env, base)

    def test_the_wheel_holds_the_package_its_stub_and_the_module(self):
        import zipfile
        wheels = os.path.join(self.tmp, "wheels")
        self.run_ok(["/usr/bin/python3", "-m", "pip", "wheel", "--no-deps", "-w", wheels, os.path.join(ROOT, "python")],
                    clean_env())
        (name,) = os.listdir(wheels)
        tag = f"cp{sys.version_info.major}{sys.version_info.minor}"
        self.assertEqual(name, f"coverbench-0.1.0-{tag}-{tag}-linux_x86_64.whl")
        with zipfile.ZipFile(os.path.join(wheels, name)) as z:
            names = set(z.namelist())
            record = z.read("coverbench-0.1.0.dist-info/RECORD").decode()
        for n in ("coverbench/__init__.py", "coverbench/serve.py", "coverbench/_core.pyi", "coverbench/py.typed",
                  "coverbench/_core" + sysconfig.get_config_var("EXT_SUFFIX"), "coverbench/libcoverbench_gdal.so",
                  "coverbench/libcoverbench_ompl.so", "coverbench-0.1.0.dist-info/METADATA",
                  "coverbench-0.1.0.dist-info/WHEEL"):
            self.assertIn(n, names)
            self.assertIn(n + ",sha256=", record)
        # Nothing of the build is left in the source tree's python/.
        left = [n for n in os.listdir(os.path.join(ROOT, "python")) if n in ("build", "dist") or n.endswith(".egg-info")]
        self.assertEqual(left, [])


class Types(unittest.TestCase):
    CONFIG = os.path.join(ROOT, "python", "pyproject.toml")

    def mypy(self, *paths):
        return subprocess.run(["/usr/bin/python3", "-m", "mypy", "--config-file", self.CONFIG, "--no-incremental",
                               "--cache-dir", os.devnull, *paths], capture_output=True, text=True, cwd=ROOT)

    def test_mypy_accepts_the_package_and_the_examples(self):
        r = self.mypy("python/coverbench", "examples/python_planner", "examples/python_api")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("Success: no issues found in", r.stdout)

    def test_mypy_refuses_a_wrong_call(self):
        with tempfile.TemporaryDirectory() as d:
            bad = os.path.join(d, "bad.py")
            with open(bad, "w", encoding="utf-8") as f:
                f.write("import coverbench\ncoverbench.plan('w.json', 3)\ncoverbench.score('w.json', [], [], judge=1)\n")
            r = self.mypy(bad)
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
        self.assertIn('Argument 2 to "plan" has incompatible type "int"; expected "str"', r.stdout)
        self.assertIn('Argument "judge" to "score" has incompatible type "int"; expected "str"', r.stdout)


if __name__ == "__main__":
    unittest.main()
