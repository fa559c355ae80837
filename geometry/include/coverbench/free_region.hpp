#pragma once
/// The free centre region F = erode(boundary, r) minus dilate(obstacles, r + c), r = s / 2, as
/// polygons: a definition of the geometry layer, used by the planning toolkit (with a margin) and
/// by the fast metrics engine (without one).

#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Largest distance between an arc and the chords approximating it in the free region (metres).
inline constexpr double kArcTolerance = 5e-5;
/// How far inside the exact F the approximated free region is drawn (metres).
inline constexpr double kFreeSpaceMargin = kArcTolerance + 5e-6;

/// Rotates every coordinate of the wall about the origin (for sweep directions).
Wall rotateWall(const Wall& wall, double radians);

/// The free centre region of a wall for a tool, drawn `margin` metres inside the exact F with arcs
/// within `arc_tolerance`. The defaults give the planners' conservative F; the metrics engine asks
/// for margin 0 and a fine tolerance.
Region freeRegion(const Wall& wall, const ToolParams& tool, double margin = kFreeSpaceMargin,
                  double arc_tolerance = kArcTolerance);

}  // namespace coverbench
