// The wall model's checks: input errors as one line, numbers as messages show them, and a wall's
// geometric sense (obstacles inside, something left to cover).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
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
/// centre; polygons by a vertex strictly inside the wall (its first few: cheap, and what an
/// obstacle on a wall usually has), else by the area of their intersection, or, for polygons too
/// small for the region grid (1 um), by any vertex strictly inside the wall.
template <class BoundaryRegion>
bool reachesIntoWall(const Obstacle& o, const Region& obstacle, const Wall& wall, BoundaryRegion boundary) {
  if (o.type == ObstacleType::Circle) {
    double gap = INFINITY;
    for (std::size_t i = 0; i < wall.boundary.size(); ++i)
      gap = std::min(gap, distancePointSegment(o.center, wall.boundary[i], wall.boundary[(i + 1) % wall.boundary.size()]));
    return gap < o.radius || (gap > 0.0 && pointInRing(o.center, wall.boundary));
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(4, o.polygon.size()); ++i)
    if (strictlyInside(o.polygon[i], wall.boundary)) return true;
  if (area(intersect(obstacle, boundary())) > 0.0) return true;
  for (const Point& p : o.polygon)
    if (strictlyInside(p, wall.boundary)) return true;
  return false;
}

}  // namespace

void validateWall(const Wall& wall, const std::string& source) {
  for (const auto& [point, field] : {std::pair{wall.start, "start"}, std::pair{wall.end, "end"}})
    if (point && !pointInRing(*point, wall.boundary))
      throw InputError(source, field, "(" + shortNumber(point->x) + ", " + shortNumber(point->y) + ") lies outside the wall");
  // The boundary's region is built only when a check needs it: Clipper's scanbeams cost about
  // n x (edges crossing a scanline), seconds for a 25,000-vertex star, and most walls need it not.
  std::optional<Region> boundary;
  auto boundaryRegion = [&]() -> const Region& {
    if (!boundary) boundary = regionFromRings({wall.boundary});
    return *boundary;
  };
  std::vector<Ring> obstacle_rings;
  double obstacles_area = 0.0;
  for (std::size_t i = 0; i < wall.obstacles.size(); ++i) {
    const Region obstacle = obstacleRegion(wall.obstacles[i], 1e-6);
    if (!reachesIntoWall(wall.obstacles[i], obstacle, wall, boundaryRegion))
      throw InputError(source, "obstacles[" + std::to_string(i) + "]", "lies entirely outside the wall");
    obstacles_area += area(obstacle);
    for (const Ring& ring : allRings(obstacle)) obstacle_rings.push_back(ring);
  }
  if (!obstacle_rings.empty()) {
    // What is free is at least the wall's area less every obstacle's: when that is clearly more
    // than nothing, the subtraction cannot say otherwise.
    if (std::fabs(signedArea(wall.boundary)) - obstacles_area > 1e-6) return;
    const Region free = subtract(boundaryRegion(), regionFromRings(obstacle_rings));
    if (area(free) <= 1e-9) throw InputError(source, "obstacles", "leave nothing of the wall to cover");
  }
}

}  // namespace coverbench
