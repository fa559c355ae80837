// Exact validity: CGAL's exact kernel, no tolerance. Shares nothing with the geometry layer's
// predicates or the fast engine's ClearanceField; the only things read from the rest of CoverBench
// are the wall, the tool and the path as plain numbers.
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/squared_distance_2.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "coverbench/judge.hpp"
#include "exact_arcs.hpp"
#include "exact_line.hpp"
#include "exact_kernel.hpp"

namespace coverbench::judge {
namespace {

/// A double box that surely contains everything within `reach` of the box of (a, b): the
/// comparisons below only skip pairs this box test rules out, so the box must err outwards.
struct Box {
  double x0, y0, x1, y1;
  bool meets(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};
Box boxAround(Point a, Point b, double reach) {
  const double m = reach * (1.0 + 1e-9) + 1e-9;
  const double inf = std::numeric_limits<double>::infinity();
  return {std::nextafter(std::fmin(a.x, b.x) - m, -inf), std::nextafter(std::fmin(a.y, b.y) - m, -inf),
          std::nextafter(std::fmax(a.x, b.x) + m, inf), std::nextafter(std::fmax(a.y, b.y) + m, inf)};
}

struct Edge {
  S2 segment;
  Box box;
};
std::vector<Edge> ringEdges(const Ring& ring) {
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point a = ring[i], b = ring[(i + 1) % ring.size()];
    edges.push_back({S2(exactPoint(a), exactPoint(b)), boxAround(a, b, 0.0)});
  }
  return edges;
}

struct PolygonShape {
  std::vector<P2> vertices;
  std::vector<Edge> edges;
  Box box;
};
PolygonShape polygonShape(const Ring& ring) {
  PolygonShape p;
  for (Point q : ring) p.vertices.push_back(exactPoint(q));
  p.edges = ringEdges(ring);
  Point lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Point q : ring) {
    lo = {std::fmin(lo.x, q.x), std::fmin(lo.y, q.y)};
    hi = {std::fmax(hi.x, q.x), std::fmax(hi.y, q.y)};
  }
  p.box = boxAround(lo, hi, 0.0);
  return p;
}
bool inside(const PolygonShape& p, const P2& q) {
  return CGAL::bounded_side_2(p.vertices.begin(), p.vertices.end(), q, K()) != CGAL::ON_UNBOUNDED_SIDE;
}
bool strictlyInside(const PolygonShape& p, const P2& q) {
  return CGAL::bounded_side_2(p.vertices.begin(), p.vertices.end(), q, K()) == CGAL::ON_BOUNDED_SIDE;
}

/// Whether the segment e meets the interior of the convex counter-clockwise polygon q: the
/// parameters of e's points strictly inside every edge's half-plane form an open interval.
bool meetsInterior(const std::vector<P2>& q, const S2& e) {
  const P2 &s = e.source(), &t = e.target();
  FT lo = 0, hi = 1;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const V2 edge = q[(k + 1) % q.size()] - q[k];
    const FT f0 = crossOf(edge, s - q[k]), f1 = crossOf(edge, t - q[k]);
    const FT slope = f1 - f0;
    if (slope == 0) {
      if (f0 <= 0) return false;
      continue;
    }
    const FT root = -f0 / slope;
    if (slope > 0) lo = std::max(lo, root);
    else hi = std::min(hi, root);
    if (!(lo < hi)) return false;
  }
  return lo < hi;
}

/// Squared distance from the path piece [a, b] (a point when a == b) to an edge.
FT squaredDistance(const P2& a, const P2& b, const S2& edge) {
  if (a == b) return CGAL::squared_distance(a, edge);
  return CGAL::squared_distance(S2(a, b), edge);
}
FT squaredDistance(const P2& a, const P2& b, const P2& centre) {
  if (a == b) return CGAL::squared_distance(a, centre);
  return CGAL::squared_distance(S2(a, b), centre);
}

/// A car's rules, exactly: every arc's radius at least the turn radius; at every waypoint the
/// next segment starts in the direction the last one ended (within kCarHeadingTolerance: the sine
/// of the angle between them at most its sine, and the two facing the same way), or, for a car
/// that reverses, in the opposite one.
void drivable(const Path& path, const VehicleModel& car, const std::vector<P2>& points, ExactValidity& v) {
  const FT rho(car.turn_radius), sin_tol(std::sin(kCarHeadingTolerance));
  bool have = false;
  V2 before;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (points[i] == points[i + 1]) continue;
    const double bulge = path.bulge.empty() ? 0.0 : path.bulge[i];
    bool bad = false;
    // The directions it starts and ends with, exactly: the chord's for a straight segment; for an
    // arc, its radius at each end turned a quarter the arc's way.
    V2 start = points[i + 1] - points[i], end = start;
    if (bulge != 0.0) {
      const ExactArc arc = exactArc(path.waypoints[i], path.waypoints[i + 1], bulge, 1.0);
      if (arc.radius2 < rho * rho) bad = true;
      const V2 ra = points[i] - arc.centre, rb = points[i + 1] - arc.centre;
      const FT t(arc.turn);
      start = V2(-ra.y() * t, ra.x() * t);
      end = V2(-rb.y() * t, rb.x() * t);
    }
    if (have) {
      const FT cross = before.x() * start.y() - before.y() * start.x();
      const FT dot = before * start;
      const bool parallel = cross * cross <= sin_tol * sin_tol * before.squared_length() * start.squared_length();
      if (!parallel || (dot < 0 && !car.reverse) || dot == 0) bad = true;
    }
    before = end;
    have = true;
    if (!bad) continue;
    ++v.not_drivable;
    ++v.violations;
    if (v.violating.size() < ExactValidity::kMaxListed) v.violating.push_back(i);
  }
}

/// A round obstacle: its centre and radius rho, exactly.
struct Round {
  P2 centre;
  FT radius;  ///< rho
  Box box;
};

/// The wall and the tool, exactly: what every check of a path compares against.
class Scene {
 public:
  /// The disk of a path's points is the one that holds the tool in every heading: a disk's own, a
  /// line's circumscribed one, a rectangle's (its radius rounded up to a rational).
  Scene(const Wall& wall, const ToolParams& tool)
      : r_(CGAL::to_interval(ExactShape(tool).reachAtLeast()).second), c_(tool.clearance),
        r_exact_(ExactShape(tool).reachAtLeast()),
        boundary_(polygonShape(wall.boundary)) {
    for (const Obstacle& o : wall.obstacles) {
      if (o.type == ObstacleType::Circle) {
        rounds_.push_back({exactPoint(o.center), FT(o.radius), boxAround(o.center, o.center, o.radius)});
      } else {
        polygons_.push_back(polygonShape(o.polygon));
      }
    }
    for (Point p : wall.boundary) {
      lo_x_ = std::min(lo_x_, p.x);
      lo_y_ = std::min(lo_y_, p.y);
      hi_x_ = std::max(hi_x_, p.x);
      hi_y_ = std::max(hi_y_, p.y);
    }
  }

  /// The piece [ea, eb] of a segment with the disk grown by `grow` (0, or an arc's stray from its
  /// chords): whether it leaves the wall (`outside`) or comes too close to an obstacle (`close`).
  /// Where each end lies: inside the wall, and not strictly inside any polygon obstacle. A piece
  /// that keeps its distances crosses no edge, so its first end decides.
  void piece(const P2& ea, const P2& eb, const FT& grow, bool& outside, bool& close) const {
    const Point a{CGAL::to_double(ea.x()), CGAL::to_double(ea.y())}, b{CGAL::to_double(eb.x()), CGAL::to_double(eb.y())};
    const double g = CGAL::to_interval(grow).second;
    const FT rr = r_exact_ + grow, rr2 = rr * rr, rrc = rr + FT(c_), rrc2 = rrc * rrc;
    if (!outside) outside = !inside(boundary_, ea);
    if (!outside) {
      const Box reach = boxAround(a, b, r_ + g);
      for (const Edge& e : boundary_.edges) {
        if (!reach.meets(e.box)) continue;
        if (squaredDistance(ea, eb, e.segment) < rr2) {
          outside = true;
          break;
        }
      }
    }
    const Box reach = boxAround(a, b, r_ + c_ + g);
    for (const PolygonShape& o : polygons_) {
      if (close) break;
      if (!reach.meets(o.box)) continue;
      if (strictlyInside(o, ea)) {
        close = true;
        break;
      }
      for (const Edge& e : o.edges) {
        if (!reach.meets(e.box)) continue;
        if (squaredDistance(ea, eb, e.segment) < rrc2) {
          close = true;
          break;
        }
      }
    }
    for (const Round& o : rounds_) {
      if (close) break;
      if (!reach.meets(o.box)) continue;
      const FT limit = o.radius + rrc;
      if (squaredDistance(ea, eb, o.centre) < limit * limit) close = true;
    }
  }

  /// Segment `segment` of the path, from points[ia] to points[ib] (ia == ib: a point): whether
  /// the tool leaves the wall (`outside`) or comes too close to an obstacle (`close`).
  void segment(const Path& path, const std::vector<P2>& points, std::size_t segment, std::size_t ia, std::size_t ib,
               bool& outside, bool& close) const {
    outside = close = false;
    const double bulge = path.bulge.empty() || ia == ib ? 0.0 : path.bulge[segment];
    if (bulge == 0.0) {
      piece(points[ia], points[ib], FT(0), outside, close);
      return;
    }
    // Chords of 1e-3 m, then 1e-5 m, then kArcChordSagitta (1e-7 m): each try is a certified
    // verdict when it passes (the disk grown by the chords' stray holds the arc's), so only an
    // arc near its limit is cut finely, and only a failing one as finely as ever. A step of 100
    // in sagitta is 10 times the chords; finer steps cost a failing arc more tries than they save.
    for (double sagitta = std::fmax(1e-3, kArcChordSagitta);; sagitta = std::fmax(sagitta / 100.0, kArcChordSagitta)) {
      outside = close = false;
      const ExactArc arc = exactArc(path.waypoints[ia], path.waypoints[ib], bulge, sagitta);
      if (!arc.ordered) outside = true;  // no certified bound: refused
      for (std::size_t k = 0; k + 1 < arc.points.size() && !(outside && close); ++k)
        piece(arc.points[k], arc.points[k + 1], arc.stray, outside, close);
      if ((!outside && !close) || sagitta <= kArcChordSagitta) break;
    }
  }

  /// A convex polygon q (counter-clockwise, exact) that a line tool sweeps: whether it leaves the
  /// wall (an edge of the wall meets its interior, or its centroid lies outside) or comes closer
  /// than c to an obstacle (an obstacle's edge meets its interior or comes closer than c to one of
  /// its edges, its centroid lies inside a polygon obstacle, or a round one's centre is nearer
  /// than rho + c to it). A convex polygon whose interior no edge of the wall meets lies inside or
  /// outside the wall as its centroid does; likewise for an obstacle.
  void convex(const std::vector<P2>& q, bool& outside, bool& close) const {
    FT sx = 0, sy = 0;
    double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
    for (const P2& v : q) {
      sx += v.x(), sy += v.y();
      const auto ix = CGAL::to_interval(v.x()), iy = CGAL::to_interval(v.y());
      lo_x = std::min(lo_x, ix.first), hi_x = std::max(hi_x, ix.second);
      lo_y = std::min(lo_y, iy.first), hi_y = std::max(hi_y, iy.second);
    }
    const P2 centroid(sx / FT(static_cast<int>(q.size())), sy / FT(static_cast<int>(q.size())));
    const Box box = boxAround({lo_x, lo_y}, {hi_x, hi_y}, 0.0), reach = boxAround({lo_x, lo_y}, {hi_x, hi_y}, c_);
    if (!outside) outside = !inside(boundary_, centroid);
    for (const Edge& e : boundary_.edges) {
      if (outside) break;
      if (box.meets(e.box) && meetsInterior(q, e.segment)) outside = true;
    }
    const FT c2 = FT(c_) * FT(c_);
    for (const PolygonShape& o : polygons_) {
      if (close) break;
      if (!reach.meets(o.box)) continue;
      if (strictlyInside(o, centroid)) {
        close = true;
        break;
      }
      for (const Edge& e : o.edges) {
        if (!reach.meets(e.box)) continue;
        if (meetsInterior(q, e.segment)) close = true;
        for (std::size_t k = 0; k < q.size() && !close && c_ > 0.0; ++k)
          if (CGAL::squared_distance(S2(q[k], q[(k + 1) % q.size()]), e.segment) < c2) close = true;
        if (close) break;
      }
    }
    for (const Round& o : rounds_) {
      if (close) break;
      if (!reach.meets(o.box)) continue;
      if (CGAL::bounded_side_2(q.begin(), q.end(), o.centre, K()) != CGAL::ON_UNBOUNDED_SIDE) {
        close = true;
        break;
      }
      const FT limit = o.radius + FT(c_);
      for (std::size_t k = 0; k < q.size() && !close; ++k)
        if (CGAL::squared_distance(S2(q[k], q[(k + 1) % q.size()]), o.centre) < limit * limit) close = true;
    }
  }

  /// The turn of a line or rectangle tool about p: the sectors its corners sweep, through fans of
  /// triangles that contain them (exact_line.hpp), tried with chords of 1e-3, 1e-5 and
  /// kArcChordSagitta m as an arc is: a try that passes settles it; when the last fails, the turn
  /// is refused.
  void turn(const P2& p, const ExactTurn& t, const ExactShape& shape, bool& outside, bool& close) const {
    bool out = false, near = false;
    const double reach = shape.reach();
    const FT reach2 = shape.reach2();
    const std::vector<ExactTurn> corners = cornerTurns(t, shape);
    for (double sagitta = 1e-3;; sagitta = std::fmax(sagitta / 100.0, kArcChordSagitta)) {
      out = near = false;
      for (const ExactTurn& corner : corners)
        for (int side : {1, -1}) {
          const std::vector<Triangle> fan = sectorFan(p, corner, reach, reach2, std::fmin(sagitta, reach / 2.0), true, side);
          if (fan.empty()) out = true;  // no certified container: refused
          for (const Triangle& tri : fan) convex(std::vector<P2>(tri.begin(), tri.end()), out, near);
        }
      if ((!out && !near) || sagitta <= kArcChordSagitta) break;
    }
    outside = outside || out;
    close = close || near;
  }

  /// One end of a gantry's lifted segment: the disk at p within the wall's bounding box, compared
  /// exactly (the box is convex: with both ends' tools inside it, the whole segment's are).
  bool diskInFrame(Point p) const { return inFrame(p); }

  /// A line or rectangle tool lowered or lifted at p with the heading d (the tool-on move it
  /// begins or ends): its shape, through the rational rectangle that contains it, inside the
  /// wall's bounding box, compared exactly.
  bool shapeInFrame(const P2& p, const V2& d, const ExactShape& shape) const {
    const V2 m = leftNormal(d), km = m * scaleFor(m, shape.h, shape.h2, true);
    const V2 kd = shape.e == 0.0 ? V2(0, 0) : d * scaleFor(d, shape.e, shape.e2, true);
    for (const V2& q : {km + kd, km - kd, -km + kd, -km - kd}) {
      const P2 c = p + q;
      if (c.x() < FT(lo_x_) || c.x() > FT(hi_x_) || c.y() < FT(lo_y_) || c.y() > FT(hi_y_)) return false;
    }
    return true;
  }

  /// Whether p, taken as a point of the path, breaks either rule (it lies outside F).
  bool outsideF(const P2& p) const {
    bool outside = false, close = false;
    piece(p, p, FT(0), outside, close);
    return outside || close;
  }

  /// Whether the straight segment from a to b may be part of a depot leg (path.hpp: depot legs),
  /// exactly: not a point, its centre line in the closed wall and with no point in common with
  /// any obstacle.
  bool depotSegment(const P2& a, const P2& b) const {
    if (a == b) return false;
    // In the wall: the segment is cut where it meets the boundary (its edges' crossings and the
    // vertices on it); each piece between two cuts lies inside, outside or on the boundary
    // throughout, and its midpoint says which.
    const V2 d = b - a;
    const FT len2 = d.squared_length();
    std::vector<FT> cuts{FT(0), FT(1)};
    for (const Edge& e : boundary_.edges) {
      const P2 &p = e.segment.source(), &q = e.segment.target();
      if (CGAL::orientation(a, b, p) == CGAL::COLLINEAR && CGAL::collinear_are_strictly_ordered_along_line(a, p, b))
        cuts.push_back(((p - a) * d) / len2);
      const V2 f = q - p, ap = p - a;
      const FT den = d.x() * f.y() - d.y() * f.x();
      if (den == 0) continue;
      const FT t = (ap.x() * f.y() - ap.y() * f.x()) / den, u = (ap.x() * d.y() - ap.y() * d.x()) / den;
      if (t > 0 && t < 1 && u >= 0 && u <= 1) cuts.push_back(t);
    }
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
      if (cuts[k] != cuts[k + 1] && !inside(boundary_, a + d * ((cuts[k] + cuts[k + 1]) / 2))) return false;
    // Off every obstacle: no point in common with any.
    const S2 leg(a, b);
    for (const PolygonShape& o : polygons_) {
      if (strictlyInside(o, a)) return false;
      for (const Edge& e : o.edges)
        if (CGAL::do_intersect(leg, e.segment)) return false;
    }
    for (const Round& o : rounds_)
      if (CGAL::squared_distance(leg, o.centre) <= o.radius * o.radius) return false;
    return true;
  }

 private:
  bool inFrame(Point p) const {
    const FT x(p.x), y(p.y);
    return x - r_exact_ >= FT(lo_x_) && x + r_exact_ <= FT(hi_x_) && y - r_exact_ >= FT(lo_y_) &&
           y + r_exact_ <= FT(hi_y_);
  }

  double r_, c_;
  FT r_exact_;
  PolygonShape boundary_;
  std::vector<PolygonShape> polygons_;
  std::vector<Round> rounds_;
  double lo_x_ = INFINITY, lo_y_ = INFINITY, hi_x_ = -INFINITY, hi_y_ = -INFINITY;
};

/// Counts a violating segment in `v`: leaving the wall (`outside`), too close to an obstacle
/// (`close`), or both.
void flag(ExactValidity& v, std::size_t segment, bool outside, bool close) {
  v.outside_boundary += outside;
  v.too_close += close;
  if (!outside && !close) return;
  ++v.violations;
  if (v.violating.size() < ExactValidity::kMaxListed) v.violating.push_back(segment);
}

}  // namespace

ExactValidity judgeValidity(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle) {
  ExactValidity v;
  const std::size_t n = path.waypoints.size();
  if (n == 0) return v;
  const Scene scene(wall, tool);
  std::vector<P2> points;
  points.reserve(n);
  for (Point p : path.waypoints) points.push_back(exactPoint(p));
  auto check = [&](std::size_t segment, std::size_t ia, std::size_t ib) {
    bool outside = false, close = false;
    scene.segment(path, points, segment, ia, ib, outside, close);
    flag(v, segment, outside, close);
  };
  // Depot legs (path.hpp: depot legs), exactly: the tool-off prefix from a start outside F up to
  // the first waypoint in F, and the suffix from the last waypoint in F to an end outside F. A leg
  // that breaks the rule is checked segment by segment like any other instead.
  auto at = [&](const std::optional<Point>& p, std::size_t k) { return p && path.waypoints[k] == *p; };
  // The segments of the leg from waypoint `from` walking by `step` (+1 from the start, -1 from
  // the end) to the first waypoint in F; 0 when there is no such leg.
  auto depotLeg = [&](std::size_t from, long step) -> std::size_t {
    std::size_t here = from, k = 0;
    for (;;) {
      if ((step < 0 && here == 0) || (step > 0 && here + 1 >= n)) return 0;
      const std::size_t next = step > 0 ? here + 1 : here - 1, segment = std::min(here, next);
      if (path.tool_on[segment] || (!path.bulge.empty() && path.bulge[segment] != 0.0) ||
          !scene.depotSegment(points[here], points[next]))
        return 0;
      ++k;
      here = next;
      if (!scene.outsideF(points[here])) return k;
    }
  };
  const std::size_t lead_in = n >= 2 && at(wall.start, 0) && scene.outsideF(points[0]) ? depotLeg(0, 1) : 0;
  const std::size_t lead_out = n >= 2 && at(wall.end, n - 1) && scene.outsideF(points[n - 1]) ? depotLeg(n - 1, -1) : 0;
  v.depot_legs = static_cast<std::size_t>(lead_in > 0) + static_cast<std::size_t>(lead_out > 0);
  // Segment i lies in a depot leg (the end's leg is segments n - 1 - lead_out to n - 2).
  auto inDepotLeg = [&](std::size_t i) { return i < lead_in || i + 1 + lead_out >= n; };
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (inDepotLeg(i)) v.depot_length += std::hypot(path.waypoints[i + 1].x - path.waypoints[i].x, path.waypoints[i + 1].y - path.waypoints[i].y);
  // A line or rectangle tool (exact_line.hpp): each move's rectangle on the wall and the turn at
  // its start from the last such move (zero-length moves skipped). A path that never moves has no
  // heading: its tool must fit in every one (the Scene's disk).
  const bool line = tool.turnsWithHeading() && std::any_of(points.begin(), points.end(), [&](const P2& p) { return p != points[0]; });
  if (tool.turnsWithHeading() && (vehicle.isCar() || std::any_of(path.bulge.begin(), path.bulge.end(), [](double b) { return b != 0.0; })))
    throw std::invalid_argument(std::string("judge: a ") + (tool.isLine() ? "line" : "rectangle") + " tool's path is judged on straight moves only (no car, no arcs)");
  const ExactShape shape(tool);
  std::optional<V2> heading;  // the direction of the last move on the wall
  auto lineCheck = [&](std::size_t i) {
    if (points[i] == points[i + 1]) return;  // the line there is the one the moves around it end and start with
    bool outside = false, close = false;
    scene.convex(lineRectangle(points[i], points[i + 1], shape, true), outside, close);
    if (heading) {
      const ExactTurn t = exactTurn(*heading, points[i + 1] - points[i]);
      if (t.turns) scene.turn(points[i], t, shape, outside, close);
    }
    heading = points[i + 1] - points[i];
    flag(v, i, outside, close);
  };
  if (n == 1) check(0, 0, 0);
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (inDepotLeg(i)) {
      if (points[i] != points[i + 1]) heading = points[i + 1] - points[i];  // its end's turn is the next move's
      continue;
    } else if (vehicle.liftsTool() && !path.tool_on[i]) {
      // A line or rectangle is lifted and lowered at the heading of the tool-on move it ends or
      // begins; without one, at any heading (the Scene's disk).
      bool outside = false;
      for (const auto& [k, step] : {std::pair<std::size_t, int>{i, -1}, {i + 1, 1}}) {
        const bool has = step < 0 ? k > 0 : k + 1 < n;
        const std::size_t other = step < 0 ? k - 1 : k + 1, segment = std::min(k, other);
        if (tool.turnsWithHeading() && has && path.tool_on[segment] && points[k] != points[other])
          outside = outside || !scene.shapeInFrame(points[k], step < 0 ? points[k] - points[other] : points[other] - points[k], shape);
        else
          outside = outside || !scene.diskInFrame(path.waypoints[k]);
      }
      flag(v, i, outside, false);
      heading.reset();  // the tool turns lifted
    } else if (line) {
      lineCheck(i);
    } else {
      check(i, i, i + 1);
    }
  if (vehicle.isCar()) drivable(path, vehicle, points, v);
  v.valid = v.violations == 0;
  return v;
}

}  // namespace coverbench::judge
