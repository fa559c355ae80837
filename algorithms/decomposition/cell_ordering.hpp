#pragma once
/// The order in which a decomposition planner covers its cells, and how it enters each one.
///
/// A cell is covered from one end to the other in one of four orientations (which end first,
/// first pass up or down), each with its own entry and exit corner. Cells form an undirected
/// Boost.Graph graph: an edge per pair of touching cells, weighted by the distance between their
/// nearest corners; separate parts are joined by edges between their nearest cells, so every
/// strategy sees one graph. Once a strategy has fixed the sequence, every cell's orientation is
/// chosen by dynamic programming over the straight distances from each cell's exit to the next
/// cell's entry.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"

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
  double estimated_cost = 0.0;  ///< the transitions' estimated length (metres)
};

/// Orders the cells. `keep_going` is polled by the 2-opt loops; when it says stop, the best order
/// so far is returned (still a permutation of all cells).
Ordering orderCells(const std::vector<CellEnds>& cells, const std::vector<CellLink>& links, Order order,
                    const std::function<bool()>& keep_going);

}  // namespace coverbench::decomposition
