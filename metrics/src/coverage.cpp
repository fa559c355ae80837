// Coverage (R and P as polygons; S exact for a valid path, as polygons otherwise), the pass
// histogram from the exact level areas (pass_areas.cpp), and the scanline pass counts behind the
// overlap pictures.
#include <algorithm>
#include <cmath>

#include "coverbench/metrics.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/free_region.hpp"
#include "line_tool.hpp"

namespace coverbench {
namespace {

/// Maximal runs of consecutive tool-on segments, as polylines (a zero-length run is one point).
std::vector<std::vector<Point>> toolOnRuns(const Path& path) {
  std::vector<std::vector<Point>> runs;
  for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
    if (!path.tool_on[i]) continue;
    if (i == 0 || !path.tool_on[i - 1]) runs.push_back({path.waypoints[i]});
    runs.back().push_back(path.waypoints[i + 1]);
  }
  return runs;
}

/// The x-interval where the horizontal line at `y` meets the capsule of `radius` around [a, b].
bool capsuleSpan(Point a, Point b, double radius, double y, double& lo, double& hi) {
  lo = INFINITY;
  hi = -INFINITY;
  auto disk = [&](Point c) {
    const double dy = y - c.y;
    if (std::fabs(dy) > radius) return;
    const double half = std::sqrt(radius * radius - dy * dy);
    lo = std::fmin(lo, c.x - half);
    hi = std::fmax(hi, c.x + half);
  };
  disk(a);
  disk(b);
  const Point d = b - a;
  const double len = norm(d);
  if (len > 0.0) {
    // The rectangle a +- r n, b +- r n: cross the line with its four edges.
    const Point n{-d.y / len * radius, d.x / len * radius};
    const Point quad[4] = {a + n, b + n, b - n, a - n};
    for (int k = 0; k < 4; ++k) {
      const Point p = quad[k], q = quad[(k + 1) % 4];
      if ((p.y > y) == (q.y > y)) continue;
      const double x = p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y);
      lo = std::fmin(lo, x);
      hi = std::fmax(hi, x);
    }
  }
  return lo <= hi;
}

}  // namespace

namespace {

/// One polygon of F grown by r, as its outer ring grown by r and its holes shrunk by r. A point is
/// outside a polygon grown by r iff its r-disk lies in one component of the polygon's complement
/// (the disk is connected): the polygon grown is `outer` minus `holes`, which are disjoint and
/// inside it. The same region as growing F in one offset, without Clipper uniting the loops its
/// round joins throw inside the holes (2-3x faster on walls with many windows).
struct GrownPolygon {
  Region outer;
  Region holes;
};
std::vector<GrownPolygon> grownFreeRegion(const Wall& wall, const ToolParams& tool,
                                          double arc_tolerance = kMetricArcTolerance) {
  const double r = tool.radius();
  std::vector<GrownPolygon> out;
  for (const PolygonWithHoles& poly : freeRegion(wall, tool, 0.0, arc_tolerance)) {
    GrownPolygon g{offsetRegion({{poly.outer, {}}}, r, arc_tolerance), {}};
    for (const Ring& hole : poly.holes) {
      Ring inside = hole;
      std::reverse(inside.begin(), inside.end());  // the hole as a polygon of its own
      const Region shrunk = offsetRegion({{std::move(inside), {}}}, -r, arc_tolerance);
      g.holes.insert(g.holes.end(), shrunk.begin(), shrunk.end());
    }
    out.push_back(std::move(g));
  }
  return out;
}

/// R = F grown by r: the union of its polygons grown.
Region reachableRegion(std::vector<GrownPolygon> grown) {
  Region out;
  for (GrownPolygon& g : grown) {
    Region piece = g.holes.empty() ? std::move(g.outer) : subtract(g.outer, g.holes);
    out = out.empty() ? std::move(piece) : unite(out, piece);
  }
  return out;
}

/// |R| without building R: a connected F's shrunk holes are disjoint and inside its grown outer
/// ring, so their areas subtract; the pieces of a disconnected F may overlap once grown.
double reachableArea(const Wall& wall, const ToolParams& tool) {
  std::vector<GrownPolygon> grown = grownFreeRegion(wall, tool);
  if (grown.size() != 1) return area(reachableRegion(std::move(grown)));
  return area(grown[0].outer) - area(grown[0].holes);
}

/// Whether a counter-clockwise ring turns left at every vertex (strictly convex).
bool strictlyConvex(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (!(cross(ring[(i + 1) % n] - ring[i], ring[(i + 2) % n] - ring[(i + 1) % n]) > 0.0)) return false;
  return true;
}

/// An obstacle as a convex region: a counter-clockwise strictly convex ring, or a disk.
struct ConvexObstacle {
  Ring ring;  ///< empty for a disk
  Point centre{0.0, 0.0};
  double radius = 0.0;
  Box box;
  bool isDisk() const { return ring.empty(); }
  /// |O grown by g| (Steiner's formula: exact for a convex set).
  double grownArea(double g) const {
    if (isDisk()) return M_PI * (radius + g) * (radius + g);
    double perimeter = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) perimeter += distance(ring[i], ring[(i + 1) % ring.size()]);
    return signedArea(ring) + g * perimeter + M_PI * g * g;
  }
};

/// The distance between two disjoint convex obstacles, 0 if they meet.
double obstacleDistance(const ConvexObstacle& a, const ConvexObstacle& b) {
  if (a.isDisk() && b.isDisk()) return std::fmax(0.0, distance(a.centre, b.centre) - a.radius - b.radius);
  if (a.isDisk() || b.isDisk()) {
    const ConvexObstacle& disk = a.isDisk() ? a : b;
    const ConvexObstacle& poly = a.isDisk() ? b : a;
    return std::fmax(0.0, distanceSegmentFilledRing(disk.centre, disk.centre, poly.ring) - disk.radius);
  }
  double d = INFINITY;
  for (std::size_t i = 0; i < a.ring.size(); ++i)
    d = std::fmin(d, distanceSegmentFilledRing(a.ring[i], a.ring[(i + 1) % a.ring.size()], b.ring));
  // b inside a: none of a's edges comes near b, but b's vertices lie in a.
  return pointInRing(b.ring[0], a.ring) ? 0.0 : d;
}

Region paintableRegion(const Wall& wall) {
  std::vector<Ring> obstacle_rings;
  for (const Obstacle& o : wall.obstacles)
    for (const Ring& ring : allRings(obstacleRegion(o, kMetricArcTolerance))) obstacle_rings.push_back(ring);
  return subtract(regionFromRings({wall.boundary}), regionFromRings(obstacle_rings));
}

/// A line or rectangle tool's R: X, the wall minus its obstacles grown by c (docs/metrics.md#tool-shapes).
Region lineReachableRegion(const Wall& wall, const ToolParams& tool, double arc_tolerance) {
  Region grown;
  for (const Obstacle& o : wall.obstacles) {
    Region piece = obstacleRegion(o, arc_tolerance);
    if (tool.clearance > 0.0) piece = offsetRegion(piece, tool.clearance, arc_tolerance);
    grown = grown.empty() ? std::move(piece) : unite(grown, piece);
  }
  const Region wall_region = regionFromRings({wall.boundary});
  return grown.empty() ? wall_region : subtract(wall_region, grown);
}

/// |opening of B by r| = |erode(B, r)| + r perimeter(erode(B, r)) + pi r^2 for a strictly convex B
/// (Steiner's formula), if eroding B by r keeps every edge; false otherwise.
bool convexOpeningArea(const Ring& b, double r, double& out) {
  if (!strictlyConvex(b)) return false;
  const std::size_t n = b.size();
  std::vector<Point> normal(n);  // inward unit normals
  for (std::size_t i = 0; i < n; ++i) {
    const Point e = b[(i + 1) % n] - b[i];
    normal[i] = Point{-e.y, e.x} * (1.0 / norm(e));
  }
  // Vertex i of erode(B, r) is where edges i - 1 and i, each moved r inwards, meet.
  Ring eroded(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point n0 = normal[(i + n - 1) % n], n1 = normal[i];
    eroded[i] = b[i] + (n0 + n1) * (r / (1.0 + dot(n0, n1)));
  }
  double perimeter = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point e = eroded[(i + 1) % n] - eroded[i];
    if (!(dot(e, b[(i + 1) % n] - b[i]) > 0.0)) return false;  // the edge vanished or turned over
    perimeter += norm(e);
  }
  out = signedArea(eroded) + r * perimeter + M_PI * r * r;
  return true;
}

/// Whether a convex obstacle lies inside B at least `depth` from its boundary.
bool deepInside(const ConvexObstacle& q, const Ring& boundary, double depth) {
  const Point probe = q.isDisk() ? q.centre : q.ring[0];
  if (!pointInRing(probe, boundary)) return false;
  if (q.isDisk()) return distanceSegmentRingEdges(q.centre, q.centre, boundary) - q.radius >= depth;
  for (std::size_t i = 0; i < q.ring.size(); ++i)
    if (!(distanceSegmentRingEdges(q.ring[i], q.ring[(i + 1) % q.ring.size()], boundary) >= depth)) return false;
  return true;
}

}  // namespace

/// Why the closed forms hold (the header says when they apply). R is the wall B
/// minus the obstacles dilated by c (X), opened by the tool disk. An obstacle O apart from the rest
/// changes R by exactly Q = O dilated by c, which lies inside the opening of the rest: a point
/// outside Q within 2 r of it is in the tool disk touching Q from outside at Q's point nearest to it
/// (that disk stays in B and clear of the other obstacles); a point farther is in a disk of the
/// rest's opening that keeps clear of Q; and the disk around any point of Q is in B and clear of
/// the other obstacles. So |R| = |R without those obstacles| - sum |Q| and, as they are disjoint
/// and inside B, |P| = |P without them| - sum |O|, with |Q| = |O| + c perimeter(O) + pi c^2
/// (Steiner's formula for convex sets). On a wall of many windows this skips the offsets of all
/// their rounded corners, most of the cost of scoring before.
RegionAreas regionAreas(const Wall& wall, const ToolParams& tool) {
  constexpr double kSpare = 1e-9;
  const double r = tool.radius(), c = tool.clearance;
  const std::size_t n = wall.obstacles.size();
  std::vector<ConvexObstacle> convex(n);
  std::vector<bool> is_convex(n, false), apart(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    const Obstacle& o = wall.obstacles[k];
    ConvexObstacle& q = convex[k];
    if (o.type == ObstacleType::Circle) {
      q.centre = o.center, q.radius = o.radius;
      q.box = {o.center.x - o.radius, o.center.y - o.radius, o.center.x + o.radius, o.center.y + o.radius};
      is_convex[k] = o.radius > 0.0;
    } else {
      q.ring = o.polygon;
      if (signedArea(q.ring) < 0.0) std::reverse(q.ring.begin(), q.ring.end());
      q.box = boundingBox(q.ring);
      is_convex[k] = strictlyConvex(q.ring);
    }
    apart[k] = is_convex[k] && deepInside(q, wall.boundary, 2.0 * r + c + kSpare);
  }
  // An obstacle nearer than 2 (r + c) to any other is not apart. Only pairs whose boxes come that
  // near are measured (a sweep over the boxes' left ends); a pair with an obstacle that is not
  // convex is near if its boxes are.
  const double gap = 2.0 * (r + c) + kSpare;
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return convex[x].box.min_x < convex[y].box.min_x; });
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n && convex[order[j]].box.min_x < convex[order[i]].box.max_x + gap; ++j) {
      const std::size_t x = order[i], y = order[j];
      if ((!apart[x] && !apart[y]) || boxDistance(convex[x].box, convex[y].box) >= gap) continue;
      if (is_convex[x] && is_convex[y] && obstacleDistance(convex[x], convex[y]) >= gap) continue;
      apart[x] = apart[y] = false;
    }
  Wall rest = wall;
  rest.obstacles.clear();
  double apart_reachable = 0.0, apart_paintable = 0.0;
  RegionAreas out;
  for (std::size_t k = 0; k < n; ++k) {
    if (!apart[k]) {
      rest.obstacles.push_back(wall.obstacles[k]);
      continue;
    }
    apart_reachable += convex[k].grownArea(c);
    apart_paintable += convex[k].grownArea(0.0);
    ++out.obstacles_in_closed_form;
  }
  out.wall_in_closed_form = rest.obstacles.empty() && convexOpeningArea(rest.boundary, r, out.reachable);
  if (!out.wall_in_closed_form) out.reachable = reachableArea(rest, tool);
  out.paintable = rest.obstacles.empty() ? signedArea(rest.boundary) : area(paintableRegion(rest));
  out.reachable -= apart_reachable;
  out.paintable -= apart_paintable;
  return out;
}

Region reachableRegion(const Wall& wall, const ToolParams& tool, double arc_tolerance) {
  if (tool.turnsWithHeading()) return lineReachableRegion(wall, tool, arc_tolerance);
  return reachableRegion(grownFreeRegion(wall, tool, arc_tolerance));
}

namespace {

bool sameShape(const Wall& a, const Wall& b) {
  if (a.boundary != b.boundary || a.obstacles.size() != b.obstacles.size()) return false;
  for (std::size_t k = 0; k < a.obstacles.size(); ++k) {
    const Obstacle &x = a.obstacles[k], &y = b.obstacles[k];
    if (x.type != y.type || x.polygon != y.polygon || !(x.center == y.center) || x.radius != y.radius) return false;
  }
  return true;
}

/// regionAreas of the last two walls scored on this thread: an experiment scores every planner's
/// path on a wall in turn (two workers share a wall's runs), and R's and P's areas depend only on
/// the wall's shape, r and c. The same values as computing them again, bit for bit.
RegionAreas recentRegionAreas(const Wall& wall, const ToolParams& tool) {
  struct Entry {
    Wall wall;
    double width = 0.0, clearance = 0.0;
    RegionAreas areas;
  };
  thread_local std::vector<Entry> recent;
  for (const Entry& e : recent)
    if (e.width == tool.tool_width && e.clearance == tool.clearance && sameShape(e.wall, wall)) return e.areas;
  Entry e{wall, tool.tool_width, tool.clearance, regionAreas(wall, tool)};
  e.wall.name.clear();
  if (recent.size() == 2) recent.erase(recent.begin());
  recent.push_back(std::move(e));
  return recent.back().areas;
}

}  // namespace

CoverageRegions coverageRegions(const Wall& wall, const ToolParams& tool, const Path& path) {
  CoverageRegions g;
  if (tool.turnsWithHeading()) {
    g.reachable = lineReachableRegion(wall, tool, kMetricArcTolerance);
    g.paintable = paintableRegion(wall);
    g.swept = coveredAtLeast(line_tool::sweptRings(path, tool.radius(), tool.halfDepth()), 1);
    return g;
  }
  g.reachable = reachableRegion(grownFreeRegion(wall, tool));
  g.paintable = paintableRegion(wall);
  Path chords;
  g.swept = sweptRegion(toolOnRuns(measuredPath(path, chords)), tool.radius(), kMetricArcTolerance);
  return g;
}

Coverage coverage(const CoverageRegions& g) {
  Coverage c;
  c.reachable_area = area(g.reachable);
  c.paintable_area = area(g.paintable);
  c.swept_area = area(g.swept);
  c.coverage_reachable = c.reachable_area > 0 ? area(intersect(g.swept, g.reachable)) / c.reachable_area : 0.0;
  c.coverage_wall = c.paintable_area > 0 ? area(intersect(g.swept, g.paintable)) / c.paintable_area : 0.0;
  return c;
}

Coverage coverage(const Wall& wall, const ToolParams& tool, const Path& path, const Validity& validity,
                  double swept_area) {
  if (!validity.valid) return coverage(coverageRegions(wall, tool, path));
  if (tool.turnsWithHeading()) {  // S lies in R and in P, as for a disk: their areas, and S's from the pass levels
    Coverage c;
    c.reachable_area = area(lineReachableRegion(wall, tool, kMetricArcTolerance));
    c.paintable_area = recentRegionAreas(wall, tool).paintable;
    c.swept_area = swept_area;
    c.coverage_reachable = c.reachable_area > 0 ? std::fmin(1.0, swept_area / c.reachable_area) : 0.0;
    c.coverage_wall = c.paintable_area > 0 ? std::fmin(1.0, swept_area / c.paintable_area) : 0.0;
    return c;
  }
  // Every segment keeps its tool disk inside the wall and c away from the obstacles (to 1e-9 m), so
  // S lies in R and in P: both intersections are S itself, whose area is exact.
  Coverage c;
  const RegionAreas areas = recentRegionAreas(wall, tool);
  c.reachable_area = areas.reachable;
  c.paintable_area = areas.paintable;
  c.swept_area = swept_area;
  // R's and P's arcs are chords (50 um): a path covering all of R may measure a hair over it.
  c.coverage_reachable = c.reachable_area > 0 ? std::fmin(1.0, swept_area / c.reachable_area) : 0.0;
  c.coverage_wall = c.paintable_area > 0 ? std::fmin(1.0, swept_area / c.paintable_area) : 0.0;
  return c;
}

Coverage coverage(const Wall& wall, const ToolParams& tool, const Path& path) {
  if (tool.turnsWithHeading()) return coverage(coverageRegions(wall, tool, path));
  return coverage(wall, tool, path, checkValidity(wall, tool, path), passLevelAreas(path, tool.radius(), 1)[0]);
}

int passCount(const Path& in, double radius, Point q) {
  Path chords;
  const Path& path = measuredPath(in, chords);
  int count = 0;
  for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
    if (!path.tool_on[i]) continue;
    if (distancePointSegment(q, path.waypoints[i], path.waypoints[i + 1]) > radius) continue;
    const bool continues = i > 0 && path.tool_on[i - 1] && distance(q, path.waypoints[i]) <= radius;
    if (!continues) ++count;
  }
  return count;
}

namespace {

/// Walks horizontal scanlines `h` apart over the path's tool-on capsules and reports, for every
/// maximal x-interval of constant pass count > 0, (y, x0, x1, count).
template <class Visit>
void scanPasses(const Path& in, double radius, double h, Visit visit) {
  Path chords;
  const Path& path = measuredPath(in, chords);
  // passes(q) = #(tool-on capsules containing q) - #(continuation disks containing q), where a
  // continuation disk sits at each waypoint joining two tool-on segments.
  struct Shape {
    Point a, b;
    int weight;
  };
  std::vector<Shape> shapes;
  double y_min = INFINITY, y_max = -INFINITY;
  for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
    if (!path.tool_on[i]) continue;
    shapes.push_back({path.waypoints[i], path.waypoints[i + 1], +1});
    if (i > 0 && path.tool_on[i - 1]) shapes.push_back({path.waypoints[i], path.waypoints[i], -1});
    y_min = std::fmin(y_min, std::fmin(path.waypoints[i].y, path.waypoints[i + 1].y) - radius);
    y_max = std::fmax(y_max, std::fmax(path.waypoints[i].y, path.waypoints[i + 1].y) + radius);
  }
  if (shapes.empty()) return;
  const auto rows = static_cast<std::size_t>(std::ceil((y_max - y_min) / h));
  // Bucket shapes by the scanlines they span.
  std::vector<std::vector<std::uint32_t>> by_row(rows);
  for (std::uint32_t k = 0; k < shapes.size(); ++k) {
    const Shape& s = shapes[k];
    const double lo = std::fmin(s.a.y, s.b.y) - radius, hi = std::fmax(s.a.y, s.b.y) + radius;
    const auto first = static_cast<std::size_t>(std::max(0.0, std::floor((lo - y_min) / h - 0.5)));
    for (std::size_t row = first; row < rows && y_min + (static_cast<double>(row) + 0.5) * h <= hi; ++row)
      by_row[row].push_back(k);
  }
  std::vector<std::pair<double, int>> events;
  for (std::size_t row = 0; row < rows; ++row) {
    const double y = y_min + (static_cast<double>(row) + 0.5) * h;
    events.clear();
    for (std::uint32_t k : by_row[row]) {
      double lo, hi;
      if (!capsuleSpan(shapes[k].a, shapes[k].b, radius, y, lo, hi)) continue;
      events.push_back({lo, shapes[k].weight});
      events.push_back({hi, -shapes[k].weight});
    }
    std::sort(events.begin(), events.end());
    int count = 0;
    for (std::size_t e = 0; e + 1 < events.size(); ++e) {
      count += events[e].second;
      if (count > 0 && events[e + 1].first > events[e].first) visit(y, events[e].first, events[e + 1].first, count);
    }
  }
}

}  // namespace

Passes passesOnScanlines(const Path& path, double radius, double resolution, std::size_t bins) {
  Passes out;
  out.histogram.assign(bins, 0.0);
  std::vector<double> length_with(bins + 1, 0.0);  // index = pass count (capped at bins)
  scanPasses(path, radius, resolution, [&](double, double x0, double x1, int count) {
    length_with[std::min<std::size_t>(static_cast<std::size_t>(count), bins)] += x1 - x0;
  });
  for (std::size_t k = 1; k <= bins; ++k) out.swept_area += length_with[k] * resolution;
  if (out.swept_area > 0.0) {
    for (std::size_t k = 1; k <= bins; ++k) out.histogram[k - 1] = length_with[k] * resolution / out.swept_area;
    out.overlap = 1.0 - out.histogram[0];
  }
  return out;
}

namespace {

/// The pass histogram and overlap from the areas |{passes >= k}|, k = 1 .. bins.
Passes passesFromLevels(const std::vector<double>& at_least) {
  const std::size_t bins = at_least.size();
  Passes out;
  out.histogram.assign(bins, 0.0);
  out.swept_area = bins > 0 ? at_least[0] : 0.0;
  if (out.swept_area > 0.0) {
    for (std::size_t k = 0; k < bins; ++k)
      out.histogram[k] = (at_least[k] - (k + 1 < bins ? at_least[k + 1] : 0.0)) / out.swept_area;
    out.overlap = bins > 1 ? at_least[1] / out.swept_area : 0.0;
  }
  return out;
}

}  // namespace

Passes passes(const Path& path, double radius, std::size_t bins) {
  return passesFromLevels(passLevelAreas(path, radius, bins));
}

Passes passes(const Path& path, const ToolParams& tool, std::size_t bins) {
  if (!tool.turnsWithHeading()) return passes(path, tool.radius(), bins);
  // The line's swept shapes as polygons: |{passes >= k}| from one union a level.
  const std::vector<Ring> rings = line_tool::sweptRings(path, tool.radius(), tool.halfDepth());
  std::vector<double> at_least(bins, 0.0);
  for (std::size_t k = 0; k < bins; ++k) {
    at_least[k] = coveredAtLeastArea(rings, static_cast<int>(k + 1));
    if (at_least[k] == 0.0) break;
  }
  return passesFromLevels(at_least);
}

Region passRegion(const Path& path, const ToolParams& tool, double resolution, int min_passes) {
  if (tool.turnsWithHeading()) return coveredAtLeast(line_tool::sweptRings(path, tool.radius(), tool.halfDepth()), min_passes);
  return passRegion(path, tool.radius(), resolution, min_passes);
}

Region overlapRegion(const Path& path, double radius, double resolution) { return passRegion(path, radius, resolution, 2); }

Region passRegion(const Path& path, double radius, double resolution, int min_passes) {
  // Strips one scanline high where passes >= min_passes, stacked into staircase polygons: a stack grows
  // while its strip in the previous row overlaps exactly one strip in this row and vice versa.
  // The polygons do not overlap, so no union (which is quadratic in Clipper for many strips).
  struct Strip {
    double x0, x1;
  };
  struct Stack {
    double y0;                // bottom of the first strip
    std::vector<Strip> rows;  // one strip per row, bottom to top
  };
  Region out;
  auto close = [&](const Stack& st) {
    Ring ring;
    auto y = [&](std::size_t k) { return st.y0 + static_cast<double>(k) * resolution; };
    for (std::size_t k = 0; k < st.rows.size(); ++k) {  // left side, upwards
      ring.push_back({st.rows[k].x0, y(k)});
      ring.push_back({st.rows[k].x0, y(k + 1)});
    }
    for (std::size_t k = st.rows.size(); k-- > 0;) {  // right side, downwards
      ring.push_back({st.rows[k].x1, y(k + 1)});
      ring.push_back({st.rows[k].x1, y(k)});
    }
    // Drop repeated points and the middle of straight runs (rows sharing an x).
    auto straight = [](Point a, Point b, Point c) { return (a.x == b.x && b.x == c.x) || (a.y == b.y && b.y == c.y); };
    Ring clean;
    for (const Point& p : ring) {
      if (!clean.empty() && clean.back() == p) continue;
      if (clean.size() >= 2 && straight(clean[clean.size() - 2], clean.back(), p)) clean.back() = p;
      else clean.push_back(p);
    }
    while (clean.size() >= 3 && straight(clean[clean.size() - 2], clean.back(), clean[0])) clean.pop_back();
    PolygonWithHoles poly;
    poly.outer = std::move(clean);
    out.push_back(std::move(poly));
  };
  std::vector<Stack> open;  // stacks whose top strip is in row `last_y`, in x order
  std::vector<Strip> row;   // the strips of row `row_y`, in x order
  double row_y = NAN, last_y = NAN;
  auto overlaps = [](const Strip& a, const Strip& b) { return a.x0 < b.x1 && b.x0 < a.x1; };
  auto finishRow = [&] {
    if (!(row_y - last_y < 1.5 * resolution)) {  // a gap of empty rows ends every stack
      for (const Stack& st : open) close(st);
      open.clear();
    }
    // How many strips each stack touches and how many stacks each strip touches.
    std::vector<Strip> tops;
    for (const Stack& st : open) tops.push_back(st.rows.back());
    std::vector<int> stack_hits(open.size(), 0), strip_hits(row.size(), 0);
    for (std::size_t i = 0, first = 0; i < row.size(); ++i) {
      while (first < tops.size() && tops[first].x1 <= row[i].x0) ++first;
      for (std::size_t m = first; m < tops.size() && tops[m].x0 < row[i].x1; ++m)
        if (overlaps(tops[m], row[i])) ++stack_hits[m], ++strip_hits[i];
    }
    std::vector<Stack> next;
    for (std::size_t i = 0, m = 0; i < row.size(); ++i) {
      while (m < open.size() && tops[m].x1 <= row[i].x0) ++m;
      bool extended = false;
      if (strip_hits[i] == 1)
        for (std::size_t q = m; q < open.size() && tops[q].x0 < row[i].x1; ++q)
          if (overlaps(tops[q], row[i]) && stack_hits[q] == 1) {
            open[q].rows.push_back(row[i]);
            next.push_back(std::move(open[q]));
            stack_hits[q] = -1;  // moved
            extended = true;
          }
      if (!extended) next.push_back({row_y - resolution / 2, {row[i]}});
    }
    for (std::size_t m = 0; m < open.size(); ++m)
      if (stack_hits[m] != -1) close(open[m]);
    open = std::move(next);
    last_y = row_y;
    row.clear();
  };
  scanPasses(path, radius, resolution, [&](double y, double x0, double x1, int count) {
    if (count < min_passes || x1 - x0 < 1e-9) return;  // rounding slivers are not drawn
    if (y != row_y) {
      if (!std::isnan(row_y)) finishRow();
      row_y = y;
    }
    if (!row.empty() && row.back().x1 >= x0) row.back().x1 = std::fmax(row.back().x1, x1);
    else row.push_back({x0, x1});
  });
  if (!std::isnan(row_y)) finishRow();
  for (const Stack& st : open) close(st);
  return out;
}

}  // namespace coverbench
