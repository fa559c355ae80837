"""Opens a page in Debian's headless Chromium over the DevTools protocol, the way a user would:
waits for it to load, fails on any console error or uncaught exception, checks that every image
loaded and that the expected parts are there, and saves screenshots.

usage: check_page.py PAGE.html SCREENSHOT_PREFIX [--expect-text TEXT]... [--min-images N]
       [--min-tables N] [--section ID]...
"""
import argparse
import base64
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.request

import websocket  # Debian: python3-websocket

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--remote-debugging-port=0", "--window-size=1400,1400"]


class Page:
    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=60, suppress_origin=True)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        my_id = self.next_id
        self.ws.send(json.dumps({"id": my_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == my_id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            self.events.append(msg)

    def wait_for(self, method, timeout=120):
        end = time.time() + timeout
        for e in self.events:
            if e.get("method") == method:
                return e
        while time.time() < end:
            msg = json.loads(self.ws.recv())
            self.events.append(msg)
            if msg.get("method") == method:
                return msg
        raise TimeoutError(method)

    def evaluate(self, expression):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"evaluate: {r['exceptionDetails']}")
        return r["result"].get("value")

    def screenshot(self, path):
        data = self.call("Page.captureScreenshot", format="png")["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))


def errors(events):
    out = []
    for e in events:
        m, p = e.get("method"), e.get("params", {})
        if m == "Runtime.exceptionThrown":
            out.append("exception: " + json.dumps(p.get("exceptionDetails", {}))[:300])
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console." + p["type"] + ": " + json.dumps(p.get("args", []))[:300])
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            out.append("log: " + p["entry"].get("text", "") + " " + p["entry"].get("url", ""))
        elif m == "Page.javascriptDialogOpening":
            out.append("dialog: " + p.get("message", ""))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("page")
    ap.add_argument("shots")
    ap.add_argument("--expect-text", action="append", default=[])
    ap.add_argument("--min-images", type=int, default=1)
    ap.add_argument("--min-tables", type=int, default=1)
    ap.add_argument("--section", action="append", default=[])
    args = ap.parse_args()
    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    profile = tempfile.mkdtemp(prefix="coverbench-chromium-")
    proc = subprocess.Popen([chromium, *FLAGS, f"--user-data-dir={profile}", "about:blank"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        port = None
        end = time.time() + 60
        while time.time() < end and port is None:
            line = proc.stderr.readline()
            m = re.search(r"DevTools listening on ws://[^:]+:(\d+)/", line)
            if m:
                port = int(m.group(1))
        if port is None:
            print("FAIL: chromium did not start its DevTools endpoint", file=sys.stderr)
            return 1
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30))
        page = Page(next(t for t in targets if t["type"] == "page")["webSocketDebuggerUrl"])
        for domain in ("Runtime", "Log", "Page"):
            page.call(domain + ".enable")
        page.call("Emulation.setDeviceMetricsOverride", width=1400, height=1400, deviceScaleFactor=1, mobile=False)
        url = "file://" + os.path.abspath(args.page)
        page.call("Page.navigate", url=url)
        page.wait_for("Page.loadEventFired")
        report = page.evaluate("""(() => {
            const imgs = [...document.images];
            return {images: imgs.length,
                    broken: imgs.filter(i => !i.complete || i.naturalWidth === 0).map(i => i.getAttribute('src')),
                    tables: document.querySelectorAll('table').length,
                    scripts: document.querySelectorAll('script').length,
                    sections: [...document.querySelectorAll('section')].map(s => s.id),
                    text: document.body.innerText};
        })()""")
        problems = errors(page.events)
        if report["broken"]:
            problems.append(f"{len(report['broken'])} images did not load: {report['broken'][:5]}")
        if report["images"] < args.min_images:
            problems.append(f"{report['images']} images, expected at least {args.min_images}")
        if report["tables"] < args.min_tables:
            problems.append(f"{report['tables']} tables, expected at least {args.min_tables}")
        if report["scripts"]:
            problems.append(f"{report['scripts']} script elements: the page should have none")
        for s in args.section:
            if s not in report["sections"]:
                problems.append(f"section #{s} missing (have {report['sections']})")
        for t in args.expect_text:
            if t not in report["text"]:
                problems.append(f"text not shown as text: {t!r}")
        os.makedirs(os.path.dirname(os.path.abspath(args.shots)), exist_ok=True)
        page.screenshot(args.shots + "-top.png")
        for s in args.section:
            page.evaluate(f"document.getElementById({json.dumps(s)}).scrollIntoView()")
            time.sleep(0.2)
            page.screenshot(f"{args.shots}-{s}.png")
        if problems:
            for p in problems:
                print("FAIL:", p, file=sys.stderr)
            return 1
        print(f"ok: {report['images']} images, {report['tables']} tables, sections {report['sections']}; "
              f"screenshots {args.shots}-*.png")
        return 0
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
