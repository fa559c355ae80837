"""Serves a planner written in Python over CoverBench's planner protocol, version 1 or 2
(docs/external_planners.md): one problem per line of JSON on stdin, one plan per line on stdout.
Each answer repeats its request's version (the manifest's ``coverbench_planner``).

    python3 -m coverbench.serve my_module:MyPlanner

or, at the end of a planner's own file, ``serve(MyPlanner())``. The planner is any object with a
method ``plan(problem)`` that returns a dict: ``status`` ("ok", "partial", "no_reachable_area",
"invalid_input", "timeout" or "error"), ``reason``, and for ok and partial ``waypoints`` ([x, y]
pairs), ``tool_on`` (one bool per segment), optionally ``bulge`` and ``stats`` (numbers). The
process is started once and serves many problems; what the planner prints goes to stderr, so it
cannot break the protocol; an exception becomes status error with its message, and so does a plan
JSON cannot hold (a NaN or an infinite coordinate, an object that is not a number).
"""
from __future__ import annotations

import importlib
import json
import math
import os
import sys
import traceback
from typing import IO, Any, Dict, List, Optional, Protocol

#: The protocol versions served; an answer repeats its request's.
PROTOCOLS = (1, 2)
#: The newest of them.
PROTOCOL = 2


class Planner(Protocol):
    """What ``serve`` needs of a planner: ``plan(problem)`` returning the plan as a dict."""

    def plan(self, problem: Problem) -> Dict[str, Any]:
        """The plan for `problem`: status, reason, and for ok and partial waypoints and tool_on."""


class Problem:
    """One problem: the wall (as a wall file's JSON), the tool, the vehicle, the parameters.

    From protocol 2 the tool has a ``tool_shape`` ("disk", "line" or "rectangle"), a
    ``tool_depth`` (a rectangle's, m; 0 for the others) and a ``profile``: None, or the flux
    profile's dict (``kind``; ``sigma`` or ``beta`` for their kinds; ``rate``, ``depth``; ``target`` when set;
    ``flow`` "speed" when the gun's flow follows the tool's speed). In
    protocol 1 they are "disk", 0 and None."""

    def __init__(self, data: Dict[str, Any]) -> None:
        self.data: Dict[str, Any] = data
        self.wall: Dict[str, Any] = data["wall"]
        self.tool_width = float(data["tool"]["width"])
        self.clearance = float(data["tool"]["clearance"])
        self.tool_shape: str = data["tool"].get("shape", "disk")
        self.tool_depth = float(data["tool"].get("depth", 0.0))
        self.profile: Optional[Dict[str, Any]] = data["tool"].get("profile")
        self.vehicle: Dict[str, Any] = data["vehicle"]
        self.params: Dict[str, Any] = data["params"]
        self.seed: int = data["seed"]
        self.time_limit_s: float = data.get("time_limit_s", math.inf)

    @property
    def radius(self) -> float:
        """Half the tool width (m)."""
        return self.tool_width / 2.0


def _answer(protocol: int, request_id: Any, plan: Any) -> Dict[str, Any]:
    if not isinstance(plan, dict):
        return {"protocol": protocol, "id": request_id, "status": "error",
                "reason": f"plan() returned {type(plan).__name__}, not a dict"}
    out: Dict[str, Any] = {"protocol": protocol, "id": request_id}
    out.update(plan)
    return out


def serve(planner: Planner, stdin: Optional[IO[str]] = None, stdout: Optional[IO[str]] = None) -> None:
    """Answers every problem on stdin until it closes: one request per line, one answer per line
    (docs/external_planners.md). What the planner prints goes to stderr."""
    stdin = stdin or sys.stdin
    out = stdout or sys.stdout
    sys.stdout = sys.stderr  # a print() in the planner must not break the protocol
    for line in stdin:
        if not line.strip():
            continue
        request: Any
        reason = ""
        protocol = PROTOCOL
        try:
            request = json.loads(line)
            request_id = request.get("id") if isinstance(request, dict) else None
        except ValueError as e:
            request, request_id = None, None
            reason = f"the request is not JSON: {e}"
        if not isinstance(request, dict):
            reason = reason if request is None else "the request is not a JSON object"
            answer = {"protocol": protocol, "id": request_id, "status": "error", "reason": reason}
        elif request.get("protocol") not in PROTOCOLS or isinstance(request.get("protocol"), bool):
            answer = {"protocol": protocol, "id": request_id, "status": "error",
                      "reason": f"this planner speaks protocol 1 or 2, not {request.get('protocol')}"}
        else:
            protocol = request["protocol"]
            try:
                answer = _answer(protocol, request_id, planner.plan(Problem(request["problem"])))
            except Exception as e:  # noqa: BLE001 - the run says what went wrong
                traceback.print_exc(file=sys.stderr)
                answer = {"protocol": protocol, "id": request_id, "status": "error",
                          "reason": f"{type(e).__name__}: {e}"}
        out.write(_line(protocol, request_id, answer) + "\n")
        out.flush()


def _line(protocol: int, request_id: Any, answer: Dict[str, Any]) -> str:
    """The answer as one line of JSON; an answer JSON cannot hold (NaN, infinity, an object that is
    not a number, string, list or dict) is status error saying why, never a dead planner."""
    try:
        return json.dumps(answer, allow_nan=False, separators=(",", ":"))
    except (ValueError, TypeError, RecursionError) as e:
        traceback.print_exc(file=sys.stderr)
        return json.dumps({"protocol": protocol, "id": request_id, "status": "error",
                           "reason": f"the plan cannot be written as JSON: {type(e).__name__}: {e}"},
                          separators=(",", ":"))


def main(argv: Optional[List[str]] = None) -> int:
    """``python3 -m coverbench.serve MODULE:CLASS``: serves an instance of CLASS."""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1 or ":" not in argv[0]:
        print("usage: python3 -m coverbench.serve MODULE:CLASS", file=sys.stderr)
        return 2
    module_name, class_name = argv[0].split(":", 1)
    sys.path.insert(0, os.getcwd())
    planner = getattr(importlib.import_module(module_name), class_name)()
    serve(planner)
    return 0


if __name__ == "__main__":
    sys.exit(main())
