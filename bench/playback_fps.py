"""Frame timing of the report's path player on a long path, in Debian's headless Chromium.

Plans one wall with one planner into an experiment of its own (a field with a small tool gives
100,000 waypoints and more), writes its report, opens it from disk, starts the gallery's player
and plays the path at each speed for a few seconds (from a third of the way, half a second after
the jump there), recording every animation frame's time stamp and how long the player took to
draw it. Prints the waypoints, the frames per second, the 95th
percentile frame interval and the draw time per frame.

usage: python3 bench/playback_fps.py --coverbench build/coverbench [--wall FILE] [--planner P]
       [--tool-width S] [--seconds N] [--work DIR]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "browser"))
from check_page import errors, opened  # noqa: E402

MEASURE = """(async () => {
    const fig = document.querySelector('figure[data-playback]');
    fig.scrollIntoView();
    fig.querySelector('.player-start').click();
    const sleep = ms => new Promise(r => setTimeout(r, ms));
    for (let k = 0; k < 2000 && !fig.coverbenchPlayer; ++k) await sleep(25);
    const p = fig.coverbenchPlayer;
    const out = {waypoints: p.waypoints(), duration: p.duration(), runs: []};
    for (const speed of [0.25, 1, 20]) {
        p.pause(); p.setSpeed(speed); p.seek(p.duration() / 3); p.play();
        await sleep(500);  // past the seek, which paints a third of the path in one frame
        const stamps = [];
        const f0 = p.frames(), d0 = p.drawMs();
        await new Promise(done => {
            const t0 = performance.now();
            const frame = now => { stamps.push(now); if (now - t0 < SECONDS * 1000) requestAnimationFrame(frame); else done(); };
            requestAnimationFrame(frame);
        });
        p.pause();
        out.runs.push({speed, stamps, frames: p.frames() - f0, draw_ms: p.drawMs() - d0});
    }
    const c0 = performance.now();
    p.seek(p.duration());  // every segment painted at once: the worst single frame
    out.seek_end_ms = performance.now() - c0;
    return out;
})()"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--coverbench", required=True)
    ap.add_argument("--wall", default=os.path.join(HERE, "walls", "field_100m_15_buildings.json"))
    ap.add_argument("--planner", default="spiral")
    ap.add_argument("--tool-width", type=float, default=0.25)
    ap.add_argument("--seconds", type=float, default=3.0)
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="coverbench-playback-")
    os.makedirs(os.path.join(work, "walls"), exist_ok=True)
    shutil.copy(args.wall, os.path.join(work, "walls", os.path.basename(args.wall)))
    with open(os.path.join(work, "c.yaml"), "w") as f:
        f.write(f"name: playback\noutput: out\ndatasets:\n  - folder: walls\nplanners: [{args.planner}]\n"
                f"tool:\n  width: {args.tool_width}\n  clearance: 0\nlimits:\n  time_s: 600\n")
    subprocess.run([args.coverbench, "run", os.path.join(work, "c.yaml")], check=True, stdout=subprocess.DEVNULL)
    page_file = os.path.join(work, "out", "report", "index.html")
    with opened(page_file) as page:
        r = page.evaluate(MEASURE.replace("SECONDS", str(args.seconds)))
        problems = errors(page.events)
    print(f"{args.planner} on {os.path.basename(args.wall)}, tool {args.tool_width} m: {r['waypoints']} waypoints, "
          f"{r['duration']:.0f} s under the time model")
    for run in r["runs"]:
        gaps = sorted(b - a for a, b in zip(run["stamps"], run["stamps"][1:]))
        fps = (len(run["stamps"]) - 1) / ((run["stamps"][-1] - run["stamps"][0]) / 1000)
        p95 = gaps[int(0.95 * (len(gaps) - 1))]
        print(f"  {run['speed']:>5}x: {fps:.1f} frames/s over {args.seconds:g} s, 95th percentile interval {p95:.1f} ms, "
              f"draw {run['draw_ms'] / max(run['frames'], 1):.2f} ms per frame ({run['frames']} frames)")
    print(f"  a jump to the end (every segment painted in one frame): {r['seek_end_ms']:.0f} ms")
    for p in problems:
        print("console:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
