#pragma once
/// Arcs as arcs. F's boundary is round wherever the tool turns around a corner of an obstacle or
/// into a reflex corner of the wall: a circle of radius r + c (or r) about that corner, and
/// loops inside it are concentric circles. The free region holds those circles as chains of
/// short chords (within kArcTolerance), and a path that follows F's boundary, a boundary loop, or
/// a transit wrapped around an obstacle inherits the chords: a quarter circle of 0.07 m is about
/// 20 waypoints, each a heading change of a few degrees that a time model stopping at waypoints
/// charges as a stop. Here such a chain becomes the arc it traces (Path::bulge), checked exactly
/// before it is used, so a path's waypoints and turns describe its shape.

#include <cstddef>

#include "coverbench/path.hpp"

namespace coverbench {

class Workspace;
struct PlanResult;
struct Problem;

/// A chain of chords is fitted by one arc when every vertex lies within this distance of the arc
/// (metres): F's own tolerance for its arcs (kArcTolerance), far above Clipper's rounding of their
/// vertices (kRegionResolution). (1e-5 leaves arcs of traced round obstacles as chords; 1e-4 fits
/// no more than this in the default experiment.)
inline constexpr double kArcFitTolerance = 5e-5;
/// ... and every chord lies within this of the arc (metres): the chords of F's own arcs (within
/// kArcTolerance of them) and no coarser, so the painted band moves by at most that. Loops offset
/// at a coarser tolerance (a headland's inner loops, the spiral's rings) keep their chords: as
/// arcs they would move their paint by up to their tolerance. In the default experiment a looser
/// 1.5e-3 moved coverage by up to 6.1e-5; this one by up to 1.9e-5 (scripts/compare_results.py).
inline constexpr double kArcFitSagitta = 1.5e-4;
/// ... and turns by at most this at each vertex (radians, 20 degrees): a corner is a corner.
inline constexpr double kArcFitMaxTurn = 0.35;
/// An arc replaces at least this many chords.
inline constexpr std::size_t kArcFitMinChords = 3;

/// Whether the arc (or line, bulge 0) from a to b keeps the tool valid with kPlanningMargin to
/// spare (ClearanceField::arcFree: distances in closed form).
bool arcFree(const Workspace& ws, Point a, Point b, double bulge);
/// Every segment of the path is free (arcFree).
bool pathFree(const Workspace& ws, const Path& path);

struct ArcFit {
  std::size_t arcs = 0;     ///< arcs written
  std::size_t chords = 0;   ///< chords they replace
  std::size_t refused = 0;  ///< chains that fitted an arc the exact check refused (kept as chords)
};

/// The path with every chain of at least kArcFitMinChords straight segments of one tool state
/// that lie on one circle (kArcFitTolerance, kArcFitSagitta, kArcFitMaxTurn, turning one way,
/// at most a half circle per arc) replaced by that arc, where arcFree holds. A gantry's lifted
/// moves, segments that are already arcs and everything else stay as they are.
Path withBoundaryArcs(const Path& path, const Workspace& ws, ArcFit& fit);

/// What planners built on PathBuilder call on their finished path: withBoundaryArcs, and the
/// statistics boundary_arcs and boundary_arc_chords. Nothing is changed when the problem says
/// the path will be smoothed for a car (Problem::straight_segments_only), whose smoothing reads
/// straight segments.
void fitBoundaryArcs(PlanResult& result, const Workspace& ws, const Problem& problem);

}  // namespace coverbench
