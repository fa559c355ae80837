#include "coverbench/clearance.hpp"

#include <algorithm>

#include "coverbench/path.hpp"

namespace coverbench {
namespace {

/// An arc as the distance functions take it: centre, radius, start radial and signed sweep.
struct Arc {
  Point a, b, centre;
  double radius = 0.0;
  Point start;         ///< a - centre
  Point end;           ///< b - centre
  double sweep = 0.0;  ///< signed, radians
  Box box;             ///< a box holding the arc (its ends and the extreme points it passes)
};

Arc makeArc(Point a, Point b, double bulge) {
  const ArcGeometry g = arcGeometry(a, b, bulge);
  Arc arc{a, b, g.centre, g.radius, a - g.centre, b - g.centre, g.sweep, {}};
  arc.box.add(a);
  arc.box.add(b);
  return arc;
}

/// Whether the direction v (not 0) from the centre lies within the arc's sweep, by the signs of
/// cross products (no angles: this runs for every edge near every arc checked). Turning the arc's
/// way, v is within when it lies at most half a turn past the start and not past the end (a sweep
/// under half a turn: both half-planes), or when it is not strictly between the end and the start
/// (a sweep of half a turn or more: outside the complement's wedge).
bool withinSweep(const Arc& arc, Point v) {
  const double turn = arc.sweep < 0.0 ? -1.0 : 1.0;
  const double from_start = turn * cross(arc.start, v), to_end = turn * cross(v, arc.end);
  if (std::fabs(arc.sweep) < M_PI) return from_start >= 0.0 && to_end >= 0.0 && (from_start > 0.0 || dot(arc.start, v) > 0.0);
  return !(from_start < 0.0 && to_end < 0.0);
}

double distancePointArc(Point p, const Arc& arc) {
  const Point v = p - arc.centre;
  const double d = norm(v);
  if (d > 0.0 && withinSweep(arc, v)) return std::fabs(d - arc.radius);
  return std::fmin(distance(p, arc.a), distance(p, arc.b));
}

double distanceSegmentArc(Point p, Point q, const Arc& arc) {
  double best = std::fmin(std::fmin(distancePointArc(p, arc), distancePointArc(q, arc)),
                          std::fmin(distancePointSegment(arc.a, p, q), distancePointSegment(arc.b, p, q)));
  const Point d = q - p;
  const double len2 = dot(d, d);
  if (len2 == 0.0 || best == 0.0) return best;
  // The foot of the centre on the segment's line: the radial pair there, when it is on the segment.
  const double t = dot(arc.centre - p, d) / len2;
  const Point foot = p + d * t, v = foot - arc.centre;
  const double dist = norm(v);
  if (t > 0.0 && t < 1.0 && dist > 0.0 && withinSweep(arc, v)) best = std::fmin(best, std::fabs(dist - arc.radius));
  // Where the line meets the circle, on the segment and within the sweep: they cross.
  if (dist < arc.radius) {
    const double half = std::sqrt((arc.radius * arc.radius - dist * dist) / len2);
    for (const double s : {t - half, t + half})
      if (s >= 0.0 && s <= 1.0 && withinSweep(arc, p + d * s - arc.centre)) return 0.0;
  }
  return best;
}

/// Distance from the arc to the filled polygon `ring` (0 when they meet or the arc is inside).
double distanceArcFilledRing(const Arc& arc, const Ring& ring) {
  if (pointInRing(arc.a, ring)) return 0.0;
  double best = INFINITY;
  for (std::size_t k = 0, n = ring.size(); k < n && best > 0.0; ++k)
    best = std::fmin(best, distanceSegmentArc(ring[k], ring[(k + 1) % n], arc));
  return best;
}

/// The edge's box is within `need` of the arc's (squared, with the room for rounding the
/// measurements' pruning takes): only then may the edge lie nearer than `need`.
bool edgeMayBeNearer(const Arc& arc, Point p, Point q, double need) {
  const Box edge{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)};
  return squaredBoxDistance(arc.box, edge) < need * need * (1.0 + 1e-12);
}

/// Some edge of `ring` lies nearer the arc than `need` (distanceSegmentArc < need); edges whose
/// boxes are farther are not measured.
bool ringEdgeNearer(const Arc& arc, const Ring& ring, double need) {
  for (std::size_t k = 0, n = ring.size(); k < n; ++k) {
    const Point p = ring[k], q = ring[(k + 1) % n];
    if (edgeMayBeNearer(arc, p, q, need) && distanceSegmentArc(p, q, arc) < need) return true;
  }
  return false;
}

/// The arc with its box: its ends, and each axis extreme of the circle it sweeps over.
Arc boxedArc(Point a, Point b, double bulge) {
  Arc arc = makeArc(a, b, bulge);
  for (const Point dir : {Point{1, 0}, Point{0, 1}, Point{-1, 0}, Point{0, -1}})
    if (withinSweep(arc, dir)) arc.box.add(arc.centre + dir * arc.radius);
  return arc;
}

}  // namespace

ClearanceField::ClearanceField(const Wall& wall) : wall_(&wall) {
  obstacle_boxes_.reserve(wall.obstacles.size());
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle) {
      Box b;
      b.add({o.center.x - o.radius, o.center.y - o.radius});
      b.add({o.center.x + o.radius, o.center.y + o.radius});
      obstacle_boxes_.push_back(b);
    } else {
      obstacle_boxes_.push_back(boundingBox(o.polygon));
    }
  }
  // A grid pays off from about 8 obstacles (the 24-window facade's car zigzag plan: 7.5 % fewer
  // instructions than a scan of every box; walls of 3-5 obstacles within 0.3 % either way); aim
  // at about one obstacle per bucket.
  if (obstacle_boxes_.size() < 8) return;
  for (const Box& b : obstacle_boxes_) grid_box_.add({b.min_x, b.min_y}), grid_box_.add({b.max_x, b.max_y});
  const double area = std::max(grid_box_.width() * grid_box_.height(), 1e-12);
  grid_cell_ = std::max({std::sqrt(area / static_cast<double>(obstacle_boxes_.size())), grid_box_.width() / 512.0,
                         grid_box_.height() / 512.0, 1e-6});
  grid_nx_ = static_cast<long>(grid_box_.width() / grid_cell_) + 1;
  grid_ny_ = static_cast<long>(grid_box_.height() / grid_cell_) + 1;
  grid_.resize(static_cast<std::size_t>(grid_nx_ * grid_ny_));
  for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i) {
    const Box& b = obstacle_boxes_[i];
    const long x0 = static_cast<long>((b.min_x - grid_box_.min_x) / grid_cell_);
    const long x1 = std::min(grid_nx_ - 1, static_cast<long>((b.max_x - grid_box_.min_x) / grid_cell_));
    const long y0 = static_cast<long>((b.min_y - grid_box_.min_y) / grid_cell_);
    const long y1 = std::min(grid_ny_ - 1, static_cast<long>((b.max_y - grid_box_.min_y) / grid_cell_));
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x) grid_[static_cast<std::size_t>(y * grid_nx_ + x)].push_back(static_cast<std::uint32_t>(i));
  }
}

template <class F>
bool ClearanceField::forObstaclesNear(const Box& box, double reach, F&& f) const {
  if (grid_.empty()) {
    for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i)
      if (!f(i)) return false;
    return true;
  }
  auto clampIndex = [](double v, long n) { return std::clamp(static_cast<long>(std::floor(v)), 0L, n - 1); };
  if (box.max_x + reach < grid_box_.min_x || box.min_x - reach > grid_box_.max_x || box.max_y + reach < grid_box_.min_y ||
      box.min_y - reach > grid_box_.max_y)
    return true;
  const long x0 = clampIndex((box.min_x - reach - grid_box_.min_x) / grid_cell_, grid_nx_);
  const long x1 = clampIndex((box.max_x + reach - grid_box_.min_x) / grid_cell_, grid_nx_);
  const long y0 = clampIndex((box.min_y - reach - grid_box_.min_y) / grid_cell_, grid_ny_);
  const long y1 = clampIndex((box.max_y + reach - grid_box_.min_y) / grid_cell_, grid_ny_);
  for (long y = y0; y <= y1; ++y)
    for (long x = x0; x <= x1; ++x)
      for (std::uint32_t i : grid_[static_cast<std::size_t>(y * grid_nx_ + x)])
        if (!f(i)) return false;
  return true;
}

double ClearanceField::obstacleDistance(std::size_t i, Point a, Point b) const {
  const Obstacle& o = wall_->obstacles[i];
  if (o.type == ObstacleType::Circle)
    return std::fmax(0.0, distancePointSegment(o.center, a, b) - o.radius);
  return distanceSegmentFilledRing(a, b, o.polygon);
}

SegmentClearance ClearanceField::measure(Point a, Point b, double obstacle_cutoff) const {
  SegmentClearance c;
  Box seg;
  seg.add(a);
  seg.add(b);
  // The nearest boundary edge: an edge whose box is farther than the nearest edge so far is
  // skipped (the same minimum as distanceSegmentRingEdges; squared, one square root at the end).
  const Ring& ring = wall_->boundary;
  double best2 = INFINITY;
  for (std::size_t i = 0, n = ring.size(); i < n && best2 > 0.0; ++i) {
    const Point p = ring[i], q = ring[(i + 1) % n];
    const Box edge{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)};
    if (squaredBoxDistance(seg, edge) > best2 * (1.0 + 1e-12)) continue;  // room for rounding
    best2 = std::fmin(best2, squaredDistanceSegmentSegment(a, b, p, q));
  }
  c.boundary_distance = std::sqrt(best2);
  // A segment that does not touch the boundary is entirely inside or entirely outside it.
  c.inside = c.boundary_distance > 0.0 && pointInRing(a, wall_->boundary);
  double best = obstacle_cutoff;
  // An obstacle whose box is at least `best` away cannot be nearer; compared squared, with room for
  // the rounding of best^2 (measuring one more obstacle changes nothing).
  auto maybeNearer = [&](std::size_t i) {
    return squaredBoxDistance(seg, obstacle_boxes_[i]) < best * best * (1.0 + 1e-12);
  };
  auto visit = [&](std::size_t i) {
    if (!maybeNearer(i)) return;
    const double d = obstacleDistance(i, a, b);
    if (d < best) {
      best = d;
      c.nearest_obstacle = static_cast<long>(i);
    }
  };
  if (!grid_.empty() && std::isinf(best)) {
    // Unbounded: a scan of every obstacle finds the nearest at the same cost as the grid would.
    for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i) visit(i);
  } else {
    forObstaclesNear(seg, best, [&](std::size_t i) {
      visit(i);
      return true;
    });
  }
  c.obstacle_distance = best;
  return c;
}

bool ClearanceField::segmentFree(Point a, Point b, double radius, double clearance, double margin) const {
  // Squared distances throughout: this is the planners' hot path.
  const double need_obstacle = radius + clearance + margin;
  const double need_obstacle2 = need_obstacle * need_obstacle;
  Box seg;
  seg.add(a);
  seg.add(b);
  const bool clear = forObstaclesNear(seg, need_obstacle, [&](std::size_t i) {
    if (squaredBoxDistance(seg, obstacle_boxes_[i]) >= need_obstacle2) return true;
    const Obstacle& o = wall_->obstacles[i];
    if (o.type == ObstacleType::Circle) {
      const double reach = o.radius + need_obstacle;
      return squaredDistancePointSegment(o.center, a, b) >= reach * reach;
    }
    if (pointInRing(a, o.polygon)) return false;
    const Ring& ring = o.polygon;
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      if (squaredDistanceSegmentSegment(a, b, ring[k], ring[(k + 1) % n]) < need_obstacle2) return false;
    return true;
  });
  if (!clear) return false;
  const Ring& ring = wall_->boundary;
  const std::size_t n = ring.size();
  const double need_boundary = radius + margin;
  const double need_boundary2 = need_boundary * need_boundary;
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = ring[i], q = ring[(i + 1) % n];
    Box edge;
    edge.add(p);
    edge.add(q);
    if (squaredBoxDistance(seg, edge) >= need_boundary2) continue;
    if (squaredDistanceSegmentSegment(a, b, p, q) < need_boundary2) return false;
  }
  return pointInRing(a, ring);
}

SegmentClearance ClearanceField::measureArc(Point a, Point b, double bulge, double obstacle_cutoff) const {
  if (bulge == 0.0) return measure(a, b, obstacle_cutoff);
  const Arc arc = boxedArc(a, b, bulge);
  SegmentClearance c;
  const Ring& ring = wall_->boundary;
  double best = INFINITY;
  for (std::size_t i = 0, n = ring.size(); i < n && best > 0.0; ++i) {
    const Point p = ring[i], q = ring[(i + 1) % n];
    const Box edge{std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)};
    if (squaredBoxDistance(arc.box, edge) > best * best * (1.0 + 1e-12)) continue;
    best = std::fmin(best, distanceSegmentArc(p, q, arc));
  }
  c.boundary_distance = best;
  // An arc that does not touch the boundary is entirely inside or entirely outside it.
  c.inside = c.boundary_distance > 0.0 && pointInRing(a, ring);
  double nearest = obstacle_cutoff;
  auto visit = [&](std::size_t i) {
    if (squaredBoxDistance(arc.box, obstacle_boxes_[i]) >= nearest * nearest * (1.0 + 1e-12)) return true;
    const Obstacle& o = wall_->obstacles[i];
    const double d = o.type == ObstacleType::Circle ? std::fmax(0.0, distancePointArc(o.center, arc) - o.radius)
                                                    : distanceArcFilledRing(arc, o.polygon);
    if (d < nearest) {
      nearest = d;
      c.nearest_obstacle = static_cast<long>(i);
    }
    return true;
  };
  if (!grid_.empty() && std::isinf(nearest)) {
    for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i) visit(i);
  } else {
    forObstaclesNear(arc.box, nearest, visit);
  }
  c.obstacle_distance = nearest;
  return c;
}

bool ClearanceField::arcFree(Point a, Point b, double bulge, double radius, double clearance, double margin) const {
  if (bulge == 0.0) return segmentFree(a, b, radius, clearance, margin);
  // measureArc's answer, but stopping at the first edge or obstacle nearer than needed and never
  // measuring those whose boxes are farther (the planners' searches check tens of thousands).
  const double need_boundary = radius + margin, need_obstacle = radius + clearance + margin;
  if (!(need_boundary > 0.0)) {
    const SegmentClearance c = measureArc(a, b, bulge, need_obstacle);
    return c.inside && c.boundary_distance >= need_boundary && c.obstacle_distance >= need_obstacle;
  }
  const Arc arc = boxedArc(a, b, bulge);
  // An arc that keeps need_boundary > 0 from the boundary is entirely inside or entirely outside.
  if (ringEdgeNearer(arc, wall_->boundary, need_boundary) || !pointInRing(a, wall_->boundary)) return false;
  return forObstaclesNear(arc.box, need_obstacle, [&](std::size_t i) {
    if (squaredBoxDistance(arc.box, obstacle_boxes_[i]) >= need_obstacle * need_obstacle * (1.0 + 1e-12)) return true;
    const Obstacle& o = wall_->obstacles[i];
    if (o.type == ObstacleType::Circle) return std::fmax(0.0, distancePointArc(o.center, arc) - o.radius) >= need_obstacle;
    return !pointInRing(arc.a, o.polygon) && !ringEdgeNearer(arc, o.polygon, need_obstacle);
  });
}

}  // namespace coverbench
