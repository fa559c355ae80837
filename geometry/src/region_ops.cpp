#include "coverbench/region_ops.hpp"

#include <clipper.hpp>

#include <algorithm>
#include <cmath>

namespace coverbench {
namespace {

namespace cl = ClipperLib;
constexpr double kScale = 1.0 / kRegionResolution;

cl::IntPoint toInt(Point p) {
  return {static_cast<cl::cInt>(std::llround(p.x * kScale)),
          static_cast<cl::cInt>(std::llround(p.y * kScale))};
}
Point toPoint(const cl::IntPoint& p) {
  return {static_cast<double>(p.X) / kScale, static_cast<double>(p.Y) / kScale};
}

cl::Path toPath(const Ring& ring) {
  cl::Path path;
  path.reserve(ring.size());
  for (const Point& p : ring) path.push_back(toInt(p));
  return path;
}

Ring toRing(const cl::Path& path) {
  Ring ring;
  ring.reserve(path.size());
  for (const cl::IntPoint& p : path) ring.push_back(toPoint(p));
  return ring;
}

cl::Paths toPaths(const Region& region) {
  cl::Paths paths;
  for (const PolygonWithHoles& poly : region) {
    paths.push_back(toPath(poly.outer));
    for (const Ring& hole : poly.holes) paths.push_back(toPath(hole));
  }
  return paths;
}

void collect(const cl::PolyNode& node, Region& out) {
  // `node` is an outer ring; its children are holes, their children outer rings again.
  PolygonWithHoles poly;
  poly.outer = toRing(node.Contour);
  if (signedArea(poly.outer) < 0) std::reverse(poly.outer.begin(), poly.outer.end());
  for (const cl::PolyNode* hole : node.Childs) {
    Ring h = toRing(hole->Contour);
    if (signedArea(h) > 0) std::reverse(h.begin(), h.end());
    poly.holes.push_back(std::move(h));
  }
  out.push_back(std::move(poly));
  for (const cl::PolyNode* hole : node.Childs)
    for (const cl::PolyNode* island : hole->Childs) collect(*island, out);
}

Region fromTree(const cl::PolyTree& tree) {
  Region out;
  for (const cl::PolyNode* node : tree.Childs) collect(*node, out);
  return out;
}

/// Adds each ring turned counter-clockwise (for a non-zero union of rings of any orientation).
void addCounterClockwise(cl::Clipper& clipper, const std::vector<Ring>& rings, cl::PolyType type) {
  for (const Ring& ring : rings) {
    cl::Path path = toPath(ring);
    if (!cl::Orientation(path)) cl::ReversePath(path);
    clipper.AddPath(path, type, true);
  }
}

Region boolean(const Region& a, const Region& b, cl::ClipType type) {
  cl::Clipper clipper;
  clipper.AddPaths(toPaths(a), cl::ptSubject, true);
  clipper.AddPaths(toPaths(b), cl::ptClip, true);
  cl::PolyTree tree;
  clipper.Execute(type, tree, cl::pftNonZero, cl::pftNonZero);
  return fromTree(tree);
}

}  // namespace

std::vector<Ring> allRings(const Region& region) {
  std::vector<Ring> rings;
  for (const PolygonWithHoles& poly : region) {
    rings.push_back(poly.outer);
    for (const Ring& hole : poly.holes) rings.push_back(hole);
  }
  return rings;
}

std::vector<std::vector<RingCrossing>> scanlineCrossings(const std::vector<Ring>& rings, const std::vector<double>& ys) {
  std::vector<std::vector<RingCrossing>> out(ys.size());
  if (ys.empty()) return out;
  const double y0 = ys.front();
  const double dy = ys.size() > 1 ? ys[1] - ys[0] : 1.0;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    const Ring& ring = rings[r];
    for (std::size_t e = 0; e < ring.size(); ++e) {
      const Point a = ring[e], b = ring[(e + 1) % ring.size()];
      if (a.y == b.y) continue;
      const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
      // Lines from one step below `lo` on (the division may round either way) while below hi.
      const long first = std::max(static_cast<long>(std::floor((lo - y0) / dy)) - 1, 0L);
      for (auto i = static_cast<std::size_t>(first); i < ys.size() && ys[i] < hi + dy; ++i) {
        const double y = ys[i];
        if ((a.y > y) == (b.y > y)) continue;
        out[i].push_back({a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y), r, e});
      }
    }
  }
  for (auto& line : out)
    std::sort(line.begin(), line.end(), [](const RingCrossing& p, const RingCrossing& q) { return p.x < q.x; });
  return out;
}

Region offsetRegion(const Region& region, double delta, double arc_tolerance) {
  if (region.empty()) return {};
  cl::ClipperOffset offset;
  // Clipper rounds the number of arc steps, so its last chord on an arc can span up to 1.5 steps
  // and deviate up to 2.25 times its ArcTolerance: divide so the bound we promise holds.
  offset.ArcTolerance = arc_tolerance * kScale / 2.25;
  offset.AddPaths(toPaths(region), cl::jtRound, cl::etClosedPolygon);
  cl::PolyTree tree;
  offset.Execute(tree, delta * kScale);
  return fromTree(tree);
}

namespace {

/// Douglas-Peucker on the open chain ring[first..last] (indices modulo n): marks the vertices to
/// keep so that every dropped vertex lies within `tolerance` of the kept chain.
void douglasPeucker(const Ring& ring, std::size_t first, std::size_t last, double tolerance, std::vector<bool>& keep) {
  const std::size_t n = ring.size();
  std::vector<std::pair<std::size_t, std::size_t>> stack{{first, last}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    double worst = -1.0;
    std::size_t at = i;
    for (std::size_t k = (i + 1) % n; k != j; k = (k + 1) % n) {
      const double d = distancePointSegment(ring[k], ring[i], ring[j]);
      if (d > worst) worst = d, at = k;
    }
    if (worst > tolerance) {
      keep[at] = true;
      stack.push_back({i, at});
      stack.push_back({at, j});
    }
  }
}

Ring simplifyRing(const Ring& ring, double tolerance) {
  const std::size_t n = ring.size();
  if (n <= 4) return ring;
  // Split the closed ring at vertex 0 and the vertex farthest from it.
  std::size_t far = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (distance(ring[k], ring[0]) > distance(ring[far], ring[0])) far = k;
  std::vector<bool> keep(n, false);
  keep[0] = keep[far] = true;
  douglasPeucker(ring, 0, far, tolerance, keep);
  douglasPeucker(ring, far, 0, tolerance, keep);
  Ring out;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[k]) out.push_back(ring[k]);
  return out.size() >= 3 ? out : ring;
}

}  // namespace

Region simplifyRegion(const Region& region, double tolerance) {
  // Simplified rings can touch or cross where the region is thinner than 2 * tolerance. One
  // union of every outer ring counter-clockwise and every hole clockwise, filled where the
  // winding is positive, turns them back into a valid region: a hole takes away only from its
  // own polygon (not from an island another polygon has inside it), and a piece of hole pushed
  // outside its polygon takes away nothing.
  cl::Clipper clipper;
  for (const PolygonWithHoles& poly : region) {
    cl::Path outer = toPath(simplifyRing(poly.outer, tolerance));
    if (!cl::Orientation(outer)) cl::ReversePath(outer);
    clipper.AddPath(outer, cl::ptSubject, true);
    for (const Ring& h : poly.holes) {
      cl::Path hole = toPath(simplifyRing(h, tolerance));
      if (cl::Orientation(hole)) cl::ReversePath(hole);
      clipper.AddPath(hole, cl::ptSubject, true);
    }
  }
  cl::PolyTree tree;
  clipper.Execute(cl::ctUnion, tree, cl::pftPositive, cl::pftPositive);
  return fromTree(tree);
}

Region sweptRegion(const std::vector<std::vector<Point>>& polylines, double radius, double arc_tolerance) {
  cl::ClipperOffset offset;
  offset.ArcTolerance = arc_tolerance * kScale / 2.25;
  for (const std::vector<Point>& line : polylines) {
    cl::Path path = toPath(line);
    // Clipper drops repeated points itself; a lone point becomes a disk with etOpenRound.
    offset.AddPath(path, cl::jtRound, cl::etOpenRound);
  }
  cl::PolyTree tree;
  offset.Execute(tree, radius * kScale);
  return fromTree(tree);
}

Region sweepAlong(const Region& region, Point half) {
  // The region plus what its boundary passes over: each maximal run of edges crossing the
  // direction the same way (a chain monotone across it) sweeps the simple polygon between the
  // run moved back and the run moved forward. Runs, not single edges: a union of one
  // parallelogram per edge costs Clipper quadratic time in shared edges.
  std::vector<Ring> bands;
  for (const Ring& ring : allRings(region)) {
    const std::size_t n = ring.size();
    auto side = [&](std::size_t i) {
      const double c = cross(ring[(i + 1) % n] - ring[i], half);
      return c > 0.0 ? 1 : c < 0.0 ? -1 : 0;
    };
    // Start at an edge that begins a run, so no run wraps around the ring's start.
    std::size_t start = 0;
    while (start < n && (side(start) == 0 || side(start) == side((start + n - 1) % n))) ++start;
    if (start == n) start = 0;  // every edge on one side (cannot close) or parallel: nothing sweeps
    std::vector<Point> run;
    int run_side = 0;
    auto flush = [&] {
      if (run.size() >= 2) {
        Ring band;
        for (const Point& p : run) band.push_back(p - half);
        for (auto it = run.rbegin(); it != run.rend(); ++it) band.push_back(*it + half);
        bands.push_back(std::move(band));
      }
      run.clear();
    };
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (start + k) % n;
      const int s = side(i);
      if (s == 0 || s != run_side) flush();
      run_side = s;
      if (s == 0) continue;
      if (run.empty()) run.push_back(ring[i]);
      run.push_back(ring[(i + 1) % n]);
    }
    flush();
  }
  // One union: the region (holes wind to zero) and the bands, each turned counter-clockwise.
  cl::Clipper clipper;
  clipper.AddPaths(toPaths(region), cl::ptSubject, true);
  addCounterClockwise(clipper, bands, cl::ptClip);
  cl::PolyTree tree;
  clipper.Execute(cl::ctUnion, tree, cl::pftNonZero, cl::pftNonZero);
  return fromTree(tree);
}

Region unite(const Region& a, const Region& b) { return boolean(a, b, cl::ctUnion); }
Region intersect(const Region& a, const Region& b) { return boolean(a, b, cl::ctIntersection); }
Region subtract(const Region& a, const Region& b) { return boolean(a, b, cl::ctDifference); }

Region regionFromRings(const std::vector<Ring>& rings) {
  cl::Clipper clipper;
  addCounterClockwise(clipper, rings, cl::ptSubject);
  cl::PolyTree tree;
  clipper.Execute(cl::ctUnion, tree, cl::pftNonZero, cl::pftNonZero);
  return fromTree(tree);
}

namespace {

/// The rings counter-clockwise and k - 1 clockwise copies of a box around them all, in `clipper`.
void addLevel(cl::Clipper& clipper, const std::vector<Ring>& rings, int k) {
  Box box = boundingBox(rings[0]);
  for (const Ring& ring : rings) {
    const Box b = boundingBox(ring);
    box = {std::min(box.min_x, b.min_x), std::min(box.min_y, b.min_y), std::max(box.max_x, b.max_x), std::max(box.max_y, b.max_y)};
  }
  addCounterClockwise(clipper, rings, cl::ptSubject);
  const double m = 1.0;  // the box is clear of every ring by a metre
  cl::Path frame = toPath({{box.min_x - m, box.min_y - m}, {box.min_x - m, box.max_y + m}, {box.max_x + m, box.max_y + m},
                           {box.max_x + m, box.min_y - m}});
  if (cl::Orientation(frame)) cl::ReversePath(frame);
  for (int i = 1; i < k; ++i) clipper.AddPath(frame, cl::ptSubject, true);
}

}  // namespace

Region coveredAtLeast(const std::vector<Ring>& rings, int k) {
  if (rings.empty() || k < 1) return {};
  cl::Clipper clipper;
  addLevel(clipper, rings, k);
  cl::PolyTree tree;
  clipper.Execute(cl::ctUnion, tree, cl::pftPositive, cl::pftPositive);
  return fromTree(tree);
}

double coveredAtLeastArea(const std::vector<Ring>& rings, int k) {
  if (rings.empty() || k < 1) return 0.0;
  cl::Clipper clipper;
  addLevel(clipper, rings, k);
  cl::Paths out;  // outer rings counter-clockwise, holes clockwise: their signed areas add up
  clipper.Execute(cl::ctUnion, out, cl::pftPositive, cl::pftPositive);
  double total = 0.0;
  for (const cl::Path& path : out) total += cl::Area(path);
  return total / (kScale * kScale);
}

Ring circumscribedCircle(Point center, double radius, double tolerance) {
  // A regular n-gon with inradius `radius` has circumradius radius / cos(pi / n).
  const double ratio = radius / (radius + tolerance);
  int n = static_cast<int>(std::ceil(M_PI / std::acos(ratio)));
  n = std::max(n, 8);
  const double circumradius = radius / std::cos(M_PI / n);
  Ring ring;
  ring.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    ring.push_back({center.x + circumradius * std::cos(angle),
                    center.y + circumradius * std::sin(angle)});
  }
  return ring;
}

Region obstacleRegion(const Obstacle& obstacle, double tolerance) {
  if (obstacle.type == ObstacleType::Circle)
    return regionFromRings({circumscribedCircle(obstacle.center, obstacle.radius, tolerance)});
  return regionFromRings({obstacle.polygon});
}

}  // namespace coverbench
