"""CoverBench from Python.

- Walls: ``load_wall(path)`` and ``check_wall(wall)`` (a dict in the wall-file format; bad input
  raises ValueError with the command line's one-line message).
- Planners: ``planners()`` lists the registered ones with their parameters; ``plan(wall, planner,
  params=..., tool_width=..., clearance=...)`` runs any of them (or an external planner, by its
  manifest's path) and returns the plan as a dict.
- Scores: ``score(wall, waypoints, tool_on, ..., judge="fast" | "exact")``: every metric of the
  fast engine, and with the exact judge its certified verdict.
- Results: ``runs(database)`` reads an experiment's runs as dicts; ``runs_dataframe(database)`` as
  a pandas DataFrame when pandas is installed.
- Planners in Python: ``coverbench.serve`` serves one over the planner protocol
  (docs/external_planners.md).

The compiled part (``coverbench._core``, pybind11) is built by scripts/setup.sh into build/python.
"""
import json
import os

__all__ = ["load_wall", "check_wall", "planners", "plan", "score", "runs", "runs_dataframe"]

# The compiled module lives in the build folder (COVERBENCH_BUILD_DIR, default build/).
_build = os.environ.get("COVERBENCH_BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
__path__.append(os.path.join(os.path.abspath(_build), "python", "coverbench"))  # noqa: F821


def _native():
    try:
        from . import _core as core
    except ImportError as e:
        raise ImportError("coverbench._core is not built: run `bash scripts/setup.sh` (it builds build/python)") from e
    return core


def _wall_text(wall):
    if isinstance(wall, str) and not wall.lstrip().startswith("{"):
        return _native().wall_file(wall)  # a path
    return wall if isinstance(wall, str) else json.dumps(wall)


def load_wall(path):
    """The wall file at `path`, checked, as a dict (boundary as points, rects as polygons)."""
    return json.loads(_native().wall_file(path))


def check_wall(wall):
    """Raises ValueError (`FILE: FIELD: PROBLEM`) unless `wall` (a dict or JSON text) is a valid wall."""
    _native().check_wall(_wall_text(wall), "wall")


def planners():
    """Every registered planner: name, version, summary, reference, params (specs), promise."""
    return json.loads(_native().planners())


def plan(wall, planner, params=None, tool_width=0.1, clearance=0.02, seed=0, time_limit_s=60.0, memory_mb=4096.0):
    """Plans `wall` (a dict, JSON text or a wall file's path) with `planner` (a registered name or an
    external planner's manifest path) and judges the path as `coverbench plan` and a run do (the same
    code): status (what a run would store: ``invalid_output`` for a path that fails the validity
    check, whatever the planner said), reason, planner_status (what the planner said), valid,
    violations, not_scored, waypoints, tool_on, stats, plan_time_ms. An external planner's processes
    are held to `time_limit_s` and `memory_mb` (all of them together)."""
    settings = [(k, json.dumps(v) if isinstance(v, bool) else str(v)) for k, v in sorted((params or {}).items())]
    return json.loads(_native().plan(_wall_text(wall), planner, settings, float(tool_width), float(clearance), int(seed),
                                   float(time_limit_s), float(memory_mb)))


def score(wall, waypoints, tool_on, tool_width=0.1, clearance=0.02, bulge=None, judge="fast"):
    """Every metric of the fast engine for a path from any source; judge="exact" adds the exact
    judge's verdict (validity, certified coverage intervals)."""
    return json.loads(_native().score(_wall_text(wall), [tuple(p) for p in waypoints], list(tool_on), list(bulge or []),
                                    float(tool_width), float(clearance), judge))


def runs(database, experiment=None):
    """An experiment's runs (default: the latest) as dicts: the run export's columns."""
    return json.loads(_native().runs(database, int(experiment or 0)))


def runs_dataframe(database, experiment=None):
    """The same as a pandas DataFrame (pandas must be installed)."""
    import pandas  # noqa: PLC0415 - optional
    return pandas.DataFrame(runs(database, experiment))

