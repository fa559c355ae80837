// Certified areas: inscribed and circumscribed polygons for every disk, exact Boolean operations
// (CGAL's Polygon_set_2 on the exact kernel), exact rational areas.
//
// Every region is monotone in the disks it is built from, so building it once with the inscribed
// polygons and once with the circumscribed ones brackets it:
//   S = union of [a, b] (+) D_r over tool-on segments
//   F = (B minus (dB (+) D_r)) minus (O (+) D_{r+c}),  with O (+) D = O union (dO (+) D)
//   R = F (+) D_r = F union (dF (+) D_r)
//   P = B minus O
// (X (+) D is the Minkowski sum; a segment's sum with a convex polygon is the convex hull of the
// polygon placed at both ends.) F shrinks as D grows, so F's lower bound uses the circumscribed
// polygons and R's lower bound uses F's lower bound with the inscribed polygon.
#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/convex_hull_2.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "coverbench/judge.hpp"
#include "exact_arcs.hpp"
#include "exact_line.hpp"
#include "exact_kernel.hpp"

namespace coverbench::judge {
namespace {

using Polygon = CGAL::Polygon_2<K>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<K>;
using PolygonSet = CGAL::Polygon_set_2<K>;

enum class Side { Inner, Outer };

/// A convex polygon centred on the origin that lies inside (Inner) or contains (Outer) the disk of
/// radius rho, with `n` vertices, symmetric about the origin. Checked exactly.
std::vector<V2> diskPolygon(double rho, int n, Side side) {
  const double pi = std::acos(-1.0);
  // Inner: vertices on the circle, pulled in by 1e-12; outer: vertices at rho / cos(pi / n)
  // (where the tangents at the inner vertices' angles shifted by half a step meet), pushed out by
  // 1e-12. The slack is far above double rounding, and the exact checks below prove the result.
  const double step = 2.0 * pi / n;
  const double scale = side == Side::Inner ? rho * (1.0 - 1e-12) : rho / std::cos(pi / n) * (1.0 + 1e-12);
  const double phase = side == Side::Inner ? 0.0 : step / 2.0;
  std::vector<double> xs, ys;
  for (int k = 0; k < n / 2; ++k) {
    xs.push_back(scale * std::cos(phase + step * k));
    ys.push_back(scale * std::sin(phase + step * k));
  }
  std::vector<V2> poly;
  for (int k = 0; k < n / 2; ++k) poly.emplace_back(xs[k], ys[k]);
  for (int k = 0; k < n / 2; ++k) poly.emplace_back(-xs[k], -ys[k]);
  const FT rho2 = FT(rho) * FT(rho);
  const P2 origin = CGAL::ORIGIN;
  for (int k = 0; k < n; ++k) {
    const V2& p = poly[k];
    const V2& q = poly[(k + 1) % n];
    bool ok;
    if (side == Side::Inner) {
      ok = p.squared_length() <= rho2;
    } else {
      ok = CGAL::squared_distance(origin, K::Line_2(origin + p, origin + q)) >= rho2;
    }
    if (!ok) throw std::logic_error("judge: a disk polygon failed its exact containment check");
  }
  return poly;
}

Polygon hullAt(const P2& a, const P2& b, const std::vector<V2>& disk) {
  std::vector<P2> points;
  points.reserve(disk.size() * 2);
  for (const V2& d : disk) points.push_back(a + d);
  if (a != b)
    for (const V2& d : disk) points.push_back(b + d);
  std::vector<P2> hull;
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull));
  return Polygon(hull.begin(), hull.end());
}

Polygon polygonOf(const Ring& ring) {
  Polygon p;
  for (Point q : ring) p.push_back(exactPoint(q));
  if (p.is_clockwise_oriented()) p.reverse_orientation();
  return p;
}

PolygonSet unionOf(const std::vector<Polygon>& pieces) {
  PolygonSet set;
  if (!pieces.empty()) set.join(pieces.begin(), pieces.end());
  return set;
}

FT areaOf(const PolygonSet& set) {
  std::vector<PolygonWithHoles> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  FT total = 0;
  for (const PolygonWithHoles& p : parts) {
    if (!p.is_unbounded()) total += p.outer_boundary().area();
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) total += h->area();  // negative
  }
  return total;
}

/// Hulls of every edge of every boundary curve of `set`, with `disk`: set's boundary (+) disk.
std::vector<Polygon> boundaryHulls(const PolygonSet& set, const std::vector<V2>& disk) {
  std::vector<Polygon> hulls;
  std::vector<PolygonWithHoles> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  auto ring = [&](const Polygon& p) {
    for (auto e = p.edges_begin(); e != p.edges_end(); ++e) hulls.push_back(hullAt(e->source(), e->target(), disk));
  };
  for (const PolygonWithHoles& p : parts) {
    ring(p.outer_boundary());
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) ring(*h);
  }
  return hulls;
}
std::vector<Polygon> ringHulls(const Ring& ring, const std::vector<V2>& disk) {
  std::vector<Polygon> hulls;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point a = ring[i], b = ring[(i + 1) % ring.size()];
    hulls.push_back(hullAt(exactPoint(a), exactPoint(b), disk));
  }
  return hulls;
}

/// The regions built with one side's disk polygons.
struct Regions {
  PolygonSet reachable, paintable, swept;
};

Polygon polygonOf(const std::vector<P2>& points) { return Polygon(points.begin(), points.end()); }

/// What a line or rectangle tool sweeps with the tool on (exact_line.hpp), on `side`: each tool-on
/// move's rectangle and the sectors of each turn between two tool-on moves (zero-length moves
/// skipped), the sectors' arcs as chords of about kArcCoverageSagitta.
std::vector<Polygon> lineSwept(const ToolParams& tool, const Path& path, Side side) {
  const bool outer = side == Side::Outer;
  const ExactShape shape(tool);
  const double reach = shape.reach();
  const FT reach2 = shape.reach2();
  std::vector<Polygon> pieces;
  std::optional<V2> heading;
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    if (!path.tool_on[i]) {
      heading.reset();
      continue;
    }
    const P2 a = exactPoint(path.waypoints[i]), b = exactPoint(path.waypoints[i + 1]);
    if (a == b) continue;
    if (heading) {
      const ExactTurn t = exactTurn(*heading, b - a);
      for (const ExactTurn& corner : t.turns ? cornerTurns(t, shape) : std::vector<ExactTurn>{})
        for (int s = 1; s >= -1; s -= 2) {
          const std::vector<Triangle> fan = sectorFan(a, corner, reach, reach2, std::fmin(kArcCoverageSagitta, reach / 2.0), outer, s);
          if (fan.empty()) throw std::logic_error(std::string("judge: a ") + (tool.isLine() ? "line" : "rectangle") + " tool's turn has no certified fan");
          for (const Triangle& tri : fan) pieces.push_back(Polygon(tri.begin(), tri.end()));
        }
    }
    pieces.push_back(polygonOf(lineRectangle(a, b, shape, outer)));
    heading = b - a;
  }
  return pieces;
}

Regions buildRegions(const Wall& wall, const ToolParams& tool, const Path& path, int n, Side side) {
  // A line or rectangle tool reaches X, the wall minus its obstacles grown by c (docs/metrics.md#tool-shapes):
  // F's construction with the tool's own radius 0.
  const double r = tool.turnsWithHeading() ? 0.0 : tool.radius();
  // F is built with the opposite side's polygons (it shrinks as the disks grow).
  const Side f_side = side == Side::Inner ? Side::Outer : Side::Inner;
  const std::vector<V2> tool_disk = r > 0.0 ? diskPolygon(r, n, side) : std::vector<V2>{};
  const std::vector<V2> f_tool_disk = r > 0.0 ? diskPolygon(r, n, f_side) : std::vector<V2>{};
  const std::vector<V2> f_clear_disk = r + tool.clearance > 0.0 ? diskPolygon(r + tool.clearance, n, f_side) : std::vector<V2>{};
  Regions g;

  const PolygonSet wall_set(polygonOf(wall.boundary));
  PolygonSet obstacles;
  std::vector<Polygon> grown_pieces;
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle) {
      const P2 centre = exactPoint(o.center);
      // P, like F, shrinks as its obstacles grow: their polygons are on F's side too.
      obstacles.join(hullAt(centre, centre, diskPolygon(o.radius, n, f_side)));
      // The grown disk of radius rho + r + c, on F's side.
      grown_pieces.push_back(hullAt(centre, centre, diskPolygon(o.radius + r + tool.clearance, n, f_side)));
    } else {
      const Polygon p = polygonOf(o.polygon);
      obstacles.join(p);
      grown_pieces.push_back(p);
      if (!f_clear_disk.empty())
        for (Polygon& h : ringHulls(o.polygon, f_clear_disk)) grown_pieces.push_back(std::move(h));
    }
  }
  const PolygonSet obstacles_grown = unionOf(grown_pieces);

  g.paintable = wall_set;
  g.paintable.difference(obstacles);

  PolygonSet free_region = wall_set;
  if (r > 0.0) free_region.difference(unionOf(ringHulls(wall.boundary, f_tool_disk)));
  free_region.difference(obstacles_grown);
  std::vector<Polygon> reach = r > 0.0 ? boundaryHulls(free_region, tool_disk) : std::vector<Polygon>{};
  g.reachable = free_region;
  if (!reach.empty()) g.reachable.join(unionOf(reach));
  if (tool.turnsWithHeading()) {
    g.swept = unionOf(lineSwept(tool, path, side));
    return g;
  }

  std::vector<Polygon> capsules;
  for (std::size_t i = 0; i < path.tool_on.size(); ++i) {
    if (!path.tool_on[i]) continue;
    const Point a = path.waypoints[i], b = path.waypoints[i + 1];
    const double bulge = path.bulge.empty() ? 0.0 : path.bulge[i];
    if (bulge == 0.0) {
      capsules.push_back(hullAt(exactPoint(a), exactPoint(b), tool_disk));
      continue;
    }
    // An arc: its chords, swept by a disk shrunk (inner) or grown (outer) by the arc's certified
    // stray from them, enclose what the disk sweeps along the arc from inside and outside.
    const ExactArc arc = exactArc(a, b, bulge, kArcCoverageSagitta);
    if (!arc.ordered) throw std::logic_error("judge: an arc of more than a half circle in one segment");
    const double stray = CGAL::to_interval(arc.stray).second;
    const double radius = side == Side::Inner ? std::nextafter(r - stray, 0.0) : std::nextafter(r + stray, INFINITY);
    const std::vector<V2> disk = diskPolygon(std::fmax(radius, 0.0), n, side);
    for (std::size_t k = 0; k + 1 < arc.points.size(); ++k) capsules.push_back(hullAt(arc.points[k], arc.points[k + 1], disk));
  }
  g.swept = unionOf(capsules);
  return g;
}

FT intersectionArea(const PolygonSet& a, const PolygonSet& b) {
  PolygonSet x = a;
  x.intersection(b);
  return areaOf(x);
}

/// Certified bounds of lo / hi (0 when the denominator is 0), clipped to [0, 1].
Interval ratio(const FT& num_lo, const FT& den_hi, const FT& num_hi, const FT& den_lo) {
  Interval i;
  i.lower = den_hi > 0 ? CGAL::to_interval(num_lo / den_hi).first : 0.0;
  i.upper = den_lo > 0 ? std::fmin(1.0, CGAL::to_interval(num_hi / den_lo).second) : 1.0;
  i.lower = std::fmax(0.0, std::fmin(i.lower, 1.0));
  return i;
}
Interval between(const FT& lo, const FT& hi) { return {CGAL::to_interval(lo).first, CGAL::to_interval(hi).second}; }

}  // namespace

ExactCoverage judgeCoverage(const Wall& wall, const ToolParams& tool, const Path& path,
                            const CoverageOptions& options) {
  if (options.arc_vertices < 8 || options.arc_vertices % 8 != 0)
    throw std::invalid_argument("judge: arc_vertices must be a multiple of 8, at least 8");
  const int n = options.arc_vertices;
  const Regions in = buildRegions(wall, tool, path, n, Side::Inner);
  const Regions out = buildRegions(wall, tool, path, n, Side::Outer);
  const FT r_lo = areaOf(in.reachable), r_hi = areaOf(out.reachable);
  const FT p_lo = areaOf(in.paintable), p_hi = areaOf(out.paintable);
  const FT s_lo = areaOf(in.swept), s_hi = areaOf(out.swept);
  ExactCoverage c;
  c.arc_vertices = n;
  c.reachable_area = between(r_lo, r_hi);
  c.paintable_area = between(p_lo, p_hi);
  c.swept_area = between(s_lo, s_hi);
  c.coverage_reachable = ratio(intersectionArea(in.swept, in.reachable), r_hi,
                               intersectionArea(out.swept, out.reachable), r_lo);
  c.coverage_wall = ratio(intersectionArea(in.swept, in.paintable), p_hi,
                          intersectionArea(out.swept, out.paintable), p_lo);
  return c;
}

}  // namespace coverbench::judge
