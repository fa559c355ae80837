"""The protocol's overhead, measured (bench/external_bench.cpp): answers every problem with the
same 1000-waypoint path, its JSON made once, so a run costs the protocol and nothing else."""
import json
import sys

N = 1000
points = [[0.1 + 0.001 * i, 0.1 + 0.0005 * (i % 2)] for i in range(N)]
body = json.dumps({"status": "ok", "waypoints": points, "tool_on": [True] * (N - 1)}, separators=(",", ":"))[1:]
for line in sys.stdin:
    request_id = json.loads(line)["id"]
    sys.stdout.write('{"protocol":1,"id":%d,%s\n' % (request_id, body))
    sys.stdout.flush()
