"""coverbench._core, the compiled part (pybind11): JSON text in and out. Use the functions of
the coverbench package, which turn its answers into dicts."""
from typing import Any, Dict, List, Sequence, Tuple

class InputError(ValueError):
    """Bad input: the command line's one-line message (``SOURCE: FIELD: PROBLEM``)."""

def check_wall(text: str, source: str = "wall") -> None:
    """Checks wall-file JSON text as the command line does; raises ValueError."""

def wall_file(path: str) -> str:
    """The wall file at `path`, checked, as wall-file JSON text."""

def planners() -> str:
    """Every registered planner with its parameters, as JSON text."""

def plan(wall: str, planner: str, params: str, tool_width: float, clearance: float, seed: int,
         time_limit_s: float, memory_mb: float = 4096.0, profile: Dict[str, Any] = ..., tool_shape: str = ...,
         tool_depth: float = ...) -> str:
    """Plans and judges as `coverbench plan` does; the plan as JSON text."""

def score(wall: str, waypoints: Sequence[Tuple[float, float]], tool_on: Sequence[bool], bulge: Sequence[float],
          tool_width: float, clearance: float, judge: str, profile: Dict[str, Any] = ..., tool_shape: str = ...,
          tool_depth: float = ...) -> str:
    """Every metric of the fast engine (and the exact judge's verdict), as JSON text."""

def runs(database: str, experiment: int = 0) -> str:
    """An experiment's runs (0: the latest) as JSON text."""
