"""CoverBench from Python: plan a wall with a registered planner, score the path with both judges,
then score a path of your own. After `pip install ./python` (README.md, "From Python"):

    python plan_and_score.py datasets/canonical/living_room_north.json
"""
import sys
from typing import Any, Dict, List

import coverbench


def main(argv: List[str]) -> int:
    wall_path = argv[1] if len(argv) > 1 else "datasets/canonical/living_room_north.json"
    wall: Dict[str, Any] = coverbench.load_wall(wall_path)
    plan = coverbench.plan(wall, "zigzag", {"overlap": 0.1}, tool_width=0.1, clearance=0.02)
    print(f"zigzag: {plan['status']}, valid {plan['valid']}, {len(plan['waypoints'])} waypoints")
    scores = coverbench.score(wall, plan["waypoints"], plan["tool_on"], bulge=plan.get("bulge"), judge="exact")
    low, high = scores["exact"]["coverage_reachable"]
    print(f"coverage of the reachable area {scores['coverage_reachable']:.4f} (exact judge: [{low:.4f}, {high:.4f}])")
    # A path of your own: one tool-on pass along the bottom of the wall's bounding box.
    xs = [p[0] for p in wall["boundary"]]
    ys = [p[1] for p in wall["boundary"]]
    mine = coverbench.score(wall, [(min(xs), min(ys)), (max(xs), min(ys))], [True])
    print(f"a pass along the bottom edge: valid {mine['valid']}, violating segments {mine['violating_segments']}")
    return 0 if plan["valid"] and scores["valid"] and not mine["valid"] else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
