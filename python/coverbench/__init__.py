"""CoverBench from Python: walls, planners, both judges and an experiment's runs.

- Walls: ``load_wall(path)`` and ``check_wall(wall)`` (a dict in the wall-file format; bad input
  raises ValueError with the command line's one-line message).
- Planners: ``planners()`` lists the registered ones with their parameters; ``plan(wall, planner,
  params=..., tool_width=..., clearance=...)`` runs any of them (or an external planner, by its
  manifest's path) and judges the path as ``coverbench plan`` does.
- Scores: ``score(wall, waypoints, tool_on, ..., judge="fast" | "exact")``: every metric of the
  fast engine, ``valid`` as a bool with the violating segments, and with the exact judge its
  certified verdict.
- Tool profiles: ``plan`` and ``score`` take ``profile={"kind": "beta", "beta": 2.5}`` (kind
  uniform, gaussian with ``sigma`` or beta with ``beta``; ``rate``, ``depth``, ``target`` and ``flow`` optional; or just
  the kind's name): the tool's flux profile, read and checked as ``--profile`` is, which adds the
  five coat metrics (docs/deposition.md).
- Results: ``runs(database)`` reads an experiment's runs as dicts; ``runs_dataframe(database)`` as
  a pandas DataFrame (pandas must be installed).
- Planners in Python: ``coverbench.serve`` serves one over the planner protocol
  (docs/external_planners.md).

Waypoints come back as a numpy array of shape (n, 2) when numpy is installed, else as a list of
[x, y]; any sequence of (x, y) pairs goes in. A wall is a dict, wall-file JSON text or a wall
file's path.

Install: ``pip install ./python`` from the source tree (README.md, "From Python"); the compiled
part, ``coverbench._core`` (pybind11), is built by CMake and ships inside the package.
"""
from __future__ import annotations

import importlib
import importlib.machinery
import json
import os
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

__all__ = ["load_wall", "check_wall", "planners", "plan", "score", "runs", "runs_dataframe",
           "Wall", "Plan", "Profile", "Waypoints"]
__version__ = "0.1.0"

# In the source tree (tests, the planners CoverBench starts with python/ on PYTHONPATH) the
# compiled module is in the build folder (COVERBENCH_BUILD_DIR, default build/); an installed
# package holds it next to this file.
_here = os.path.dirname(os.path.abspath(__file__))
if not any(n == "_core" + s for n in os.listdir(_here) for s in importlib.machinery.EXTENSION_SUFFIXES):
    _build = os.environ.get("COVERBENCH_BUILD_DIR", os.path.join(_here, "..", "..", "build"))
    __path__.append(os.path.join(os.path.abspath(_build), "python", "coverbench"))  # noqa: F821

#: A wall: a dict in the wall-file format, its JSON text, or a wall file's path.
Wall = Union[Mapping[str, Any], str]
#: Waypoints as they come back: a numpy array of shape (n, 2) (float64) when numpy is installed,
#: else a list of [x, y]. Any sequence of (x, y) pairs goes in.
Waypoints = Any
#: A plan as ``plan()`` returns it (keys in the docstring of ``plan``).
Plan = Dict[str, Any]
#: A tool's flux profile: None (no profile), a kind's name ("uniform"), or a dict of ``kind``
#: ("uniform", "gaussian", "beta"), ``sigma`` (gaussian, m), ``beta`` (beta), ``rate`` (m³/s,
#: default 1e-6), ``depth`` (the fan's depth, m; default and 0: a tenth of the tool width) and
#: ``target`` (the coat aimed at, micrometres: the shares are then of it; default: none) and
#: ``flow`` ("constant", the default, or "speed": the gun's flow follows the tool's speed).
Profile = Union[None, str, Mapping[str, Any]]


class _Lazy:
    """coverbench._core, imported on first use: coverbench.serve works without it."""

    def __getattr__(self, name: str) -> Any:
        try:
            core = importlib.import_module(__name__ + "._core")
        except ImportError as e:
            raise ImportError("coverbench._core is not built: `pip install ./python` from the source tree "
                              "(README.md), or build the target coverbench_python") from e
        return getattr(core, name)


if TYPE_CHECKING:  # a type checker reads the compiled part's signatures from _core.pyi
    from . import _core
else:
    _core = _Lazy()


def _wall_text(wall: Wall) -> str:
    if isinstance(wall, str) and not wall.lstrip().startswith("{"):
        return _core.wall_file(wall)  # a path
    return wall if isinstance(wall, str) else json.dumps(wall)


def _waypoints_out(points: List[List[float]]) -> Waypoints:
    try:
        import numpy
    except ImportError:
        return points
    return numpy.asarray(points, dtype=numpy.float64).reshape(len(points), 2)


def _points_in(waypoints: Waypoints) -> List[Tuple[float, float]]:
    if hasattr(waypoints, "tolist"):  # a numpy array
        waypoints = waypoints.tolist()
    out = []
    for i, p in enumerate(waypoints):
        if len(p) != 2:
            raise ValueError(f"waypoints: waypoints[{i}]: must be an (x, y) pair")
        out.append((float(p[0]), float(p[1])))
    return out


def _profile_in(profile: Profile) -> Dict[str, Any]:
    """The profile as the compiled part reads it (which checks it as the command line does)."""
    if profile is None:
        return {}
    if isinstance(profile, str):
        return {"kind": profile}
    return dict(profile)


def load_wall(path: str) -> Dict[str, Any]:
    """The wall file at `path`, checked, as a dict (boundary as points, rects as polygons).

    Raises ValueError (``FILE: FIELD: PROBLEM``) when the file is not a valid wall."""
    result: Dict[str, Any] = json.loads(_core.wall_file(path))
    return result


def check_wall(wall: Wall) -> None:
    """Raises ValueError (``wall: FIELD: PROBLEM``) unless `wall` (a dict, JSON text or a wall
    file's path) is a valid wall."""
    _core.check_wall(_wall_text(wall), "wall")


def planners() -> List[Dict[str, Any]]:
    """Every registered planner: name, version, summary, reference, params (each with name,
    type, default, unit, description and its range or choices) and min_coverage_reachable (the
    coverage its class promises)."""
    result: List[Dict[str, Any]] = json.loads(_core.planners())
    return result


def plan(wall: Wall, planner: str, params: Optional[Mapping[str, Union[bool, int, float, str]]] = None,
         tool_width: float = 0.1, clearance: float = 0.02, seed: int = 0, time_limit_s: float = 60.0,
         memory_mb: float = 4096.0, profile: Profile = None, tool_shape: str = "disk", tool_depth: float = 0.0) -> Plan:
    """Plans `wall` with `planner` (a registered name or an external planner's manifest path) and
    judges the path as ``coverbench plan`` and a run judge it (the same code).

    Returns a dict:

    - ``status``: what a run would store: ``invalid_output`` for a path that fails the validity
      check and ``metrics_error`` for one beyond the scoring limits, whatever the planner said;
      otherwise the planner's status (ok, partial, no_reachable_area, invalid_input, timeout,
      memory_limit, crash, error, ...);
    - ``reason``; ``planner_status``: what the planner itself said;
    - ``valid`` (bool), ``violations`` (int), ``violating_segments`` (the first violating
      segments' indices; segment i joins waypoints i and i + 1), ``violation_details`` (for the
      first five: ``segment``, ``from``, ``to``, what it breaks, ``obstacle`` and
      ``obstacle_label``, the gaps reached) and ``invalid_reason`` (the run's one-line message):
      None when there is no path or it could not be scored (``not_scored`` says why);
    - ``waypoints`` (numpy (n, 2) array where numpy is installed), ``tool_on`` (list of bool),
      ``bulge`` (only when the path has arcs), ``stats``, ``plan_time_ms``;
    - with a `profile`: ``thickness_mean`` (µm), ``thickness_cv``, ``even_share``, ``thin_share``
      and ``thick_share`` (docs/deposition.md), when the path was scored.

    `params` are the planner's parameters by name. `profile` is the tool's flux profile (see
    ``Profile``): the planners that space rows for an even coat (``coat_ripple``) read it.
    `tool_shape` is ``"disk"``, ``"line"`` (a segment of length `tool_width` square to the
    heading) or ``"rectangle"`` (`tool_width` across the heading and `tool_depth` along it):
    docs/metrics.md#tool-shapes; planned for its circumscribed disk and scored as its shape (the
    reason says so). An external planner's processes are held to
    `time_limit_s` and `memory_mb` (all of them together). Bad input raises ValueError."""
    try:  # read by the parameter codec, as the server reads a request's params
        settings = json.dumps(dict(params or {}), allow_nan=False)
    except (TypeError, ValueError) as e:
        raise ValueError(f"params: {e}") from None
    out: Plan = json.loads(_core.plan(_wall_text(wall), planner, settings, float(tool_width), float(clearance),
                                          int(seed), float(time_limit_s), float(memory_mb), _profile_in(profile),
                                          str(tool_shape), float(tool_depth)))
    out["waypoints"] = _waypoints_out(out["waypoints"])
    return out


def score(wall: Wall, waypoints: Waypoints, tool_on: Sequence[bool], tool_width: float = 0.1,
          clearance: float = 0.02, bulge: Optional[Sequence[float]] = None, judge: str = "fast",
          profile: Profile = None, tool_shape: str = "disk", tool_depth: float = 0.0) -> Dict[str, Any]:
    """Scores a path from any source on `wall`: every metric of the fast engine by name
    (docs/metrics.md; None where one is not finite), ``valid`` as a bool, ``violations``,
    ``violating_segments`` (the first violating segments' indices), ``violation_details`` (what
    the first five hit: points, the obstacle by index and label or the wall's edge, the gaps
    reached) and ``invalid_reason`` (the one-line message, empty when valid). ``judge="exact"`` adds
    ``exact``: the exact judge's ``valid``, ``violations`` and certified [lower, upper] intervals
    of ``coverage_reachable`` and ``coverage_wall``.

    `waypoints`: (x, y) pairs (a numpy (n, 2) array or any sequence); `tool_on`: one bool per
    segment; `bulge`: none, or one per segment (0 straight). With a flux `profile` (see
    ``Profile``) the metrics include the coat's five: ``thickness_mean`` (µm), ``thickness_cv``,
    ``even_share``, ``thin_share``, ``thick_share``. Bad input raises ValueError (a bad profile:
    ``profile: FIELD: PROBLEM``, the command line's checks). `tool_shape`: ``"disk"``, ``"line"``
    or ``"rectangle"`` with its `tool_depth` (docs/metrics.md#tool-shapes)."""
    result: Dict[str, Any] = json.loads(_core.score(
        _wall_text(wall), _points_in(waypoints), [bool(t) for t in tool_on], [float(b) for b in (bulge or [])],
        float(tool_width), float(clearance), judge, _profile_in(profile), str(tool_shape), float(tool_depth)))
    return result


def runs(database: str, experiment: Optional[int] = None) -> List[Dict[str, Any]]:
    """An experiment's runs (default: the latest) from a results database as dicts: the columns
    of ``coverbench runs DB --format json``."""
    result: List[Dict[str, Any]] = json.loads(_core.runs(database, int(experiment or 0)))
    return result


def runs_dataframe(database: str, experiment: Optional[int] = None) -> Any:
    """The same runs as a pandas DataFrame, one row per run (pandas must be installed)."""
    import pandas
    return pandas.DataFrame(runs(database, experiment))
