#pragma once
/// Boolean operations and offsets on regions. Implemented with Clipper (integer coordinates at
/// 1 micrometre); callers see only CoverBench value types.
///
/// Offsets use round joins. Clipper places arc vertices on the true arc, so chords lie inside the
/// exact rounded offset; callers that need a conservative result add the arc tolerance to their
/// margin (see FreeSpace).

#include "coverbench/geometry.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Coordinates are snapped to this grid (metres) when entering Clipper.
inline constexpr double kRegionResolution = 1e-6;

/// Rings of a region (outer rings and holes), each as a closed ring.
std::vector<Ring> allRings(const Region& region);

/// Where a horizontal line crosses a ring edge: at x, on edge `edge` (from vertex `edge` to the
/// next) of ring `ring`.
struct RingCrossing {
  double x = 0.0;
  std::size_t ring = 0;
  std::size_t edge = 0;
};
/// The crossings of the lines y = ys[i] (ascending, evenly spaced) with the rings' edges, per
/// line sorted by x: a region's inside along a line is between crossings 0 and 1, 2 and 3, ...
/// Half-open (an edge spans lo <= y < hi), so a vertex on a line counts once; horizontal edges
/// cross nothing. Each edge is handed only the lines it spans: the cost is the edges plus the
/// crossings, not lines times edges. (Vertical lines: pass the rings with x and y swapped.)
std::vector<std::vector<RingCrossing>> scanlineCrossings(const std::vector<Ring>& rings, const std::vector<double>& ys);

/// Offsets the region by `delta` metres (positive grows, negative shrinks) with round joins whose
/// chords deviate at most `arc_tolerance` metres from the true arc.
Region offsetRegion(const Region& region, double delta, double arc_tolerance);
/// The union of the capsules of `radius` around every segment of every polyline (a one-point
/// polyline gives a disk). Round caps and joins; chords within `arc_tolerance` of the arcs.
Region sweptRegion(const std::vector<std::vector<Point>>& polylines, double radius, double arc_tolerance);

/// Douglas-Peucker simplification of every ring: the result's boundary stays within `tolerance`
/// metres of the original (either way). Keeps later offsets from multiplying the many short
/// chords of fine arcs.
Region simplifyRegion(const Region& region, double tolerance);
/// The Minkowski sum of the region and the segment from -half to +half: everything the region
/// passes over when moved along that segment.
Region sweepAlong(const Region& region, Point half);
Region unite(const Region& a, const Region& b);
Region intersect(const Region& a, const Region& b);
Region subtract(const Region& a, const Region& b);
/// Builds a region from rings of any orientation (non-zero fill), e.g. obstacles that overlap.
Region regionFromRings(const std::vector<Ring>& rings);

/// The points inside at least `k` (>= 1) of the rings (each taken counter-clockwise, so a
/// point's winding number is how many contain it): one Clipper union with k - 1 clockwise copies
/// of a box around them all, filled where the winding stays positive.
Region coveredAtLeast(const std::vector<Ring>& rings, int k);
/// The area of coveredAtLeast(rings, k) (m^2), without building the region (Clipper's paths, not
/// its tree: no hole is matched to its outer ring, which for many small holes is most of the cost).
double coveredAtLeastArea(const std::vector<Ring>& rings, int k);

/// A polygon containing the circle, with every vertex within `tolerance` of the circle.
Ring circumscribedCircle(Point center, double radius, double tolerance);
/// The obstacle as a region (circles circumscribed within `tolerance`).
Region obstacleRegion(const Obstacle& obstacle, double tolerance);

}  // namespace coverbench
