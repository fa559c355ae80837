// A ring's simplicity by CGAL's sweep (Polygon_2_algorithms' is_simple_2: Shamos-Hoey over exact
// predicates on the doubles as given), O(n log n): the only CGAL unit of the geometry layer,
// kept apart so CGAL's headers and flags reach nothing else of it.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <vector>

#include "ring_simplicity.hpp"

namespace coverbench::detail {

bool edgesMeetOnlyAtSharedVertices(const Ring& ring) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_2> points;
  points.reserve(ring.size());
  for (const Point& p : ring) points.emplace_back(p.x, p.y);
  return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

}  // namespace coverbench::detail
