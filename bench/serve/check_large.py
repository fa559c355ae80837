"""POST /api/check of a wall whose obstacle is one polygon of N vertices (default 10^6), timed
from the request's first byte to the answer's last, against a server started here.

    python3 bench/serve/check_large.py build/coverbench [N]

Prints the body's size, the answer's status and verdict, the seconds it took and the server's
peak resident memory. Time it as a
whole with farm-bench for a median over runs (docs/explorer.md has the figure)."""
import http.client
import json
import math
import re
import subprocess
import sys
import time

binary = sys.argv[1] if len(sys.argv) > 1 else "build/coverbench"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 10**6
points = [[round(500 + 400 * math.cos(2 * math.pi * i / n), 4), round(500 + 400 * math.sin(2 * math.pi * i / n), 4)] for i in range(n)]
wall = json.dumps({"name": "polygon-%d" % n, "width": 1000, "height": 1000, "obstacles": [{"type": "polygon", "points": points}]})
body = json.dumps({"wall": wall, "tool_width": 0.5}).encode()
server = subprocess.Popen([binary, "serve", "--port", "0"], stdout=subprocess.PIPE, text=True)
try:
    port = int(re.search(r":(\d+)/", server.stdout.readline()).group(1))
    started = time.monotonic()
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
    c.request("POST", "/api/check", body, {"Content-Type": "application/json"})
    r = c.getresponse()
    answer = json.loads(r.read())
    seconds = time.monotonic() - started
    with open("/proc/%d/status" % server.pid) as f:
        peak = next(line.split()[1] for line in f if line.startswith("VmHWM:"))
    print("%d vertices, %d bytes: HTTP %d, ok %s%s, %.2f s, server's peak memory %d MB" % (
        n, len(body), r.status, answer.get("ok"), "" if answer.get("ok") else " (" + str(answer.get("error")) + ")", seconds,
        int(peak) // 1024))
    sys.exit(0 if r.status == 200 and answer.get("ok") else 1)
finally:
    server.kill()
    server.wait()
