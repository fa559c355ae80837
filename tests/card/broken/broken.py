"""Five ways a planner can be broken, one per manifest beside this file (tests/card/test_card.py
runs `coverbench conformance` on each): the argument names the way.

- missing-module: imports a module no interpreter has (the manifest cannot-start needs no script);
- segfault: dies of SIGSEGV on its first problem;
- loops: never answers;
- through-obstacle: answers a straight path, across the wall, through the middle of its first
  obstacle (a rectangle);
- bad-reason: answers `error` with a reason of bytes that are not UTF-8 (it ended the JSON card
  with an internal error), then one with a NUL (it cut the reason);
- forks-and-exits: starts a child that keeps stdout open and sleeps, and exits with code 4 (each
  row read "timeout" at the limit, not the crash it is);
- endless-stderr: writes to stderr without end and never answers (nothing may wait on whoever
  reads the card's stderr: the planner is stopped at its time limit).
"""
import json
import os
import signal
import sys
import time

mode = sys.argv[1]
if mode == "forks-and-exits":
    if os.fork() == 0:
        time.sleep(600)  # holds stdout open; stopped with the planner's processes
        os._exit(0)
    sys.exit(4)
if mode == "missing-module":
    import coverbench_card_no_such_module  # noqa: F401  (ModuleNotFoundError names it on stderr)

for line in sys.stdin:
    request = json.loads(line)
    if mode == "bad-reason":
        # The first answer is not UTF-8 (0xFF 0xFE in its reason); the second is, with a NUL.
        reason = b"bad \xff\xfe bytes" if request["id"] == 1 else b"before \\u0000 after"
        sys.stdout.buffer.write(b'{"protocol": 1, "id": %d, "status": "error", "reason": "%s"}\n' % (request["id"], reason))
        sys.stdout.flush()
        continue
    if mode == "endless-stderr":
        while True:
            sys.stderr.write("x" * 65536 + "\n")
    if mode == "segfault":
        os.kill(os.getpid(), signal.SIGSEGV)
    if mode == "loops":
        while True:
            pass
    problem = request["problem"]
    wall = problem["wall"]
    ys = [p[1] for p in wall["obstacles"][0]["points"]]  # a rect obstacle comes as its four corners
    xs = [p[0] for p in wall["boundary"]]
    r = problem["tool"]["width"] / 2
    y = (min(ys) + max(ys)) / 2  # the obstacle's middle row: a path along it crosses the obstacle
    answer = {"protocol": 1, "id": request["id"], "status": "ok",
              "waypoints": [[min(xs) + r + 0.01, y], [max(xs) - r - 0.01, y]], "tool_on": [True]}
    sys.stdout.write(json.dumps(answer) + "\n")
    sys.stdout.flush()
