// The wall model's checks: input errors as one line, numbers as messages show them, and a wall's
// geometric sense (obstacles inside, something left to cover).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "coverbench/region_ops.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

InputError::InputError(std::string source, std::string field, std::string problem)
    : std::runtime_error(source + ": " + field + ": " + problem),
      source_(std::move(source)),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

std::string shortNumber(double v) {
  // Six significant digits, or as many more as it takes to read back as v: 3600.0000001 is not
  // printed as the bound 3600 it exceeds, and 0.1 stays 0.1.
  char buf[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v || !std::isfinite(v)) break;
  }
  return buf;
}

namespace {

/// Whether `p` lies inside `ring` and not on its edges.
bool strictlyInside(Point p, const Ring& ring) {
  if (!pointInRing(p, ring)) return false;
  for (std::size_t i = 0; i < ring.size(); ++i)
    if (distancePointSegment(p, ring[i], ring[(i + 1) % ring.size()]) == 0.0) return false;
  return true;
}

/// Whether an obstacle covers some of the wall's interior. Circles are decided exactly from the
/// centre; polygons by the area of their intersection, or, for polygons too small for the
/// region grid (1 um), by a vertex strictly inside the wall.
bool reachesIntoWall(const Obstacle& o, const Wall& wall, const Region& boundary) {
  if (o.type == ObstacleType::Circle) {
    double gap = INFINITY;
    for (std::size_t i = 0; i < wall.boundary.size(); ++i)
      gap = std::min(gap, distancePointSegment(o.center, wall.boundary[i], wall.boundary[(i + 1) % wall.boundary.size()]));
    return gap < o.radius || (gap > 0.0 && pointInRing(o.center, wall.boundary));
  }
  if (area(intersect(obstacleRegion(o, 1e-6), boundary)) > 0.0) return true;
  for (const Point& p : o.polygon)
    if (strictlyInside(p, wall.boundary)) return true;
  return false;
}

}  // namespace

void validateWall(const Wall& wall, const std::string& source) {
  const Region boundary = regionFromRings({wall.boundary});
  for (const auto& [point, field] : {std::pair{wall.start, "start"}, std::pair{wall.end, "end"}})
    if (point && !pointInRing(*point, wall.boundary))
      throw InputError(source, field, "(" + shortNumber(point->x) + ", " + shortNumber(point->y) + ") lies outside the wall");
  std::vector<Ring> obstacle_rings;
  for (std::size_t i = 0; i < wall.obstacles.size(); ++i) {
    if (!reachesIntoWall(wall.obstacles[i], wall, boundary))
      throw InputError(source, "obstacles[" + std::to_string(i) + "]", "lies entirely outside the wall");
    for (const Ring& ring : allRings(obstacleRegion(wall.obstacles[i], 1e-6))) obstacle_rings.push_back(ring);
  }
  if (!obstacle_rings.empty()) {
    const Region free = subtract(boundary, regionFromRings(obstacle_rings));
    if (area(free) <= 1e-9) throw InputError(source, "obstacles", "leave nothing of the wall to cover");
  }
}

}  // namespace coverbench
