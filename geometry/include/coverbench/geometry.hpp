#pragma once
/// Plain value types for 2-D geometry and the exact predicates CoverBench builds on.
///
/// Everything is in metres, double precision. "Exact" here means closed-form distance and
/// intersection computations on the true shapes (no sampling, no rasters); the only error is
/// floating-point rounding, which callers absorb with a stated tolerance.

#include <algorithm>
#include <cmath>
#include <vector>

namespace coverbench {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

inline Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
inline Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
inline Point operator*(Point a, double k) { return {a.x * k, a.y * k}; }
inline bool operator==(Point a, Point b) { return a.x == b.x && a.y == b.y; }
inline double dot(Point a, Point b) { return a.x * b.x + a.y * b.y; }
inline double cross(Point a, Point b) { return a.x * b.y - a.y * b.x; }
inline double norm(Point a) { return std::hypot(a.x, a.y); }
inline double distance(Point a, Point b) { return norm(a - b); }

/// `radians` into [-pi, pi]: exactly std::remainder(radians, 2 pi), bit for bit. Angles within a
/// turn of that range (nearly all a planner makes) take one comparison and at most one exact
/// subtraction (Sterbenz: both lie within a factor of two); only the rest call remainder, which
/// costs tens of instructions and runs hundreds of thousands of times a car plan.
inline double wrapAngle(double radians) {
  constexpr double kTwoPi = 2.0 * M_PI;
  if (std::fabs(radians) <= M_PI) return radians;  // remainder rounds a quotient of 1/2 to 0
  if (radians > M_PI && radians <= kTwoPi) return radians - kTwoPi;
  if (radians < -M_PI && radians > -kTwoPi) return radians + kTwoPi;  // -2 pi: remainder gives -0
  return std::remainder(radians, kTwoPi);
}

/// Rotates p by `radians` counter-clockwise about the origin.
Point rotate(Point p, double radians);
/// rotate() applied to every point, with the sine and cosine computed once (same results).
void rotatePoints(std::vector<Point>& points, double radians);

/// A closed polygon ring; the last vertex connects back to the first (not repeated).
using Ring = std::vector<Point>;

/// A polygon with holes. `outer` is counter-clockwise, `holes` clockwise.
struct PolygonWithHoles {
  Ring outer;
  std::vector<Ring> holes;
};

/// A planar region: a union of disjoint polygons with holes.
using Region = std::vector<PolygonWithHoles>;

/// Axis-aligned bounding box.
struct Box {
  double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
  void add(Point p) {
    min_x = std::fmin(min_x, p.x);
    min_y = std::fmin(min_y, p.y);
    max_x = std::fmax(max_x, p.x);
    max_y = std::fmax(max_y, p.y);
  }
  bool empty() const { return min_x > max_x; }
  double width() const { return max_x - min_x; }
  double height() const { return max_y - min_y; }
};
Box boundingBox(const Ring& ring);
Box boundingBox(const Region& region);
/// Distance between two boxes (0 when they overlap).
double boxDistance(const Box& a, const Box& b);
/// (Finite boxes: std::max compiles to one instruction, std::fmax to a call that handles NaN.)
inline double squaredBoxDistance(const Box& a, const Box& b) {
  const double dx = std::max(0.0, std::max(a.min_x - b.max_x, b.min_x - a.max_x));
  const double dy = std::max(0.0, std::max(a.min_y - b.max_y, b.min_y - a.max_y));
  return dx * dx + dy * dy;
}

/// Signed area: positive for counter-clockwise rings.
double signedArea(const Ring& ring);
double area(const PolygonWithHoles& polygon);
double area(const Region& region);
/// Length of an open polyline (0 for fewer than two points).
double polylineLength(const std::vector<Point>& points);

/// Distance from p to the closed segment [a, b].
double distancePointSegment(Point p, Point a, Point b);
/// True when the closed segments [a, b] and [c, d] share at least one point.
bool segmentsIntersect(Point a, Point b, Point c, Point d);
/// Distance between the closed segments [a, b] and [c, d] (0 when they intersect).
double distanceSegmentSegment(Point a, Point b, Point c, Point d);

/// Squared distance between the closed segments (0 when they intersect); cheaper, for comparisons.
double squaredDistanceSegmentSegment(Point a, Point b, Point c, Point d);
/// Squared distance from p to the closed segment [a, b].
double squaredDistancePointSegment(Point p, Point a, Point b);

/// Point in ring by the crossing rule; points exactly on the ring may go either way.
bool pointInRing(Point p, const Ring& ring);
/// Point in a polygon with holes: inside the outer ring and in none of the holes (same rule).
bool pointInPolygon(const PolygonWithHoles& polygon, Point p);
/// Distance from the segment [a, b] to the edges of the ring (not its interior).
double distanceSegmentRingEdges(Point a, Point b, const Ring& ring);
/// Distance from the segment [a, b] to the filled ring: 0 if the segment touches or enters it.
double distanceSegmentFilledRing(Point a, Point b, const Ring& ring);

/// True when no two non-adjacent edges of the ring touch and no adjacent edges overlap.
bool ringIsSimple(const Ring& ring);

}  // namespace coverbench
