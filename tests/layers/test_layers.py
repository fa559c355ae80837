"""The layering check can fail (scripts/layers.py): the build's own archives, each time with one
object added that calls what a layer above defines, must be refused, naming the library and the
symbol; a call downward must pass; a declared upward link must be refused."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import layers  # noqa: E402

BUILD = os.environ.get("COVERBENCH_BUILD_DIR", os.path.join(ROOT, "build"))


def a_function_of(lib):
    """A function (mangled) that libcoverbench_LIB defines with a strong definition."""
    out = subprocess.run(["nm", "-P", "--defined-only", os.path.join(BUILD, f"libcoverbench_{lib}.a")],
                         check=True, capture_output=True, text=True).stdout
    return next(p[0] for p in (line.split() for line in out.splitlines())
                if len(p) >= 2 and p[1] == "T" and p[0].startswith("_ZN10coverbench"))


class Layers(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.graph = layers.cmake_graph(BUILD)

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="coverbench-layers-")
        for name in os.listdir(BUILD):
            if name.startswith("libcoverbench_") and name.endswith(".a"):
                shutil.copy(os.path.join(BUILD, name), self.tmp)

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def call_from(self, lib, callee):
        """Adds to libcoverbench_LIB.a an object whose function calls `callee` (a mangled name)."""
        asm, obj = os.path.join(self.tmp, "probe.s"), os.path.join(self.tmp, "probe.o")
        with open(asm, "w") as f:
            f.write(f".text\n.globl layers_probe\nlayers_probe:\n  call {callee}\n  ret\n")
        subprocess.run(["as", "-o", obj, asm], check=True)
        subprocess.run(["ar", "r", os.path.join(self.tmp, f"libcoverbench_{lib}.a"), obj], check=True, capture_output=True)

    def test_the_build_as_it_is_passes(self):
        wrong, libraries, crossing = layers.check(self.tmp, self.graph)
        self.assertEqual(wrong, [])
        self.assertEqual(libraries, 17)
        self.assertGreater(crossing, 100)

    def test_a_call_upward_is_refused_naming_the_library_and_the_function(self):
        for lib, above in (("metrics", "planning"), ("judge", "geometry"), ("planning", "algorithms"),
                           ("geometry", "experiments"), ("experiments", "cli")):
            with self.subTest(lib=lib, calls=above):
                self.tearDown()  # a fresh copy of the archives for each
                self.setUp()
                callee = a_function_of(above)
                self.call_from(lib, callee)
                wrong, _, _ = layers.check(self.tmp, self.graph)
                self.assertEqual(len(wrong), 1, wrong)
                self.assertIn(f"libcoverbench_{lib} uses {layers.demangle(callee)}", wrong[0])
                self.assertIn(f"defined only in libcoverbench_{above}", wrong[0])

    def test_a_call_downward_passes(self):
        self.call_from("algorithms", a_function_of("planning"))
        self.assertEqual(layers.check(self.tmp, self.graph)[0], [])

    def test_a_declared_upward_link_is_refused(self):
        metrics = next(line.split('"')[1] for line in self.graph.splitlines() if 'label = "coverbench_metrics"' in line)
        planning = next(line.split('"')[1] for line in self.graph.splitlines() if 'label = "coverbench_planning"' in line)
        edge = f'"{metrics}" -> "{planning}"  // coverbench_metrics -> coverbench_planning\n'
        wrong, _, _ = layers.check(self.tmp, self.graph + edge)
        self.assertEqual(wrong, ["coverbench_metrics is declared to link coverbench_planning (CMakeLists.txt), "
                                 "a layer it must not use"])


if __name__ == "__main__":
    unittest.main()
