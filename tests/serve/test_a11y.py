"""The explorer's page checked by axe-core (issue 64): no serious or critical violation in the
runs table with a run open and playing, in the compare view, and in the workbench tab with a
plan shown. axe-core is npm's package, installed by scripts/setup.sh into reports/web/vendor (env
COVERBENCH_AXE names its axe.min.js); its source is put into the page over DevTools
(Runtime.evaluate), never fetched by the page. Screenshots in ARTIFACTS (env COVERBENCH_ARTIFACTS)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
sys.path.insert(0, HERE)
from check_page import errors, opened  # noqa: E402
from test_table import BIN, CONFIG, HELPERS, SHOTS, start_server, stop_server  # noqa: E402

AXE = os.environ.get("COVERBENCH_AXE", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reports", "web", "vendor", "node_modules", "axe-core", "axe.min.js"))

RUN_AXE = """(async () => {
    const r = await axe.run(document, {resultTypes: ['violations']});
    return r.violations.filter(v => v.impact === 'serious' || v.impact === 'critical').map(v => ({
        id: v.id, impact: v.impact, help: v.help,
        nodes: v.nodes.slice(0, 5).map(n => n.target.join(' ') + ': ' + n.failureSummary.split('\\n').slice(0, 2).join(' '))}));
})()"""


class Accessibility(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if not os.path.isfile(AXE):
            raise FileNotFoundError(
                f"{AXE}: axe-core is not installed (bash scripts/setup.sh installs it)")
        with open(AXE, encoding="utf-8") as f:
            cls.axe = f.read()
        cls.work = tempfile.mkdtemp(prefix="coverbench-a11y-")
        with open(os.path.join(cls.work, "c.yaml"), "w") as f:
            f.write(CONFIG)
        subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], check=True, capture_output=True)
        cls.server, cls.base = start_server(os.path.join(cls.work, "out", "results.sqlite"))

    @classmethod
    def tearDownClass(cls):
        stop_server(cls.server)
        shutil.rmtree(cls.work, ignore_errors=True)

    def check(self, page, where):
        page.evaluate(self.axe + "\n;true")
        found = page.evaluate(RUN_AXE)
        page.screenshot(os.path.join(SHOTS, f"a11y-{where}.png"))
        self.assertEqual(found, [], f"{where}: " + json.dumps(found, indent=1))

    def test_the_explorer_and_the_workbench_pass_axe(self):
        with opened(self.base + "/?dataset=residential", width=1280, height=1000) as page:
            # The runs table with a run open and its player made.
            page.evaluate("(async () => {" + HELPERS + """
                await ready();
                rows()[0].click();
                const fig = () => document.querySelector('#viewer figure[data-playback]');
                await until(() => fig() && fig().querySelector('.player-start'), 'the run');
                fig().querySelector('.player-start').click();
                await until(() => fig().coverbenchPlayer, 'the player');
                fig().coverbenchPlayer.pause();
            })()""")
            self.check(page, "run")
            # The compare view of every planner on that wall.
            page.evaluate("(async () => {" + HELPERS + """
                $('same-wall').click();
                await until(() => $('viewer').coverbenchCompare, 'the compare view');
            })()""")
            self.check(page, "compare")
            # The workbench with that run's wall and planner, planned.
            page.evaluate("(async () => {" + HELPERS + """
                rows()[0].click();
                await until(() => $('open-in-workbench'), 'the run');
                $('open-in-workbench').click();
                await until(() => !$('workbench').hidden && !$('wb-plan').disabled, 'the workbench ready to plan');
                $('wb-plan').click();
                await until(() => document.querySelector('#wb-result figure img'), 'the plan');
            })()""")
            self.check(page, "workbench")
            self.assertEqual(errors(page.events), [])


if __name__ == "__main__":
    unittest.main()
