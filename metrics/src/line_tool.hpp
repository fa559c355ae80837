// The line and rectangle tools (path.hpp: ToolShape) in the fast engine: where they turn, the gaps
// of the shapes they sweep, and the rings their coverage and passes are measured on
// (docs/metrics.md#tool-shapes). A rectangle of half-width h and half-depth e is a line of
// half-width h grown by e along the heading: every function takes e, and a line is e = 0.
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "coverbench/clearance.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench::line_tool {

/// A move from a to b.
struct Segment {
  Point a, b;
};
/// How the line turns at a waypoint between the move m1 and the move m2: from the half-line u1
/// (the unit left normal of m1) to u2 by the signed angle `sweep` in [-pi/2, pi/2], the smaller
/// rotation (a line is the same turned by half a circle). At a right angle it turns the way the
/// heading does. sweep 0: it does not turn (straight on, or back). Whether it turns, and which
/// way, are decided exactly from the four points (the signs of the moves' dot and cross
/// products), as the exact judge decides them.
struct Turn {
  Point u1, u2;
  double sweep = 0.0;
};
Turn turnBetween(Segment m1, Segment m2);

/// A swept shape's gaps (m): to the wall's edge and to the nearest obstacle, each 0 where the
/// shape touches or crosses it (`outside`, `overlaps`: it does, by more than kValidityTolerance).
struct Gaps {
  double boundary = INFINITY;
  double obstacle = INFINITY;
  long nearest = -1;  ///< the nearest obstacle measured nearer than the cutoff (-1: none)
  bool outside = false;
  bool overlaps = false;
};
/// The rectangle the tool of half-width h and half-depth e sweeps from a to b (a != b): square to
/// b - a, 2h wide, from e behind a to e past b.
Gaps segmentGaps(const ClearanceField& field, Point a, Point b, double h, double e, double cutoff);
/// The sectors the tool sweeps turning about p (turn.sweep != 0): one from each corner, of radius
/// hypot(h, e), from the corner's direction before the turn to its direction after (a line's two
/// ends; a rectangle's four corners).
Gaps turnGaps(const ClearanceField& field, Point p, const Turn& turn, double h, double e, double cutoff);
/// The direction from p of one corner of each opposite pair, before (`first`) and after (`second`)
/// the turn, as unit vectors: {u} for a line, those of {h u + e t, h u - e t} for a rectangle (t:
/// the heading, u its left normal). The opposite corners' are their negatives.
std::vector<std::pair<Point, Point>> turnCorners(const Turn& turn, double h, double e);

/// Sectors' arcs are chords through points on the arc with a sagitta of at most this fraction of
/// their radius h (and at most 50 um): each sector's area is short by under 1.4e-4 of it.
inline constexpr double kSectorSagitta = 1e-4;
/// What the tool of half-width h and half-depth e sweeps with the tool on: a rectangle per tool-on
/// move, and the sectors of each turn between two tool-on moves (zero-length moves are skipped:
/// the turn is between the moves around them). The path has no arcs.
std::vector<Ring> sweptRings(const Path& path, double h, double e);

}  // namespace coverbench::line_tool
