#include "coverbench/geometry.hpp"

#include <algorithm>

#include "ring_simplicity.hpp"

namespace coverbench {

Point rotate(Point p, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  return {c * p.x - s * p.y, s * p.x + c * p.y};
}

void rotatePoints(std::vector<Point>& points, double radians) {
  const double c = std::cos(radians), s = std::sin(radians);
  for (Point& p : points) p = {c * p.x - s * p.y, s * p.x + c * p.y};
}

Box boundingBox(const Ring& ring) {
  Box box;
  for (const Point& p : ring) box.add(p);
  return box;
}

Box boundingBox(const Region& region) {
  Box box;
  for (const PolygonWithHoles& poly : region)
    for (const Point& p : poly.outer) box.add(p);
  return box;
}

double boxDistance(const Box& a, const Box& b) { return std::sqrt(squaredBoxDistance(a, b)); }

double signedArea(const Ring& ring) {
  double twice = 0.0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) twice += cross(ring[i], ring[(i + 1) % n]);
  return twice / 2.0;
}

double area(const PolygonWithHoles& polygon) {
  double a = std::fabs(signedArea(polygon.outer));
  for (const Ring& hole : polygon.holes) a -= std::fabs(signedArea(hole));
  return a;
}

double area(const Region& region) {
  double a = 0.0;
  for (const PolygonWithHoles& p : region) a += area(p);
  return a;
}

double polylineLength(const std::vector<Point>& points) {
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += distance(points[i - 1], points[i]);
  return length;
}

double squaredDistancePointSegment(Point p, Point a, Point b) {
  const Point ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 == 0.0 ? 0.0 : std::clamp(dot(p - a, ab) / len2, 0.0, 1.0);
  const Point d = p - (a + ab * t);
  return dot(d, d);
}

double distancePointSegment(Point p, Point a, Point b) { return std::sqrt(squaredDistancePointSegment(p, a, b)); }

namespace {
/// Orientation sign of (a, b, c): +1 left turn, -1 right turn, 0 collinear.
int orient(Point a, Point b, Point c) {
  const double v = cross(b - a, c - a);
  return (v > 0.0) - (v < 0.0);
}
bool onSegment(Point p, Point a, Point b) {
  return std::fmin(a.x, b.x) <= p.x && p.x <= std::fmax(a.x, b.x) && std::fmin(a.y, b.y) <= p.y &&
         p.y <= std::fmax(a.y, b.y);
}
}  // namespace

bool segmentsIntersect(Point a, Point b, Point c, Point d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) {
    if (o1 != 0 || o2 != 0) return true;
  }
  if (o1 == 0 && onSegment(c, a, b)) return true;
  if (o2 == 0 && onSegment(d, a, b)) return true;
  if (o3 == 0 && onSegment(a, c, d)) return true;
  if (o4 == 0 && onSegment(b, c, d)) return true;
  return false;
}

double squaredDistanceSegmentSegment(Point a, Point b, Point c, Point d) {
  if (segmentsIntersect(a, b, c, d)) return 0.0;
  return std::fmin(std::fmin(squaredDistancePointSegment(a, c, d), squaredDistancePointSegment(b, c, d)),
                   std::fmin(squaredDistancePointSegment(c, a, b), squaredDistancePointSegment(d, a, b)));
}

double distanceSegmentSegment(Point a, Point b, Point c, Point d) {
  return std::sqrt(squaredDistanceSegmentSegment(a, b, c, d));
}

bool pointInRing(Point p, const Ring& ring) {
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Point& a = ring[i];
    const Point& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

double distanceSegmentRingEdges(Point a, Point b, const Ring& ring) {
  // The nearest edge by squared distance, one square root (the same number: sqrt is monotone and
  // correctly rounded).
  double best2 = INFINITY;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n && best2 > 0.0; ++i)
    best2 = std::fmin(best2, squaredDistanceSegmentSegment(a, b, ring[i], ring[(i + 1) % n]));
  return std::sqrt(best2);
}

double distanceSegmentFilledRing(Point a, Point b, const Ring& ring) {
  if (pointInRing(a, ring) || pointInRing(b, ring)) return 0.0;
  return distanceSegmentRingEdges(a, b, ring);
}

bool pointInPolygon(const PolygonWithHoles& polygon, Point p) {
  if (!pointInRing(p, polygon.outer)) return false;
  for (const Ring& hole : polygon.holes)
    if (pointInRing(p, hole)) return false;
  return true;
}

bool ringIsSimple(const Ring& ring) {
  // Simple: at least 3 vertices, no edge of zero length, no two edges meeting but consecutive
  // ones at their shared vertex (touching counts as meeting; so does folding back onto the last
  // edge), and an area. The sweep makes it O(n log n): walls from outside have 10^6 vertices.
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (ring[i] == ring[(i + 1) % n] || !std::isfinite(ring[i].x) || !std::isfinite(ring[i].y)) return false;
  return detail::edgesMeetOnlyAtSharedVertices(ring) && std::fabs(signedArea(ring)) > 0.0;
}

}  // namespace coverbench
