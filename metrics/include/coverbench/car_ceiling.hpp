#pragma once
/// What a forward-only car (a Dubins car) could paint at best on a wall: an estimate on a lattice
/// of poses (docs/metrics.md, "What a car could paint at best"). It reads the wall and the tool
/// only, never a path, and shares no code with any planner.
///
/// A pose (position, heading) is viable when the car can drive on from it forever without leaving
/// F, and came from a pose it could have driven forever before: the greatest set of poses each
/// with a successor (and a predecessor) in the set. A path's poses are viable except on its
/// head (before it first reaches a pose it could come back to) and its tail (after it last
/// leaves one): there it drives into a dead end it cannot leave, or out of one. Its viable poses
/// lie in one component of them (poses joined by motions). `interior` is what the tool paints
/// from the best component's poses; `with_ends` adds what a head and a tail can paint in the
/// dead ends (connected pieces of F outside that component's cells): in each, at most what the
/// piece adds and at most a band of the tool's width along the longest chain of poses a car
/// drives there. A path never leaves F, so both are taken in the piece of F where they are
/// largest.

#include <cstddef>
#include <string>

#include "coverbench/path.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

struct CarCeilingOptions {
  double turn_radius = 0.5;
  /// The lattice's cell (m); raised when the wall would need more than max_states poses.
  double resolution = 0.02;
  std::size_t headings = 72;
  std::size_t max_states = 60'000'000;
};

struct CarCeiling {
  double resolution = 0.0;   ///< the cell used (m)
  std::size_t headings = 0;  ///< headings per cell
  double step = 0.0;         ///< length of each motion on the lattice (m)
  std::size_t states = 0;    ///< free poses
  std::size_t viable = 0;    ///< of them, viable both ways
  std::size_t pieces = 0;    ///< F's pieces on the lattice (8-connected free cells); a path stays in one
  std::size_t components = 0;  ///< the viable poses' components (joined by motions); a path's viable poses lie in one
  /// Areas on the lattice (m^2): what a tool reaches at all (a tool that turns on the spot, in
  /// every piece of F), what a forward-only car paints from viable poses, and that plus what its
  /// head and tail add in dead ends (these two in the best piece of F).
  double reachable_area = 0.0, interior_area = 0.0, with_ends_area = 0.0;
  /// interior_area / reachable_area and with_ends_area / reachable_area: read a forward-only car's
  /// coverage_reachable against these.
  double interior = 0.0, with_ends = 0.0;
  /// R of the piece of F that holds the most of it (m^2), and that over reachable_area: all a path
  /// can paint, a car that reverses (or a tool that turns on the spot) included.
  double largest_piece_area = 0.0, largest_piece = 0.0;
};

/// The estimate for a forward-only car of `options.turn_radius` carrying `tool` on `wall`.
CarCeiling forwardCarCeiling(const Wall& wall, const ToolParams& tool, const CarCeilingOptions& options);

}  // namespace coverbench
