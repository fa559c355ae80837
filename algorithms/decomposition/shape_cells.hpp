#pragma once
/// A line or rectangle tool on a gantry or a holonomic robot, in the decomposition planners: the shape's own rows
/// (shape_rows.hpp, the same rows zigzag paints) painted cell by cell. The region where the
/// shape's centre may stand is decomposed as the planner decomposes (boustrophedon or
/// trapezoidal), each row piece belongs to the cell that holds it, the cells are ordered by the
/// planner's order (cell_ordering.hpp), and in each cell its pieces are painted from one end to
/// the other, alternating direction. Moves between pieces are lifted on a gantry and on the wall
/// for a holonomic robot (planShapeRows).

#include <cstddef>
#include <functional>

#include "cell_decomposition.hpp"
#include "cell_ordering.hpp"
#include "coverbench/shape_rows.hpp"

namespace coverbench::decomposition {

/// The pieces' order, and what it took.
struct ShapeCellOrder {
  PieceOrder order;              ///< every piece once
  std::size_t cells = 0;         ///< cells of the centres' region holding a piece
  std::size_t contacts = 0;      ///< pairs of touching cells among them
  std::size_t outside = 0;       ///< pieces no cell holds (painted last, nearest end first); 0 expected
  double estimated_cost = 0.0;   ///< the tour's estimate, in `cost`'s unit
};

/// Orders `rows.pieces` (rows along x) cell by cell; `cost` gives the tour's start and end (in the
/// rows' frame) and what a move between cells costs; `keep_going` is polled by the ordering.
ShapeCellOrder orderByCells(const ShapeRowPieces& rows, Kind kind, Order order, const TourCost& cost,
                            const std::function<bool()>& keep_going);

}  // namespace coverbench::decomposition
