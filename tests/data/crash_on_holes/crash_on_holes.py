# A planner that crashes on walls with holes (tests/runner/external_planner_test.cpp, issue 61): on a wall
# without obstacles it answers a short valid path; on one with obstacles it writes 5000 bytes of
# chatter to stderr, then bytes that are not UTF-8, then dies of an uncaught exception (exit
# code 1, Python's traceback on stderr). The run's record keeps the end of that stderr.
import json
import sys

for line in sys.stdin:
    req = json.loads(line)
    wall = req["problem"]["wall"]
    sys.stderr.write("crash_on_holes: planning %s\n" % wall["name"])
    sys.stderr.flush()
    if wall.get("obstacles"):
        sys.stderr.write("chatter " * 625)  # 5000 bytes: more than the 4 KiB kept
        sys.stderr.write("\n")
        sys.stderr.flush()
        sys.stderr.buffer.write(b"not UTF-8: \xff\xfe <- two bytes\n")
        sys.stderr.buffer.flush()
        raise RuntimeError("holes are not supported: %d obstacles on %s" % (len(wall["obstacles"]), wall["name"]))
    p = req["problem"]
    r = p["tool"]["width"] / 2 + p["tool"]["clearance"] + 0.01
    print(json.dumps({"protocol": 1, "id": req["id"], "status": "ok",
                      "waypoints": [[r, r], [r + 0.05, r]], "tool_on": [True]}), flush=True)
