"""A complete boustrophedon (row sweep) planner in one Python file, served to CoverBench over the
planner protocol (docs/external_planners.md); its manifest is grid_sweep.json beside it.

Rows run along x, a row spacing apart. On each row the planner computes exactly where the tool's
centre may be (the tool disk inside the wall, the clearance kept from every obstacle): the row
minus, for every wall edge, the band of points nearer than the tool's radius, and for every
obstacle edge or circle, the band nearer than radius plus clearance. It paints those intervals
and joins them with straight moves that it checks the same way (a move is free when it stays at
least the radius from every wall edge and radius plus clearance from every obstacle, with both
ends inside the wall and outside every obstacle). A piece no straight move reaches is left out,
and the plan says so (status partial). Pure Python: no geometry library.
"""
import math
from typing import List, Tuple

MARGIN = 1e-6  # spare distance on every check (m)


def rect_polygon(o):
    x, y, w, h = o["x"], o["y"], o["width"], o["height"]
    return [(x, y), (x + w, y), (x + w, y + h), (x, y + h)]


def edges(ring):
    return [(ring[i], ring[(i + 1) % len(ring)]) for i in range(len(ring))]


def point_in_ring(p, ring):
    x, y = p
    inside = False
    for (ax, ay), (bx, by) in edges(ring):
        if (ay > y) != (by > y) and x < ax + (y - ay) * (bx - ax) / (by - ay):
            inside = not inside
    return inside


def point_segment_distance(p, a, b):
    (px, py), (ax, ay), (bx, by) = p, a, b
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def segments_cross(a, b, c, d):
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    return orient(a, b, c) * orient(a, b, d) < 0 and orient(c, d, a) * orient(c, d, b) < 0


def segment_distance(a, b, c, d):
    if segments_cross(a, b, c, d):
        return 0.0
    return min(point_segment_distance(a, c, d), point_segment_distance(b, c, d),
               point_segment_distance(c, a, b), point_segment_distance(d, a, b))


def box(a, b, d):
    """The bounding box (x0, x1, y0, y1) of the segment ab grown by d."""
    return (min(a[0], b[0]) - d, max(a[0], b[0]) + d, min(a[1], b[1]) - d, max(a[1], b[1]) + d)


def box_of(ring):
    xs, ys = [p[0] for p in ring], [p[1] for p in ring]
    return (min(xs), max(xs), min(ys), max(ys))


def band_interval(y, a, b, d):
    """The x interval of the row y nearer than d to the segment ab (the capsule is convex)."""
    lo, hi = math.inf, -math.inf
    for (cx, cy) in (a, b):  # the end discs
        if abs(y - cy) < d:
            half = math.sqrt(d * d - (y - cy) ** 2)
            lo, hi = min(lo, cx - half), max(hi, cx + half)
    (ax, ay), (bx, by) = a, b
    length = math.hypot(bx - ax, by - ay)
    if length > 0:  # the band along the segment: |n.(p - a)| < d and 0 <= u.(p - a) <= length
        ux, uy = (bx - ax) / length, (by - ay) / length
        nx, ny = -uy, ux
        xl, xh = -math.inf, math.inf
        for coef, const, low, high in ((nx, ny * (y - ay) - nx * ax, -d, d), (ux, uy * (y - ay) - ux * ax, 0.0, length)):
            if abs(coef) < 1e-15:
                if not (low <= const <= high):
                    xl, xh = math.inf, -math.inf
                continue
            x1, x2 = (low - const) / coef, (high - const) / coef
            xl, xh = max(xl, min(x1, x2)), min(xh, max(x1, x2))
        if xl <= xh:
            lo, hi = min(lo, xl), max(hi, xh)
    return (lo, hi) if lo <= hi else None


class Geometry:
    def __init__(self, problem):
        wall = problem.wall
        if "boundary" in wall:
            self.boundary = [tuple(p) for p in wall["boundary"]]
        else:
            self.boundary = [(0, 0), (wall["width"], 0), (wall["width"], wall["height"]), (0, wall["height"])]
        self.polygons, self.circles = [], []
        for o in wall.get("obstacles", []):
            if o["type"] == "circle":
                self.circles.append(((o["x"], o["y"]), o["radius"]))
            elif o["type"] == "rect":
                self.polygons.append(rect_polygon(o))
            else:
                self.polygons.append([tuple(p) for p in o["points"]])
        self.r = problem.radius + MARGIN
        self.keep = problem.radius + problem.clearance + MARGIN
        # Every edge with the distance the tool's centre keeps from it, and its bounding box grown by
        # that distance: a point or a move outside the box is far enough without computing it.
        self.checks = [(a, b, d, box(a, b, d)) for d, rings in ((self.r, [self.boundary]), (self.keep, self.polygons))
                       for ring in rings for a, b in edges(ring)]
        self.boxes = [box_of(poly) for poly in self.polygons]
        self.known = {}  # free_point's answers: the same row ends and waypoints are asked again and again

    def free_point(self, p):
        if p not in self.known:
            self.known[p] = self.point_is_free(p)
        return self.known[p]

    def point_is_free(self, p):
        x, y = p
        if not point_in_ring(p, self.boundary) or any(
                b[0] <= x <= b[1] and b[2] <= y <= b[3] and point_in_ring(p, poly) for poly, b in zip(self.polygons, self.boxes)):
            return False
        return all(not (b[0] <= x <= b[1] and b[2] <= y <= b[3]) or point_segment_distance(p, a, c) >= d
                   for a, c, d, b in self.checks) and \
            all(math.dist(p, c) >= rad + self.keep for c, rad in self.circles)

    def free_move(self, p, q):
        if not (self.free_point(p) and self.free_point(q)):
            return False
        x0, x1, y0, y1 = min(p[0], q[0]), max(p[0], q[0]), min(p[1], q[1]), max(p[1], q[1])
        return all(b[0] > x1 or b[1] < x0 or b[2] > y1 or b[3] < y0 or segment_distance(p, q, a, c) >= d
                   for a, c, d, b in self.checks) and \
            all(point_segment_distance(c, p, q) >= rad + self.keep for c, rad in self.circles)

    def row_intervals(self, y):
        """Where the tool's centre may be on the row y: inside the wall, out of every band."""
        xs = [x for (a, b) in edges(self.boundary) for x in crossing(y, a, b)]
        xs.sort()
        allowed = [(xs[i], xs[i + 1]) for i in range(0, len(xs) - 1, 2)]
        blocked = [band_interval(y, a, b, self.r) for a, b in edges(self.boundary)]
        blocked += [band_interval(y, a, b, self.keep) for poly in self.polygons for a, b in edges(poly)]
        for poly in self.polygons:
            ps = sorted(x for (a, b) in edges(poly) for x in crossing(y, a, b))
            blocked += [(ps[i], ps[i + 1]) for i in range(0, len(ps) - 1, 2)]
        for (cx, cy), rad in self.circles:
            d = rad + self.keep
            if abs(y - cy) < d:
                half = math.sqrt(d * d - (y - cy) ** 2)
                blocked.append((cx - half, cx + half))
        out = []
        for lo, hi in allowed:
            pieces = [(lo, hi)]
            for band in blocked:
                if band is None:
                    continue
                bl, bh = band
                pieces = [q for (pl, ph) in pieces for q in ((pl, min(ph, bl)), (max(pl, bh), ph)) if q[1] - q[0] > 1e-9]
            out += pieces
        # Shrink by a hair so the ends pass the same checks the moves do.
        return [(a + 1e-7, b - 1e-7) for a, b in out if b - a > 2e-7]


def crossing(y, a, b):
    (ax, ay), (bx, by) = a, b
    if (ay > y) != (by > y):
        return [ax + (y - ay) * (bx - ax) / (by - ay)]
    return []


class GridSweep:
    """The planner: `plan(problem)` returns the protocol's plan."""

    def plan(self, problem):
        g = Geometry(problem)
        overlap = float(problem.params.get("overlap", 0.0))
        spacing = problem.tool_width * (1.0 - overlap)
        ys = [p[1] for p in g.boundary]
        y_lo, y_hi = min(ys) + g.r + MARGIN, max(ys) - g.r - MARGIN  # a hair inside: the rows pass the checks
        if y_hi < y_lo:
            return {"status": "no_reachable_area", "reason": "the wall is narrower than the tool"}
        rows = max(1, math.ceil((y_hi - y_lo) / spacing - 1e-9))
        heights = [y_lo + (y_hi - y_lo) * k / rows for k in range(rows + 1)] if rows > 0 else [y_lo]
        pieces = []  # (row, x0, x1, y)
        for k, y in enumerate(heights):
            pieces += [(k, a, b, y) for a, b in g.row_intervals(y)]
        if not pieces:
            return {"status": "no_reachable_area", "reason": "the tool fits on no row"}
        waypoints: List[Tuple[float, float]] = []
        tool_on: List[bool] = []
        left = set(range(len(pieces)))
        rightward = True

        def paint(i, via=()):
            """Paints piece i (in the current direction), reached from the path's end through `via`."""
            nonlocal rightward
            _, a, b, y = pieces[i]
            start, end = ((a, y), (b, y)) if rightward else ((b, y), (a, y))
            for p in list(via) + [start]:
                if waypoints:
                    here = waypoints[-1]
                    # Paint the move only up to the next row, across it (the end of a row band).
                    tool_on.append(not via and abs(here[1] - p[1]) <= spacing * 1.01 and abs(here[0] - p[0]) <= spacing)
                waypoints.append(p)
            tool_on.append(True)
            waypoints.append(end)
            left.discard(i)
            rightward = not rightward

        def reach(here, i):
            """(cost, flip) of the cheapest free straight move from `here` to piece i, or None."""
            _, a, b, y = pieces[i]
            best = None
            for flip in (False, True):
                start = (a, y) if (rightward != flip) else (b, y)
                if g.free_move(here, start):
                    cost = math.dist(here, start)
                    if best is None or cost < best[0]:
                        best = (cost, flip)
            return best

        first = min(left, key=lambda i: (pieces[i][0], pieces[i][1]))
        paint(first)
        row = pieces[first][0]
        skipped = 0
        while left:
            here = waypoints[-1]
            best = None
            # The pieces of this row and the next ones first (nearest first), then every piece left.
            near = [i for i in left if abs(pieces[i][0] - row) <= 1]
            for group in (near, [i for i in left if abs(pieces[i][0] - row) > 1]):
                for i in sorted(group, key=lambda i: (abs(pieces[i][0] - row), math.dist(here, (pieces[i][1], pieces[i][3])))):
                    r = reach(here, i)
                    if r is not None and (best is None or r[0] < best[0]):
                        best = (r[0], i, r[1])
                    if best is not None and best[0] <= 2 * spacing:
                        break
                if best is not None:
                    break
            via = []
            if best is None:
                # Back along the path already driven (its moves are free) to a waypoint that sees a
                # piece left, then straight to it.
                for k in range(len(waypoints) - 2, -1, -1):
                    reached = [(reach(waypoints[k], i), i) for i in left]
                    found = [(r[0], i, r[1]) for r, i in reached if r is not None]
                    if found:
                        best = min(found)
                        via = waypoints[k:-1][::-1]
                        break
            if best is None:
                # The same to a point within a segment driven (a piece in a narrow cusp is seen from
                # no waypoint): the points below or above a piece's ends, and a segment's quarters.
                for k in range(len(waypoints) - 2, -1, -1):
                    (ax, ay), (bx, by) = waypoints[k], waypoints[k + 1]
                    ts = [0.25, 0.5, 0.75]
                    if ax != bx:
                        ts += [(x - ax) / (bx - ax) for i in left for x in pieces[i][1:3]]
                    points = [(ax + t * (bx - ax), ay + t * (by - ay)) for t in sorted(set(ts)) if 0 < t < 1]
                    seen = [(reach(q, i), i, q) for q in points for i in left]
                    options = [(r[0], i, r[1], q) for r, i, q in seen if r is not None]
                    if options:
                        cost, piece, flip, point = min(options)
                        best = (cost, piece, flip)
                        via = waypoints[k + 1:-1][::-1] + [point]
                        break
            if best is None:
                skipped = len(left)
                break
            if best[2]:
                rightward = not rightward
            paint(best[1], via)
            row = pieces[best[1]][0]
        result = {"status": "partial" if skipped else "ok", "waypoints": [list(p) for p in waypoints], "tool_on": tool_on,
                  "stats": {"rows": len(heights), "pieces": len(pieces), "unreached_pieces": skipped}}
        if skipped:
            result["reason"] = f"{skipped} row pieces no straight move reaches were left out"
        return result


if __name__ == "__main__":
    from coverbench.serve import serve  # CoverBench puts its python/ folder on PYTHONPATH
    serve(GridSweep())
