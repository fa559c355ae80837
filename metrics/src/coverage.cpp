// Coverage on polygons and pass counts on scanlines.
#include <algorithm>
#include <cmath>

#include "coverbench/metrics.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

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

CoverageRegions coverageRegions(const Wall& wall, const ToolParams& tool, const Path& path) {
  const double r = tool.radius();
  const double tol = kMetricArcTolerance;
  CoverageRegions g;
  g.reachable = offsetRegion(freeRegion(wall, tool, 0.0, tol), r, tol);
  std::vector<Ring> obstacle_rings;
  for (const Obstacle& o : wall.obstacles)
    for (const Ring& ring : allRings(obstacleRegion(o, tol))) obstacle_rings.push_back(ring);
  g.paintable = subtract(regionFromRings({wall.boundary}), regionFromRings(obstacle_rings));
  g.swept = sweptRegion(toolOnRuns(path), r, tol);
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

Coverage coverage(const Wall& wall, const ToolParams& tool, const Path& path) {
  return coverage(coverageRegions(wall, tool, path));
}

int passCount(const Path& path, double radius, Point q) {
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
void scanPasses(const Path& path, double radius, double h, Visit visit) {
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

Passes passes(const Path& path, double radius, double resolution, std::size_t bins) {
  Passes out;
  out.histogram.assign(bins, 0.0);
  const double h = resolution > 0.0 ? resolution : radius / 25.0;
  out.resolution = h;
  std::vector<double> length_with(bins + 1, 0.0);  // index = pass count (capped at bins)
  scanPasses(path, radius, h, [&](double, double x0, double x1, int count) {
    length_with[std::min<std::size_t>(static_cast<std::size_t>(count), bins)] += x1 - x0;
  });
  double swept = 0.0;
  for (std::size_t k = 1; k <= bins; ++k) swept += length_with[k] * h;
  out.swept_area_estimate = swept;
  if (swept > 0.0) {
    for (std::size_t k = 1; k <= bins; ++k) out.histogram[k - 1] = length_with[k] * h / swept;
    out.overlap = 1.0 - out.histogram[0];
  }
  return out;
}

Region overlapRegion(const Path& path, double radius, double resolution) {
  std::vector<Ring> strips;
  scanPasses(path, radius, resolution, [&](double y, double x0, double x1, int count) {
    if (count < 2) return;
    const double y0 = y - resolution / 2, y1 = y + resolution / 2;
    strips.push_back({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  });
  return regionFromRings(strips);
}

}  // namespace coverbench
