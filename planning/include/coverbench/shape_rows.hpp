#pragma once
/// Rows of a line or rectangle tool on a gantry or a holonomic robot, planned for the shape itself,
/// not for its circumscribed disk (docs/metrics.md#tool-shapes), shared by the row planners
/// (zigzag, boustrophedon, trapezoidal): they differ only in the order the rows are painted.
///
/// In the frame's coordinates rows run along x. The shape stands square to them: half-width h
/// across (y), half-depth e along (x; a line has e = 0). A row runs from edge to edge of where its
/// centre may stand (the wall minus its outside and its obstacles grown by c, swept by the
/// rectangle [-e, e] x [-h, h]), so it paints to the edges; rows of their own take the bands the
/// regular rows leave beside obstacles. On a gantry every move between rows is lifted: it lowers
/// the shape at the heading of the row it begins (both engines' lifted rule). A holonomic robot
/// turns the shape on the wall at each row end, which sweeps (nearly) its circumscribed disk: its
/// rows are cut to end where that disk fits, and joined there on the wall (straight, or along the
/// disk's shortest route).
///
/// Where the rows alone leave too much of X (slanted or round edges, rows at a slant), loops run
/// first along the circumscribed disk's F boundary and the rows paint only what they left.
///
///   PlanResult r = planShapeRows(problem, disk_frame, options, angle_deg, budget,
///                                [](const ShapeRowPieces& rows, Point from, bool) { return nearestEndOrder(rows.pieces, from); });

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/region_ops.hpp"

namespace coverbench {

/// One free interval of one row of a region: [lo.x, hi.x] at height y.
struct RowInterval {
  std::size_t row = 0;
  double y = 0.0;
  RingCrossing lo, hi;
  bool done = false;
  Point lowEnd() const { return {lo.x, y}; }
  Point highEnd() const { return {hi.x, y}; }
};

/// Evenly spaced row heights over [y_min, y_max]: the first and last rows lie on the extremes (a
/// hair inside, so they cross the region properly) and no gap exceeds `max_spacing`.
std::vector<double> rowHeights(double y_min, double y_max, double max_spacing);

/// Free intervals of every row: crossings of each row with the region's rings, paired even-odd.
std::vector<std::vector<RowInterval>> rowIntervals(const std::vector<Ring>& rings, const std::vector<double>& ys);

/// A piece of a row the shape paints: its low-x end, then its high-x end (same y).
using RowPiece = std::pair<Point, Point>;

/// The shape's rows over a wall, before they are ordered.
struct ShapeRowPieces {
  std::vector<RowPiece> pieces;  ///< the regular rows' pieces (by height, then x), then the rows by obstacles
  Region centres;                ///< where the shape's centre may stand, square to the rows
  std::size_t rows = 0;          ///< regular rows
  std::size_t patches = 0;       ///< pieces of rows of their own beside obstacles
  double left_share = 0.0;       ///< of X, what the loops run first (if any) and every row leave
  bool expired = false;          ///< the time budget ran out before they were all found
};

/// The order rows are painted in: each piece's index, and whether it is painted from its high end.
using PieceOrder = std::vector<std::pair<std::size_t, bool>>;

/// Orders `rows.pieces`, beginning nearest `from`: where the loops run first end (`after_loops`),
/// else the lowest corner of the centres' box.
using OrderPieces = std::function<PieceOrder(const ShapeRowPieces& rows, Point from, bool after_loops)>;

/// From `from`, each time the nearest end of a piece not yet painted (rows next to each other
/// alternate; rows by obstacles are taken on the way).
PieceOrder nearestEndOrder(const std::vector<RowPiece>& pieces, Point from);

struct ShapeRowsOptions {
  double spacing = 0.0;      ///< the largest gap between rows (m)
  std::size_t loops = 1;     ///< loops run first, when the rows alone leave too much (0: never)
  double end_inset = 0.6;    ///< the loops' headland option (headland.hpp)
  double arc_tolerance = 1e-3;  ///< chords of the loops' arcs (m)
};

/// The plan of a line or rectangle tool (problem.tool) on a gantry or a holonomic robot, at
/// `angle_deg`, on `disk_frame` (the frame opened on the problem with the tool's circumscribed disk,
/// rows along x): loops when needed, the pieces in `order`, each joined by a lifted move (gantry)
/// or a move on the wall (holonomic; a piece it cannot reach counts as unreachable).
/// NoReachableArea when the shape fits nowhere square to the rows (or has nowhere to turn); Partial, with the share, when over 5 % of X is left; Timeout when
/// `budget` runs out. Stats rows, intervals, leftover_rows, rows_left_share, loops_first.
PlanResult planShapeRows(const Problem& problem, PlanFrame& disk_frame, const ShapeRowsOptions& options,
                         double angle_deg, const Budget& budget, const OrderPieces& order);

}  // namespace coverbench
