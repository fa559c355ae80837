"""The explorer's compare view and keys (issue 64), in headless Chromium on a small experiment
(three planners on five walls):

- a run's "other planners on this wall" opens the compare of every planner's run on that wall
  with the same tool: one play button, one time slider and one clock readout for all, no picture
  with a play button of its own; the clock reads 0.0 s at first; after play and after a seek every
  picture's playhead is at the clock's time (within a frame); the metrics table marks the better
  value as the registry's direction says; Space on a table row plays and pauses the clock; the pictures are at least 600 px wide, two a row at
  1280 px; the address holds the compared runs and the time, and reopens them;
- the address holds the player's speed and the pictures' zoom, of one run and of compared runs:
  a copied address reopens them, back and forward return to each earlier one, and a wheel's run
  of zoom steps is one history entry;
- a run whose wall no other planner ran on (in its experiment, with its tool) opens a compare
  that says so;
- the keys: Tab reaches the "skip to the player" link first and Enter on it takes the focus to
  the play button; Enter on a focused row opens that run and the focus stays on the row; Space
  plays and pauses; the arrows move the time by 1 s and, with Shift, 10 s; Enter on a heading's
  button sorts by it.

Every wait is for a condition with a deadline of a minute; no assertion is on a time taken.
Screenshots in ARTIFACTS (env COVERBENCH_ARTIFACTS)."""
import os
import subprocess
import sys
import tempfile
import unittest
import urllib.parse
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "browser"))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "reports", "python"))
from check_page import errors, opened  # noqa: E402
from coverbench_report import stats  # noqa: E402
from test_table import Served, BIN, CONFIG, HELPERS, SHOTS, start_server  # noqa: E402

FRAME = 1 / 60

# An experiment of one planner on one wall, made before the main one (so that the page opens the
# main one, the latest): its run's wall has no other planner's run.
LONE = """name: lone-check
output: out
datasets:
  - family: facade
    count: 1
    seed: 2
planners: [zigzag]
"""

# In the page: the viewer's pictures, their zoom and their players' speed.
VIEWER = """
const figs = () => [...document.querySelectorAll('#viewer figure')];
const query = () => new URLSearchParams(location.search);
const loaded = () => until(() => figs().length && figs().every(f => { const i = f.querySelector('img'); return i.complete && i.naturalWidth > 0; }), 'the pictures');
const shown = () => ({zoom: figs().map(f => f.coverbenchZoom ? f.coverbenchZoom.zoom() : null),
                      laid: figs().map(f => { const v = f.querySelector('.zoom-view'), i = f.querySelector('.zoom-inner'); return v && i ? i.offsetWidth / v.clientWidth : null; }),
                      canvas: figs().map(f => { const c = f.querySelector('.player-canvas'); return c ? c.width : null; }),
                      address: {zoom: query().get('zoom'), speed: query().get('speed')}});
"""

KEYS = {"Tab": ("Tab", 9, ""), "Enter": ("Enter", 13, "\r"), " ": ("Space", 32, " "),
        "ArrowLeft": ("ArrowLeft", 37, ""), "ArrowRight": ("ArrowRight", 39, "")}


def press(page, key, shift=False):
    """A key pressed and released as the user's keyboard sends it (DevTools Input events)."""
    code, vk, text = KEYS[key]
    common = dict(key=key, code=code, windowsVirtualKeyCode=vk, nativeVirtualKeyCode=vk, modifiers=8 if shift else 0)
    page.call("Input.dispatchKeyEvent", type="keyDown" if text else "rawKeyDown", text=text, **common)
    page.call("Input.dispatchKeyEvent", type="keyUp", **common)


class Compare(Served):
    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="coverbench-compare-")
        with open(os.path.join(cls.work, "c.yaml"), "w") as f:
            f.write(CONFIG)
        with open(os.path.join(cls.work, "lone.yaml"), "w") as f:
            f.write(LONE)
        subprocess.run([BIN, "run", os.path.join(cls.work, "lone.yaml"), "--no-report"], check=True, capture_output=True)
        subprocess.run([BIN, "run", os.path.join(cls.work, "c.yaml"), "--no-report"], check=True, capture_output=True)
        cls.server, cls.base = start_server(os.path.join(cls.work, "out", "results.sqlite"))
        experiments = cls.get("/api/experiments")["experiments"]
        cls.exp, cls.lone = experiments[-1], next(e for e in experiments if e["name"] == "lone-check")
        cls.runs_path = f"/api/experiments/{cls.exp['db']}/{cls.exp['id']}/runs"
        cls.specs = {s["name"]: s for s in cls.get("/api/metrics")["metrics"]}


    def test_other_planners_on_a_wall_play_on_one_clock(self):
        with opened(self.base + "/?planner=zigzag&dataset=residential", width=1280, height=1000) as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                const viewer = $('viewer');
                rows()[0].click();
                await until(() => $('same-wall'), 'the run');
                $('same-wall').click();
                await until(() => viewer.coverbenchCompare, 'the compare view');
                const all = viewer.coverbenchCompare;
                const figures = [...viewer.querySelectorAll('.compare figure')];
                const visible = e => e.getClientRects().length > 0;
                const imgs = figures.map(f => f.querySelector('img'));
                await until(() => imgs.every(i => i.complete && i.naturalWidth > 0), 'the pictures');
                const first = {clock: viewer.querySelector('.compare-clock').textContent, focus: document.activeElement.className,
                               plays: [...viewer.querySelectorAll('button')].filter(b => visible(b) && /play/.test(b.textContent)).length,
                               sliders: [...viewer.querySelectorAll('input[type=range]')].filter(visible).length,
                               widths: imgs.map(i => i.getBoundingClientRect().width), tops: figures.map(f => f.getBoundingClientRect().top),
                               keys: figures.map(f => f.dataset.playback.split('/').at(-2)),
                               planners: [...viewer.querySelectorAll('table.compare-metrics thead th')].slice(1).map(t => t.textContent),
                               marked: Object.fromEntries([...viewer.querySelectorAll('table.compare-metrics tbody tr[data-metric]')].map(
                                   tr => [tr.dataset.metric, [...tr.cells].slice(1).map(c => c.classList.contains('better'))])),
                               address: location.search, longest: all.duration()};
                // The playheads against the clock: each at the clock's time, or its own end.
                const apart = () => Math.max(...all.players.map(p => Math.abs(p.time() - Math.min(all.time(), p.duration()))));
                viewer.querySelector('.compare-play').click();
                await until(() => all.time() > 2, 'the clock past 2 s');
                const playing = {apart: apart(), t: all.time(), playing: all.playing()};
                viewer.querySelector('.compare-play').click();
                const paused = {apart: apart(), playing: all.playing(), t: all.time()};
                const scrub = viewer.querySelector('.compare-bar input[type=range]');
                scrub.value = String(all.duration() * 0.4);
                scrub.dispatchEvent(new Event('input'));
                const heads = () => [...viewer.querySelectorAll('.compare figure')].map(f => Number(f.dataset.playhead));
                const seeked = {apart: apart(), t: all.time(), heads: heads(), ends: all.players.map(p => p.duration()),
                                clock: viewer.querySelector('.compare-clock').textContent};
                await until(() => new URLSearchParams(location.search).get('t') === all.time().toFixed(3), 'the time in the address');
                return {first, playing, paused, seeked, href: location.href};
            })()""")
            page.screenshot(os.path.join(SHOTS, "compare-from-run.png"))
            # Space, with the focus on a row of the table, plays and pauses the shared clock.
            page.evaluate("document.querySelector('#runs tbody tr').focus()")
            press(page, " ")
            spaced = page.evaluate("(async () => {" + HELPERS + """
                const all = $('viewer').coverbenchCompare, t0 = all.time();
                await until(() => all.playing() && all.time() > t0, 'Space playing the clock');
                return t0;
            })()""")
            press(page, " ")
            space_paused = page.evaluate("""(() => { const all = document.getElementById('viewer').coverbenchCompare;
                return {playing: all.playing(), after: all.time(),
                        apart: Math.max(...all.players.map(p => Math.abs(p.time() - Math.min(all.time(), p.duration()))))}; })()""")
            page.evaluate("document.querySelector('table.compare-metrics').scrollIntoView()")
            page.screenshot(os.path.join(SHOTS, "compare-metrics.png"))
            self.assertEqual(errors(page.events), [])
        self.assertFalse(space_paused["playing"])
        self.assertGreater(space_paused["after"], spaced)
        self.assertLessEqual(space_paused["apart"], FRAME)
        f = r["first"]
        # Every planner's run on that wall with that tool, each once.
        wall_runs = self.get(self.runs_path + "?key=" + f["keys"][0])["runs"][0]
        expected = self.get(self.runs_path + "?" + urllib.parse.urlencode(
            {"wall": wall_runs["wall_name"], "tool": wall_runs["tool"], "limit": 1000}))["runs"]
        self.assertEqual(sorted(f["keys"]), sorted(x["key"] for x in expected))
        self.assertEqual(sorted(f["planners"]), ["boustrophedon", "spiral", "zigzag"])
        query = urllib.parse.parse_qs(urllib.parse.urlsplit(r["href"]).query)
        self.assertEqual(query["cmp"][0].split(","), f["keys"])
        self.assertEqual(query["wall"], [wall_runs["wall_name"]])
        # One clock: one play button and one slider shown, reading 0.0 s at first.
        self.assertEqual((f["plays"], f["sliders"]), (1, 1))
        self.assertTrue(f["clock"].startswith("0.0 s / "), f["clock"])
        self.assertTrue(f["clock"].endswith("(0 % of the longest run)"), f["clock"])
        self.assertEqual(f["focus"], "compare-play")
        # Two a row, each at least 600 px wide.
        self.assertTrue(all(w >= 600 for w in f["widths"]), f["widths"])
        self.assertEqual(f["tops"][0], f["tops"][1])
        self.assertGreater(f["tops"][2], f["tops"][0])
        # The better value of each metric with a direction, as the registry says.
        by_key = {x["key"]: x for x in expected}
        checked = 0
        for metric, marks in f["marked"].items():
            values = [by_key[k]["metrics"].get(metric) for k in f["keys"]]
            known = [v for v in values if v is not None]
            spec = self.specs.get(metric, {"better": 0, "tie_absolute": 0, "tie_relative": 0})
            best = (max(known) if spec["better"] > 0 else min(known)) if known else None
            tied = [v is not None and stats.tied(spec, v, best) for v in values]  # equal as the report's statistics say
            if spec["better"] == 0 or len(known) < 2 or all(t for t, v in zip(tied, values) if v is not None):
                self.assertEqual(marks, [False] * len(values), metric)
                continue
            self.assertEqual(marks, tied, metric)
            checked += 1
        self.assertGreater(checked, 5)
        # In step: while playing, paused and after a seek, every playhead at the clock's time.
        for state in (r["playing"], r["paused"], r["seeked"]):
            self.assertLessEqual(state["apart"], FRAME, state)
        self.assertTrue(r["playing"]["playing"])
        self.assertFalse(r["paused"]["playing"])
        s = r["seeked"]
        self.assertAlmostEqual(s["t"], f["longest"] * 0.4, delta=1e-9)
        for head, end in zip(s["heads"], s["ends"]):
            self.assertLessEqual(abs(head - min(s["t"], end)), FRAME)
        self.assertIn("(40 % of the longest run)", s["clock"])
        # The copied address reopens the compare at that time.
        with opened(r["href"], width=1280, height=1000) as fresh:
            again = fresh.evaluate("(async () => {" + HELPERS + """
                await ready();
                const viewer = $('viewer');
                await until(() => viewer.coverbenchCompare, 'the compare view');
                const all = viewer.coverbenchCompare;
                return {keys: [...viewer.querySelectorAll('.compare figure')].map(f => f.dataset.playback.split('/').at(-2)),
                        t: all.time(), times: all.times(), ends: all.players.map(p => p.duration())};
            })()""")
            fresh.screenshot(os.path.join(SHOTS, "compare-reopened.png"))
            self.assertEqual(errors(fresh.events), [])
        self.assertEqual(again["keys"], f["keys"])
        self.assertLessEqual(abs(again["t"] - s["t"]), FRAME)
        for t, end in zip(again["times"], again["ends"]):
            self.assertLessEqual(abs(t - min(again["t"], end)), FRAME)

    def test_a_run_alone_on_its_wall_says_so(self):
        with opened(f"{self.base}/?exp={self.lone['db']}/{self.lone['id']}", width=1280, height=1000) as page:
            r = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                rows()[0].click();
                await until(() => $('same-wall'), 'the run');
                $('same-wall').click();
                const viewer = $('viewer');
                await until(() => viewer.coverbenchCompare, 'the compare view');
                const none = viewer.querySelector('.compare-none');
                return {text: none && none.textContent, visible: !!none && none.getClientRects().length > 0, role: none && none.getAttribute('role'),
                        title: viewer.querySelector('.compare-title').textContent, figures: viewer.querySelectorAll('.compare figure').length,
                        cmp: new URLSearchParams(location.search).get('cmp'), key: rows()[0].dataset.key};
            })()""")
            page.screenshot(os.path.join(SHOTS, "compare-alone.png"))
            self.assertEqual(errors(page.events), [])
        self.assertTrue(r["visible"])
        self.assertTrue(r["text"].startswith("No other planner ran on this wall in this experiment"), r["text"])
        self.assertEqual(r["role"], "status")
        self.assertTrue(r["title"].startswith("1 run on "), r["title"])
        self.assertEqual((r["figures"], r["cmp"]), (1, r["key"]))
        # A wall with other planners' runs says nothing of the kind.
        with opened(f"{self.base}/?planner=zigzag", width=1280, height=1000) as page:
            others = page.evaluate("(async () => {" + HELPERS + """
                await ready();
                rows()[0].click();
                await until(() => $('same-wall'), 'the run');
                $('same-wall').click();
                await until(() => $('viewer').coverbenchCompare, 'the compare view');
                return {none: !!$('viewer').querySelector('.compare-none'), figures: $('viewer').querySelectorAll('.compare figure').length};
            })()""")
        self.assertEqual(others, {"none": False, "figures": 3})

    def test_speed_and_zoom_are_in_the_address(self):
        """A run at 20x zoomed 4x, then its wall's runs compared at 0.5x with the second picture
        zoomed 2x (a button) and the third 2x (three wheel steps): each copied address reopens
        that speed and zoom; back and forward step through them."""
        with opened(self.base + "/?planner=spiral", width=1280, height=1000) as page:
            r = page.evaluate("(async () => {" + HELPERS + VIEWER + """
                await ready();
                rows()[0].click();
                await until(() => figs().length === 1 && figs()[0].coverbenchZoom, 'the run');
                await loaded();
                const fig = figs()[0];
                fig.querySelector('.player-start').click();
                await until(() => fig.coverbenchPlayer, 'the player');
                const p = fig.coverbenchPlayer;
                p.pause();
                p.seek(p.duration() * 0.3);
                await until(() => query().get('t') === p.time().toFixed(3), 'the time in the address');
                const entries = history.length;
                const speed = fig.querySelector('.player-bar select');
                speed.value = '20';
                speed.dispatchEvent(new Event('change'));
                await until(() => query().get('speed') === '20', 'the speed in the address');
                fig.querySelector('.zoom-in').click();
                await until(() => query().get('zoom') === '2', 'zoom 2 in the address');
                fig.querySelector('.zoom-in').click();
                await until(() => query().get('zoom') === '4', 'zoom 4 in the address');
                const run = {...shown(), speed: p.speed(), select: speed.value, t: p.time(), href: location.href, entries: history.length - entries};
                history.back();
                await until(() => fig.coverbenchZoom.zoom() === 2 && query().get('zoom') === '2', 'back to zoom 2');
                const back1 = {...shown(), speed: p.speed()};
                history.back();
                await until(() => fig.coverbenchZoom.zoom() === 1 && !query().has('zoom'), 'back to fit');
                const back2 = {...shown(), speed: p.speed()};
                history.back();
                await until(() => p.speed() === 5 && !query().has('speed'), 'back to the first speed');
                const back3 = {...shown(), speed: p.speed(), select: speed.value};
                history.go(3);
                await until(() => fig.coverbenchZoom.zoom() === 4 && p.speed() === 20, 'forward to 20x and zoom 4');
                const forward = {...shown(), speed: p.speed(), select: speed.value};
                // The wall's runs compared: the speed stays, the pictures start at fit.
                $('same-wall').click();
                const viewer = $('viewer');
                await until(() => viewer.coverbenchCompare && figs().length === 3, 'the compare view');
                await loaded();
                const all = viewer.coverbenchCompare;
                const opened = {...shown(), speed: all.speed()};
                const cmpSpeed = viewer.querySelector('.compare-bar select');
                cmpSpeed.value = '0.5';
                cmpSpeed.dispatchEvent(new Event('change'));
                await until(() => query().get('speed') === '0.5', 'the compare speed in the address');
                figs()[1].querySelector('.zoom-in').click();
                await until(() => query().get('zoom') === '1,2,1', 'the second picture zoomed');
                const before = history.length;
                const view = figs()[2].querySelector('.zoom-view'), box = view.getBoundingClientRect();
                for (let k = 0; k < 3; ++k)
                    view.dispatchEvent(new WheelEvent('wheel', {deltaY: -100, ctrlKey: true, bubbles: true, cancelable: true,
                                                                clientX: box.left + box.width / 2, clientY: box.top + box.height / 2}));
                await until(() => query().get('zoom') === '1,2,2', 'the third picture zoomed by the wheel');
                const compared = {...shown(), speed: all.speed(), select: cmpSpeed.value, href: location.href, wheelEntries: history.length - before};
                history.back();
                await until(() => query().get('zoom') === '1,2,1' && figs()[2].coverbenchZoom.zoom() === 1, 'back before the wheel');
                const cmpBack1 = {...shown(), speed: all.speed()};
                history.back();
                await until(() => !query().has('zoom') && figs()[1].coverbenchZoom.zoom() === 1, 'back to fit');
                history.back();
                await until(() => all.speed() === 20, 'back to 20x');
                const cmpBack3 = {...shown(), speed: all.speed(), select: cmpSpeed.value};
                history.go(3);
                await until(() => all.speed() === 0.5 && query().get('zoom') === '1,2,2', 'forward again');
                await until(() => figs()[2].coverbenchZoom.zoom() > 1.99, 'the wheel zoom again');
                return {run, back1, back2, back3, forward, opened, compared, cmpBack1, cmpBack3, cmpForward: {...shown(), speed: all.speed()}};
            })()""")
            page.screenshot(os.path.join(SHOTS, "compare-zoom-speed.png"))
            self.assertEqual(errors(page.events), [])
        run = r["run"]
        self.assertEqual(run["address"], {"zoom": "4", "speed": "20"})
        self.assertEqual((run["zoom"], run["speed"], run["select"], run["entries"]), ([4], 20, "20", 3))
        self.assertAlmostEqual(run["laid"][0], 4, delta=0.01)
        self.assertEqual((r["back1"]["zoom"], r["back1"]["speed"], r["back1"]["address"]), ([2], 20, {"zoom": "2", "speed": "20"}))
        self.assertAlmostEqual(r["back1"]["laid"][0], 2, delta=0.01)
        self.assertEqual((r["back2"]["zoom"], r["back2"]["speed"], r["back2"]["address"]), ([1], 20, {"zoom": None, "speed": "20"}))
        self.assertEqual((r["back3"]["zoom"], r["back3"]["speed"], r["back3"]["select"]), ([1], 5, "5"))
        self.assertEqual((r["forward"]["zoom"], r["forward"]["speed"], r["forward"]["select"], r["forward"]["canvas"]),
                         ([4], 20, "20", run["canvas"]))
        self.assertEqual((r["opened"]["zoom"], r["opened"]["speed"], r["opened"]["address"]), ([1, 1, 1], 20, {"zoom": None, "speed": "20"}))
        c = r["compared"]
        self.assertEqual((c["address"], c["speed"], c["select"], c["wheelEntries"]), ({"zoom": "1,2,2", "speed": "0.5"}, 0.5, "0.5", 1))
        self.assertEqual(c["zoom"][:2], [1, 2])
        self.assertAlmostEqual(c["zoom"][2], 2, delta=1e-9)
        self.assertEqual((r["cmpBack1"]["zoom"], r["cmpBack1"]["speed"]), ([1, 2, 1], 0.5))
        self.assertEqual((r["cmpBack3"]["zoom"], r["cmpBack3"]["speed"], r["cmpBack3"]["select"]), ([1, 1, 1], 20, "20"))
        self.assertEqual(r["cmpForward"]["speed"], 0.5)
        self.assertAlmostEqual(r["cmpForward"]["zoom"][2], 2, delta=1e-9)
        # Each copied address, opened afresh: the same run, time, speed and zoom; the same compare.
        with opened(run["href"], width=1280, height=1000) as fresh:
            again = fresh.evaluate("(async () => {" + HELPERS + VIEWER + """
                await ready();
                await until(() => figs().length === 1 && figs()[0].dataset.restored && figs()[0].coverbenchZoom.zoom() === 4, 'the run, held and zoomed');
                const p = figs()[0].coverbenchPlayer;
                return {...shown(), speed: p.speed(), select: figs()[0].querySelector('.player-bar select').value, t: p.time()};
            })()""")
            fresh.screenshot(os.path.join(SHOTS, "run-zoom-speed-reopened.png"))
            self.assertEqual(errors(fresh.events), [])
        self.assertEqual((again["zoom"], again["speed"], again["select"], again["canvas"]), ([4], 20, "20", run["canvas"]))
        self.assertAlmostEqual(again["laid"][0], 4, delta=0.01)
        self.assertLessEqual(abs(again["t"] - run["t"]), FRAME)
        with opened(c["href"], width=1280, height=1000) as fresh:
            again = fresh.evaluate("(async () => {" + HELPERS + VIEWER + """
                await ready();
                await until(() => $('viewer').coverbenchCompare && figs().length === 3 && figs()[1].coverbenchZoom.zoom() === 2
                                  && figs()[2].coverbenchZoom.zoom() === 2, 'the compare, zoomed');
                const all = $('viewer').coverbenchCompare;
                return {...shown(), speed: all.speed(), select: $('viewer').querySelector('.compare-bar select').value};
            })()""")
            fresh.screenshot(os.path.join(SHOTS, "compare-zoom-speed-reopened.png"))
            self.assertEqual(errors(fresh.events), [])
        self.assertEqual((again["zoom"], again["speed"], again["select"], again["address"]), ([1, 2, 2], 0.5, "0.5", c["address"]))
        for got, want in zip(again["laid"], c["laid"]):
            self.assertAlmostEqual(got, want, delta=0.01)

    def test_the_keyboard_opens_plays_scrubs_and_sorts(self):
        with opened(self.base + "/?planner=spiral", width=1280, height=1000) as page:
            page.evaluate("(async () => {" + HELPERS + "await ready(); })()")
            focus = "(() => { const e = document.activeElement; return e.id || e.className || e.tagName; })()"
            # Tab first reaches the skip link; Enter on it takes the focus to the player's button.
            press(page, "Tab")
            first_tab = page.evaluate(focus)
            # Enter on a focused row opens its run; the focus stays on the row.
            key = page.evaluate("(() => { const r = document.querySelector('#runs tbody tr:nth-child(2)'); r.focus(); return r.dataset.key; })()")
            press(page, "Enter")
            opened_run = page.evaluate("(async () => {" + HELPERS + """
                await until(() => document.querySelector('#viewer figure[data-playback] .player-start'), 'the run');
                return {run: new URLSearchParams(location.search).get('run'), focus: document.activeElement.dataset.key || document.activeElement.tagName};
            })()""")
            # Space plays (starting the player), Space again pauses: the focus never leaves the row.
            # Every time the player shows is watched: none may be before 0 s.
            page.evaluate("""(() => { window.negative = [];
                new MutationObserver(ms => { for (const m of ms) { const t = m.target.dataset.playhead;
                    if (t !== undefined && Number(t) < 0) window.negative.push(t); } })
                  .observe(document.getElementById('viewer'), {subtree: true, attributes: true, attributeFilter: ['data-playhead']}); })()""")
            press(page, " ")
            played = page.evaluate("(async () => {" + HELPERS + """
                const fig = document.querySelector('#viewer figure[data-playback]');
                await until(() => fig.coverbenchPlayer && fig.coverbenchPlayer.playing() && fig.coverbenchPlayer.time() > 0, 'playing');
                return document.activeElement.dataset.key || document.activeElement.tagName;
            })()""")
            press(page, " ")
            paused = page.evaluate("""(() => { const p = document.querySelector('#viewer figure[data-playback]').coverbenchPlayer;
                return {playing: p.playing(), focus: document.activeElement.dataset.key || document.activeElement.tagName}; })()""")
            negative = page.evaluate("window.negative")
            page.evaluate("document.querySelector('#viewer figure[data-playback]').coverbenchPlayer.seek(20)")
            steps = []
            for arrow, shift in (("ArrowRight", False), ("ArrowRight", True), ("ArrowLeft", False), ("ArrowLeft", True)):
                press(page, arrow, shift)
                steps.append(page.evaluate("document.querySelector('#viewer figure[data-playback]').coverbenchPlayer.time()"))
            press(page, " ")
            replay = page.evaluate("(async () => {" + HELPERS + """
                const p = document.querySelector('#viewer figure[data-playback]').coverbenchPlayer;
                await until(() => p.playing(), 'playing again');
                p.pause();
                // The address follows the player's time within a quarter second (the page polls it).
                await until(() => new URLSearchParams(location.search).get('t') === p.time().toFixed(3), 'the time in the address');
                return true;
            })()""")
            # The run's address opened afresh: the first Tab reaches the skip link, and Enter on it
            # takes the focus to the player's button.
            href = page.evaluate("location.href")
            page.events = [e for e in page.events if e.get("method") != "Page.loadEventFired"]
            page.call("Page.navigate", url=href)
            page.wait_for("Page.loadEventFired")
            page.evaluate("(async () => {" + HELPERS + "await ready(); const fig = () => document.querySelector('#viewer figure[data-playback]'); "
                          "await until(() => fig() && fig().dataset.restored, 'the player held at the address time'); })()")
            tabs = 0
            while tabs < 5 and page.evaluate(focus) != "skip-player":
                press(page, "Tab")
                tabs += 1
            press(page, "Enter")
            on_play = page.evaluate("(() => { const e = document.activeElement; return {text: e.textContent, bar: !!e.closest('.player-bar')}; })()")
            press(page, "Enter")
            after_enter = page.evaluate("(async () => {" + HELPERS + """
                const p = document.querySelector('#viewer figure[data-playback]').coverbenchPlayer;
                await until(() => p.playing(), 'playing from the play button');
                p.pause();
                return {bar: !!document.activeElement.closest('.player-bar'), tag: document.activeElement.tagName};
            })()""")
            # Enter on a heading's button sorts by that column.
            page.evaluate("document.querySelector('#runs thead th[data-column=\"dataset\"] button').focus()")
            press(page, "Enter")
            sorted_by = page.evaluate("(async () => {" + HELPERS + """
                await settled(q => q.get('sort') === 'dataset', 'the sort');
                return {sort: new URLSearchParams(location.search).get('sort'),
                        aria: document.querySelector('#runs thead th[data-column="dataset"]').getAttribute('aria-sort')};
            })()""")
            page.screenshot(os.path.join(SHOTS, "keys.png"))
            self.assertEqual(errors(page.events), [])
        self.assertEqual(first_tab, "skip-player")
        self.assertEqual(opened_run, {"run": key, "focus": key})
        self.assertEqual(played, key)
        self.assertEqual(paused, {"playing": False, "focus": key})
        self.assertEqual(negative, [])  # the player's clock never reads before 0 s (it read -0.3 s)
        self.assertEqual([round(t, 9) for t in steps], [21, 31, 30, 20])
        self.assertTrue(replay)
        self.assertLessEqual(tabs, 1)
        self.assertTrue(on_play["bar"], on_play)  # the address holds a time: the player is made, held there
        self.assertEqual(after_enter, {"bar": True, "tag": "BUTTON"})
        self.assertEqual(sorted_by, {"sort": "dataset", "aria": "ascending"})


if __name__ == "__main__":
    unittest.main()
