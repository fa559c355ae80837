#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>
#include <utility>

#include "coverbench/clearance.hpp"
#include "coverbench/metrics.hpp"
#include "line_tool.hpp"

namespace coverbench {
namespace {

/// The headings (radians) a segment starts and ends with: the chord's, turned by half the arc's
/// sweep back and forth.
std::pair<double, double> headings(const Path& path, std::size_t i) {
  const Point d = path.waypoints[i + 1] - path.waypoints[i];
  const double chord = std::atan2(d.y, d.x);
  const double bulge = path.bulgeOf(i);
  const double half = bulge == 0.0 ? 0.0 : 2.0 * std::atan(bulge);
  return {chord - half, chord + half};
}

/// A car's rules: arcs no tighter than its turn radius; the heading continuous at every waypoint
/// (within kCarHeadingTolerance), or reversed there when the car may reverse.
void checkDrivable(const Path& path, const VehicleModel& car, Validity& v, std::vector<Violation>& described) {
  bool have = false;
  double end_heading = 0.0;
  for (std::size_t i = 0; i < path.segments(); ++i) {
    if (path.waypoints[i] == path.waypoints[i + 1]) continue;
    bool bad = false;
    const double bulge = path.bulgeOf(i);
    if (bulge != 0.0 && arcGeometry(path.waypoints[i], path.waypoints[i + 1], bulge).radius < car.turn_radius * (1.0 - 1e-12))
      bad = true;
    const auto [start, end] = headings(path, i);
    if (have) {
      const double change = std::fabs(std::remainder(start - end_heading, 2.0 * M_PI));
      const bool smooth = change <= kCarHeadingTolerance;
      const bool cusp = car.reverse && change >= M_PI - kCarHeadingTolerance;
      if (!smooth && !cusp) bad = true;
    }
    end_heading = end;
    have = true;
    if (!bad) continue;
    ++v.not_drivable;
    ++v.violations;
    if (v.violating.size() < kMaxListedViolations) v.violating.push_back(i);
    if (described.size() < kDescribedViolations) {
      Violation d;
      d.segment = i;
      d.from = path.waypoints[i];
      d.to = path.waypoints[i + 1];
      d.not_drivable = true;
      described.push_back(d);
    }
  }
}

/// `extra` (a car's undrivable segments) merged into v.described: one entry a segment, by index,
/// the first kDescribedViolations kept.
void mergeDescribed(Validity& v, const std::vector<Violation>& extra) {
  for (const Violation& e : extra) {
    auto same = std::find_if(v.described.begin(), v.described.end(), [&](const Violation& d) { return d.segment == e.segment; });
    if (same != v.described.end())
      same->not_drivable = true;
    else
      v.described.push_back(e);
  }
  std::stable_sort(v.described.begin(), v.described.end(),
                   [](const Violation& a, const Violation& b) { return a.segment < b.segment; });
  if (v.described.size() > kDescribedViolations) v.described.resize(kDescribedViolations);
}

/// A number as messages show it: `digits` significant digits, no "-0".
std::string num(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v == 0.0 ? 0.0 : v);
  return buf;
}

/// "gap m < limit m", with as many more digits as it takes for the two to differ (a gap short by
/// a micrometre of 0.05 m is not shown as "0.05 m < 0.05 m").
std::string shortfall(double gap, double limit) {
  int digits = 6;
  while (digits < 17 && num(gap, digits) == num(limit, digits)) ++digits;
  return num(gap, digits) + " m < " + num(limit, digits) + " m";
}

}  // namespace

bool depotSegment(const ClearanceField& field, Point a, Point b) {
  if (a == b) return false;
  // Off every obstacle: not even touching one.
  if (!(field.measure(a, b).obstacle_distance > 0.0)) return false;
  // In the closed wall: the segment is cut where it meets the boundary (its edges' crossings and
  // the vertices on it); each piece between two cuts lies inside, outside or on the boundary
  // throughout, and its midpoint says which.
  const Ring& ring = field.wall().boundary;
  const Point d = b - a;
  const double len2 = dot(d, d);
  const double tol2 = kValidityTolerance * kValidityTolerance;
  std::vector<double> cuts{0.0, 1.0};
  for (std::size_t i = 0, m = ring.size(); i < m; ++i) {
    const Point p = ring[i], e = ring[(i + 1) % m] - p;
    const double t = dot(p - a, d) / len2;
    if (t > 0.0 && t < 1.0 && squaredDistanceSegmentSegment(p, p, a, b) <= tol2) cuts.push_back(t);
    const double den = cross(d, e);
    if (den == 0.0) continue;
    const double s = cross(p - a, e) / den, u = cross(p - a, d) / den;
    if (s > 0.0 && s < 1.0 && u >= 0.0 && u <= 1.0) cuts.push_back(s);
  }
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (!(cuts[k + 1] > cuts[k])) continue;
    const Point mid = a + d * ((cuts[k] + cuts[k + 1]) / 2.0);
    if (!pointInRing(mid, ring) && distanceSegmentRingEdges(mid, mid, ring) > kValidityTolerance) return false;
  }
  return true;
}

double arcChords(const ArcGeometry& arc, double sagitta) {
  // Sub-arcs of angle psi have sagitta R (1 - cos(psi / 2)) <= sagitta.
  const double psi_max = 2.0 * std::acos(std::fmax(-1.0, 1.0 - sagitta / arc.radius));
  return std::ceil(std::fabs(arc.sweep) / std::fmax(psi_max, 1e-12));
}

Path chordalPath(const Path& path, double sagitta) {
  if (!path.hasArcs()) return path;
  Path out;
  if (!path.waypoints.empty()) out.moveTo(path.waypoints[0], false);
  for (std::size_t i = 0; i < path.segments(); ++i) {
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    const double bulge = path.bulgeOf(i);
    if (bulge == 0.0) {
      out.moveTo(b, path.tool_on[i]);
      continue;
    }
    const ArcGeometry g = arcGeometry(a, b, bulge);
    const auto k = static_cast<std::size_t>(arcChords(g, sagitta));
    const double start = std::atan2(a.y - g.centre.y, a.x - g.centre.x);
    for (std::size_t j = 1; j < k; ++j) {
      const double t = start + g.sweep * static_cast<double>(j) / static_cast<double>(k);
      out.moveTo(g.centre + Point{std::cos(t), std::sin(t)} * g.radius, path.tool_on[i]);
    }
    out.moveTo(b, path.tool_on[i]);
  }
  return out;
}

const Path& measuredPath(const Path& path, Path& storage) {
  if (!path.hasArcs()) return path;
  storage = chordalPath(path, kMetricArcTolerance);
  return storage;
}

namespace {

/// One end of a gantry's lifted move, waypoint k (the move before it: step -1; after it: +1): the
/// tool there inside the wall's bounding box `frame` (with both ends inside, the whole move is,
/// the box being convex). A line or rectangle tool is lifted and lowered at the heading of the
/// tool-on move it ends or begins (there its own shape must be in the box); without one it may be
/// lowered at any heading (the disk that holds it must be).
bool toolInFrame(const Path& path, const ToolParams& tool, const Box& frame, std::size_t k, int step) {
  auto inside = [&](Point q, double r) {
    return q.x - r >= frame.min_x - kValidityTolerance && q.x + r <= frame.max_x + kValidityTolerance &&
           q.y - r >= frame.min_y - kValidityTolerance && q.y + r <= frame.max_y + kValidityTolerance;
  };
  const Point p = path.waypoints[k];
  const std::size_t n = path.waypoints.size();
  if (!tool.turnsWithHeading() || (step < 0 ? k == 0 : k + 1 >= n)) return inside(p, tool.reachRadius());
  const std::size_t other = step < 0 ? k - 1 : k + 1;
  if (!path.tool_on[std::min(k, other)] || p == path.waypoints[other]) return inside(p, tool.reachRadius());
  const Point d = step < 0 ? p - path.waypoints[other] : path.waypoints[other] - p;
  const Point t = d * (1.0 / norm(d)), u{-t.y, t.x};
  for (double a : {-1.0, 1.0})
    for (double b : {-1.0, 1.0})
      if (!inside(p + u * (a * tool.radius()) + t * (b * tool.halfDepth()), 0.0)) return false;
  return true;
}

}  // namespace

Validity checkValidity(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle) {
  Validity v;
  const ClearanceField field(wall);
  // The disk that holds the tool in every heading: the tool at a point of the path (before its
  // first move, and for the lifted and depot rules), and any disk.
  const double r = tool.reachRadius();
  const std::size_t n = path.waypoints.size();
  const Box frame = boundingBox(wall.boundary);
  auto lifted = [&](std::size_t segment, Point a, Point b) {
    const bool outside = !toolInFrame(path, tool, frame, segment, -1) || !toolInFrame(path, tool, frame, segment + 1, 1);
    v.outside_boundary += outside;
    v.violations += outside;
    if (outside && v.violating.size() < kMaxListedViolations) v.violating.push_back(segment);
    if (outside && v.described.size() < kDescribedViolations) {
      Violation d;
      d.segment = segment;
      d.from = a;
      d.to = b;
      d.outside_boundary = d.lifted = true;
      v.described.push_back(d);
    }
  };
  // The gaps of segment or arc i (distances in closed form, ClearanceField::measureArc).
  // The tool disk's gaps to the boundary and to the obstacles, from its centre's distances.
  auto gaps = [&](const SegmentClearance& c) {
    return std::pair{c.inside ? c.boundary_distance - r : -c.boundary_distance - r, c.obstacle_distance - r};
  };
  // A line or rectangle tool (line_tool.hpp): the rectangle of each move it makes on the wall and
  // the turn at the move's start, from the last such move (zero-length moves skipped: they turn
  // nothing). A path that never moves has no heading: its tool must fit in every one (the disk r).
  const bool line = tool.turnsWithHeading() && std::any_of(path.waypoints.begin(), path.waypoints.end(),
                                                 [&](Point p) { return !(p == path.waypoints[0]); });
  std::optional<line_tool::Segment> heading;  // the last move on the wall
  auto lineGaps = [&](Point a, Point b) {
    const double cutoff = std::fmax(v.min_clearance, tool.clearance) + r;
    line_tool::Gaps g = line_tool::segmentGaps(field, a, b, tool.radius(), tool.halfDepth(), cutoff);
    if (heading) {
      const line_tool::Turn turn = line_tool::turnBetween(*heading, line_tool::Segment{a, b});
      if (turn.sweep != 0.0) {
        const line_tool::Gaps t = line_tool::turnGaps(field, a, turn, tool.radius(), tool.halfDepth(), cutoff);
        g.outside = g.outside || t.outside;
        g.overlaps = g.overlaps || t.overlaps;
        g.boundary = std::fmin(g.boundary, t.boundary);
        if (t.nearest >= 0 && ((t.overlaps && !g.overlaps) || t.obstacle < g.obstacle || g.nearest < 0)) g.nearest = t.nearest;
        g.obstacle = std::fmin(g.obstacle, t.obstacle);
      }
    }
    heading = line_tool::Segment{a, b};
    return g;
  };
  auto check = [&](std::size_t segment, Point a, Point b) {
    const double bulge = n > 1 ? path.bulgeOf(segment) : 0.0;
    if (line && a == b) return;  // the line there is the one the moves around it end and start with
    SegmentClearance c;
    double boundary_gap = 0.0, obstacle_gap = 0.0;
    bool line_out = false, line_overlap = false;
    if (line) {
      const line_tool::Gaps g = lineGaps(a, b);
      boundary_gap = g.boundary, obstacle_gap = g.obstacle, c.nearest_obstacle = g.nearest;
      line_out = g.outside, line_overlap = g.overlaps;
    } else {
      c = field.measureArc(a, b, bulge, std::fmax(v.min_clearance, tool.clearance) + r);
      std::tie(boundary_gap, obstacle_gap) = gaps(c);
    }
    v.min_boundary_gap = std::fmin(v.min_boundary_gap, boundary_gap);
    v.min_clearance = std::fmin(v.min_clearance, obstacle_gap);
    const bool outside = line_out || boundary_gap < -kValidityTolerance;
    const bool close = line_overlap || obstacle_gap < tool.clearance - kValidityTolerance;
    v.outside_boundary += outside;
    v.too_close += close;
    if ((outside || close) && v.violating.size() < kMaxListedViolations) v.violating.push_back(segment);
    v.violations += outside || close;
    if ((outside || close) && v.described.size() < kDescribedViolations) {
      Violation d;
      d.segment = segment;
      d.from = a;
      d.to = b;
      d.outside_boundary = outside;
      d.too_close = close;
      d.boundary_gap = line_out ? NAN : boundary_gap;  // a line's swept shape crossing the edge: no depth
      // The obstacle gap is exact when an obstacle came nearer than the cutoff (always so when
      // `close`); otherwise it is only "at least the cutoff" and not shown.
      if (c.nearest_obstacle >= 0) {
        d.clearance = line_overlap ? NAN : obstacle_gap;
        d.obstacle = c.nearest_obstacle;
        d.obstacle_label = wall.obstacles[static_cast<std::size_t>(c.nearest_obstacle)].label;
      }
      v.described.push_back(d);
    }
  };
  // Depot legs (path.hpp: depot legs): the tool-off prefix from a start outside F up to the first
  // waypoint in F, and the suffix from the last waypoint in F to an end outside F. A leg that
  // breaks the rule is checked segment by segment like any other instead.
  auto outsideF = [&](Point p) {
    const auto [boundary_gap, obstacle_gap] = gaps(field.measure(p, p, r + tool.clearance));
    return boundary_gap < -kValidityTolerance || obstacle_gap < tool.clearance - kValidityTolerance;
  };
  // The segments of the leg from waypoint `from` walking by `step` (+1 from the start, -1 from
  // the end) to the first waypoint in F; 0 when there is no such leg.
  auto depotLeg = [&](std::size_t from, long step) -> std::size_t {
    std::size_t at = from, k = 0;
    for (;;) {
      if ((step < 0 && at == 0) || (step > 0 && at + 1 >= n)) return 0;
      const std::size_t next = step > 0 ? at + 1 : at - 1, segment = std::min(at, next);
      if (path.tool_on[segment] || path.bulgeOf(segment) != 0.0 || !depotSegment(field, path.waypoints[at], path.waypoints[next]))
        return 0;
      ++k;
      at = next;
      if (!outsideF(path.waypoints[at])) return k;
    }
  };
  const std::size_t lead_in = n >= 2 && wall.start && path.waypoints.front() == *wall.start && outsideF(*wall.start) ? depotLeg(0, 1) : 0;
  const std::size_t lead_out = n >= 2 && wall.end && path.waypoints.back() == *wall.end && outsideF(*wall.end) ? depotLeg(n - 1, -1) : 0;
  v.depot_legs = static_cast<std::size_t>(lead_in > 0) + static_cast<std::size_t>(lead_out > 0);
  // Segment i lies in a depot leg (the end's leg is segments n - 1 - lead_out to n - 2).
  auto inDepotLeg = [&](std::size_t i) { return i < lead_in || i + 1 + lead_out >= n; };
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (inDepotLeg(i)) v.depot_length += distance(path.waypoints[i], path.waypoints[i + 1]);
  if (n == 1) check(0, path.waypoints[0], path.waypoints[0]);
  const bool lifts = vehicle.liftsTool();
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (inDepotLeg(i)) {
      // The leg's tool may overhang; the turn at its end in F is checked with the move after it.
      if (!(path.waypoints[i] == path.waypoints[i + 1])) heading = line_tool::Segment{path.waypoints[i], path.waypoints[i + 1]};
      continue;
    }
    else if (lifts && !path.tool_on[i]) {
      lifted(i, path.waypoints[i], path.waypoints[i + 1]);
      heading.reset();  // the tool turns lifted
    } else
      check(i, path.waypoints[i], path.waypoints[i + 1]);
  if (vehicle.isCar()) {
    std::vector<Violation> undrivable;
    checkDrivable(path, vehicle, v, undrivable);
    mergeDescribed(v, undrivable);
  }
  v.valid = v.violations == 0;
  return v;
}

std::string describeViolations(const Validity& validity, double required_clearance) {
  if (validity.valid) return std::string();
  // The opening as it always was ("1 segments" too): python/tests and users' scripts match it.
  std::string text = std::to_string(validity.violations) + " segments violate the wall or the clearance";
  std::size_t shown = 0;
  for (const Violation& d : validity.described) {
    text += shown == 0 ? ": " : "; ";
    ++shown;
    text += "segment " + std::to_string(d.segment) + " (" + num(d.from.x) + ", " + num(d.from.y) + ")->(" + num(d.to.x) +
            ", " + num(d.to.y) + ")";
    std::vector<std::string> what;
    if (d.lifted) {
      what.push_back("leaves the wall's bounding box (a lifted move)");
    } else if (d.outside_boundary && std::isnan(d.boundary_gap)) {
      what.push_back("crosses the wall's edge (the tool's swept shape)");
    } else if (d.outside_boundary) {
      what.push_back("leaves the wall's edge (gap " + shortfall(d.boundary_gap, 0.0) + ")");
    }
    if (d.too_close && std::isnan(d.clearance)) {
      const std::string name = d.obstacle_label.empty() ? "obstacles[" + std::to_string(d.obstacle) + "]"
                                                        : "obstacle \"" + d.obstacle_label + "\"";
      what.push_back("overlaps " + name + " (the tool's swept shape)");
    } else if (d.too_close) {
      const std::string name = d.obstacle_label.empty() ? "obstacles[" + std::to_string(d.obstacle) + "]"
                                                        : "obstacle \"" + d.obstacle_label + "\"";
      what.push_back(std::string(d.clearance < 0.0 ? "enters " : "comes too close to ") + name + " (clearance " +
                     shortfall(d.clearance, required_clearance) + ")");
    }
    if (d.not_drivable) what.push_back("cannot be driven by the car (an arc tighter than its turn radius, or a heading jump)");
    for (std::size_t k = 0; k < what.size(); ++k) text += (k == 0 ? " " : " and ") + what[k];
  }
  // `violations` counts a segment once for the wall and once more when a car cannot drive it.
  const std::size_t listed = std::min(validity.described.size(), validity.violations);
  if (validity.violations > listed) text += "; " + std::to_string(validity.violations - listed) + " more";
  return text;
}

Lengths pathLengths(const Path& path) {
  Lengths l;
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    const double d = path.bulge.empty() ? distance(path.waypoints[i], path.waypoints[i + 1]) : segmentLength(path, i);
    l.total += d;
    (path.tool_on[i] ? l.cover : l.transit) += d;
  }
  return l;
}

}  // namespace coverbench
