#pragma once
/// The order in which a decomposition planner covers its cells, and how it enters each one.
///
/// A cell is covered from one end to the other in one of four orientations (which end first,
/// first pass up or down), each with its own entry and exit corner. Cells form an undirected
/// Boost.Graph graph: an edge per pair of touching cells, weighted by the distance between their
/// nearest corners; separate parts are joined by edges between their nearest cells, so every
/// strategy sees one graph. Once a strategy has fixed the sequence, every cell's orientation is
/// chosen by dynamic programming over the straight moves from each cell's exit to the next
/// cell's entry (and from the start and to the end, when the path has them).

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/motion.hpp"

namespace coverbench::decomposition {

enum class Order {
  Dfs,     ///< depth-first discovery order over the cell graph (seed 002)
  Greedy,  ///< from each exit, the unvisited cell entry nearest in a straight line
  Tsp,     ///< Boost's metric_tsp_approx tour, the DFS order and the greedy order, each improved
           ///< by 2-opt (reversing a stretch also covers its cells backwards) and single-cell
           ///< moves over exact entry and exit corners; the cheapest is kept
};

/// How a cell can be covered: entry and exit points for orientation o in 0..3 (bit 0: start at
/// the right end and move left; bit 1: the first pass goes down).
struct CellEnds {
  Point entry[4];
  Point exit[4];
  /// The orientation that covers the cell backwards: it enters at exit[o] and leaves at entry[o].
  int reverse[4] = {0, 1, 2, 3};
  Point centre;
};

/// A pass's two ends: its low end, then its high end.
using PassEnds = std::pair<Point, Point>;

/// The CellEnds of a cell covered by `count` parallel passes in turn, alternating direction, the
/// first `front` and the last `back` in their order; `centre` as given.
CellEnds alternatingEnds(const PassEnds& front, const PassEnds& back, std::size_t count, Point centre);

/// Two cells that touch.
struct CellLink {
  std::size_t a = 0, b = 0;
};

struct Visit {
  std::size_t cell = 0;
  int orientation = 0;
};

struct Ordering {
  std::vector<Visit> visits;  ///< every cell exactly once
  double estimated_cost = 0.0;  ///< the TourCost's estimate (metres or seconds)
};

/// What the move from one visit's exit to the next visit's entry costs, from its straight length:
/// the length itself (the objectives `length` and `turns`: the moves between cells add the same
/// turns whatever the order), or, for the objective `time`, the time to drive it from standstill
/// to standstill under the time model (a cell's last pass ends in a turn and the next cell's first
/// pass begins with one) plus two turns' fixed cost. The time is concave in the length, so the
/// cheapest order under it is not always the shortest.
struct MoveCost {
  std::optional<MotionLimits> clock;  ///< nothing: the length
  double operator()(double length) const { return clock && length != 0.0 ? timed(length) : length; }
  double timed(double length) const;  ///< the clock's cost of a move of that length
  const char* unit() const { return clock ? "s" : "m"; }
};

/// What an order costs: its moves between visits and, where the path must begin or end at a
/// point (the wall's start and end), the move from the start to the first visit's entry and from
/// the last visit's exit to the end, each by `move`.
struct TourCost {
  MoveCost move;
  std::optional<Point> start, end;
};

/// Orders the cells, minimising the TourCost. `keep_going` is polled by the 2-opt loops; when it
/// says stop, the best order so far is returned (still a permutation of all cells).
Ordering orderCells(const std::vector<CellEnds>& cells, const std::vector<CellLink>& links, Order order,
                    const std::function<bool()>& keep_going, const TourCost& cost = {});

}  // namespace coverbench::decomposition
