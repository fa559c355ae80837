// The line tool (path.hpp: ToolShape::Line) in the fast engine: where it turns, the gaps of the
// shapes it sweeps, and the rings its coverage and passes are measured on (docs/metrics.md#tool-shapes).
#pragma once

#include <cmath>
#include <vector>

#include "coverbench/clearance.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench::line_tool {

/// How the line turns at a waypoint between a move in direction d1 and one in direction d2: from
/// the half-line u1 (the unit left normal of d1) to u2 by the signed angle `sweep` in
/// [-pi/2, pi/2], the smaller rotation (a line is the same turned by half a circle). At a right
/// angle it turns the way the heading does. sweep 0: it does not turn (straight on, or back).
struct Turn {
  Point u1, u2;
  double sweep = 0.0;
};
Turn turnBetween(Point d1, Point d2);

/// A swept shape's gaps (m): to the wall's edge and to the nearest obstacle, each 0 where the
/// shape touches or crosses it (`outside`, `overlaps`: it does, by more than kValidityTolerance).
struct Gaps {
  double boundary = INFINITY;
  double obstacle = INFINITY;
  long nearest = -1;  ///< the nearest obstacle measured nearer than the cutoff (-1: none)
  bool outside = false;
  bool overlaps = false;
};
/// The rectangle the line of half-width h sweeps from a to b (a != b).
Gaps segmentGaps(const ClearanceField& field, Point a, Point b, double h, double cutoff);
/// The two sectors of radius h the line sweeps turning about p (turn.sweep != 0).
Gaps turnGaps(const ClearanceField& field, Point p, const Turn& turn, double h, double cutoff);

/// Sectors' arcs are chords through points on the arc with a sagitta of at most this fraction of
/// their radius h (and at most 50 um): each sector's area is short by under 1.4e-4 of it.
inline constexpr double kSectorSagitta = 1e-4;
/// What the line of half-width h sweeps with the tool on: a rectangle per tool-on move, and the
/// two sectors of each turn between two tool-on moves (zero-length moves are skipped: the turn is
/// between the moves around them). The path has no arcs.
std::vector<Ring> sweptRings(const Path& path, double h);

}  // namespace coverbench::line_tool
