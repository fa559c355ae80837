// The wall model's checks: input errors as one line, numbers as messages show them, and a wall's
// geometric sense (obstacles inside, something left to cover).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <utility>

#include "coverbench/region_ops.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

namespace {

/// Whether `p` lies inside `ring` and not on its edges.
bool strictlyInside(Point p, const Ring& ring) {
  if (!pointInRing(p, ring)) return false;
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (distancePointSegment(p, ring[i], ring[(i + 1) % ring.size()]) == 0.0) return false;
  return true;
}

/// Whether an obstacle covers some of the wall's interior. Circles are decided exactly from the
/// centre; polygons by a vertex strictly inside the wall (its first few: cheap, and what an
/// obstacle on a wall usually has), else by the area of their intersection, or, for polygons too
/// small for the region grid (1 um), by any vertex strictly inside the wall.
template <class ObstacleRegion, class BoundaryRegion>
bool reachesIntoWall(const Obstacle& o, const Wall& wall, ObstacleRegion obstacle, BoundaryRegion boundary) {
  if (o.type == ObstacleType::Circle) {
    double gap = INFINITY;
    for (std::size_t i = 0; i < wall.boundary.size(); ++i)
      gap = std::min(gap, distancePointSegment(o.center, wall.boundary[i], wall.boundary[(i + 1) % wall.boundary.size()]));
    return gap < o.radius || (gap > 0.0 && pointInRing(o.center, wall.boundary));
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(4, o.polygon.size()); ++i)
    if (strictlyInside(o.polygon[i], wall.boundary)) return true;
  if (area(intersect(obstacle(), boundary())) > 0.0) return true;
  for (const Point& p : o.polygon)
    if (strictlyInside(p, wall.boundary)) return true;
  return false;
}

double ringPerimeter(const Ring& ring) {
  double length = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) length += distance(ring[i], ring[(i + 1) % ring.size()]);
  return length;
}

/// The most vertices the check that obstacles leave something of the wall may hand to Clipper
/// (the obstacles' polygons and circles as polygons): past it the wall is refused, not checked
/// for minutes. Only walls whose obstacles' areas add up to the wall's reach that check.
constexpr double kMaxCheckedVertices = 2e6;

}  // namespace

void validateWall(const Wall& wall, const std::string& source) {
  for (const auto& [point, field] : {std::pair{wall.start, "start"}, std::pair{wall.end, "end"}})
    if (point && !pointInRing(*point, wall.boundary))
      throw InputError(source, field, "(" + shortNumber(point->x) + ", " + shortNumber(point->y) + ") lies outside the wall");
  // Regions are built only when a check needs them: Clipper's scanbeams cost about n x (edges
  // crossing a scanline), seconds for a 25,000-vertex star, and most walls need none.
  std::optional<Region> boundary;
  auto boundaryRegion = [&]() -> const Region& {
    if (!boundary) boundary = regionFromRings({wall.boundary});
    return *boundary;
  };
  // A circle as a polygon around it, within 1 um or a millionth of its radius (a circle of
  // 4 km at 1 um took 140,000 vertices).
  auto regionOf = [](const Obstacle& o) {
    return obstacleRegion(o, o.type == ObstacleType::Circle ? std::max(1e-6, 1e-6 * o.radius) : 1e-6);
  };
  double obstacles_area = 0.0, perimeters = ringPerimeter(wall.boundary), vertices = 0.0;
  for (std::size_t i = 0; i < wall.obstacles.size(); ++i) {
    const Obstacle& o = wall.obstacles[i];
    if (!reachesIntoWall(o, wall, [&] { return regionOf(o); }, boundaryRegion))
      throw InputError(source, "obstacles[" + std::to_string(i) + "]", "lies entirely outside the wall");
    if (o.type == ObstacleType::Circle) {
      const double r = o.radius + std::max(1e-6, 1e-6 * o.radius);  // the polygon lies within this circle
      obstacles_area += M_PI * r * r;
      perimeters += 2 * M_PI * r;
      vertices += M_PI / std::acos(o.radius / r) + 8;
    } else {
      obstacles_area += std::fabs(signedArea(o.polygon));
      perimeters += ringPerimeter(o.polygon);
      vertices += static_cast<double>(o.polygon.size());
    }
  }
  if (wall.obstacles.empty()) return;
  // What is free is at least the wall's area less every obstacle's (less what the region grid's
  // rounding, 1 um, can move along every edge): when that is more than nothing, the subtraction
  // cannot say otherwise.
  if (std::fabs(signedArea(wall.boundary)) - obstacles_area > 1e-6 + 1e-6 * perimeters) return;
  if (vertices > kMaxCheckedVertices)
    throw InputError(source, "obstacles",
                     "cover as much area as the wall, and are too many to check whether they leave any of it (about " +
                         shortNumber(std::round(vertices)) + " vertices with the circles as polygons, at most " +
                         shortNumber(kMaxCheckedVertices) + ")");
  std::vector<Ring> obstacle_rings;
  for (const Obstacle& o : wall.obstacles)
    for (const Ring& ring : allRings(regionOf(o))) obstacle_rings.push_back(ring);
  const Region free = subtract(boundaryRegion(), regionFromRings(obstacle_rings));
  if (area(free) <= 1e-9) throw InputError(source, "obstacles", "leave nothing of the wall to cover");
}

}  // namespace coverbench
