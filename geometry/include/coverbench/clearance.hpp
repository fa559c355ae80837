#pragma once
/// Exact clearance queries of segments against a wall: the single source of truth for "does the
/// tool stay inside the wall and away from every obstacle". Used by the metrics engine to validate
/// every path and by planners to decide whether a straight move is allowed.
///
/// A segment is a moving tool centre. Distances are closed-form (point/segment/polygon/circle),
/// never sampled.

#include <cmath>
#include <cstdint>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Validity tolerance (metres): a gap this much smaller than required still counts as kept,
/// absorbing floating-point rounding only.
inline constexpr double kValidityTolerance = 1e-9;

/// Distances from one segment to the wall's features.
struct SegmentClearance {
  bool inside = false;             ///< the segment lies inside the boundary polygon
  double boundary_distance = 0.0;  ///< distance from the segment to the boundary's edges
  double obstacle_distance = INFINITY;  ///< distance to the nearest obstacle (0 if it touches one)
  /// That obstacle's index in Wall::obstacles (the first of the nearest measured); -1 when none was
  /// measured nearer than the cutoff.
  long nearest_obstacle = -1;
};

class ClearanceField {
 public:
  explicit ClearanceField(const Wall& wall);

  /// All distances for the segment [a, b] (a == b for a point). Obstacles farther than
  /// `obstacle_cutoff` may be reported as exactly `obstacle_cutoff` (saves work when the caller
  /// only needs to know "at least this far").
  SegmentClearance measure(Point a, Point b, double obstacle_cutoff = INFINITY) const;

  /// True when a tool disk of `radius` moving along [a, b] stays inside the boundary with at least
  /// `margin` to spare and keeps at least `clearance + margin` from every obstacle.
  bool segmentFree(Point a, Point b, double radius, double clearance, double margin) const;

  /// measure() for the circular arc from a to b of bulge `bulge` (Path::bulge; 0: the segment),
  /// in closed form: the distance between an arc and a point, a segment or a circle is the least
  /// of the ends' distances and of the one interior pair whose join is radial to the arc and
  /// square to the segment (0 where they cross).
  SegmentClearance measureArc(Point a, Point b, double bulge, double obstacle_cutoff = INFINITY) const;
  /// segmentFree() for that arc.
  bool arcFree(Point a, Point b, double bulge, double radius, double clearance, double margin) const;

  const Wall& wall() const { return *wall_; }

 private:
  double obstacleDistance(std::size_t i, Point a, Point b) const;
  /// Calls f(i) for every obstacle whose box may lie within `reach` of `box` (some more than
  /// once); false from f stops the scan and is returned.
  template <class F>
  bool forObstaclesNear(const Box& box, double reach, F&& f) const;

  const Wall* wall_;
  std::vector<Box> obstacle_boxes_;
  // Obstacles bucketed by box in a uniform grid (walls with many obstacles only).
  Box grid_box_;
  double grid_cell_ = 0.0;
  long grid_nx_ = 0, grid_ny_ = 0;
  std::vector<std::vector<std::uint32_t>> grid_;
};

}  // namespace coverbench
