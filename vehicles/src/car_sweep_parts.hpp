#pragma once
// The pieces of the car's sweep (coverbench/car_sweep.hpp, docs/vehicles.md) that its source files
// share: constants, small path helpers, and the stages carSweep runs. Private to vehicles/src.
//   car_layout.cpp      headland layout, passes round holes, block orders
//   car_rings.cpp       the headland rings driven, and passes along what their smoothing skipped
//   car_row_sweep.cpp   one sweep over the rows (sweepOnce)
//   car_paint_grid.cpp  the raster of what a path paints, and the fill passes found on it
//   car_strokes.cpp     strokes and painting transits after the fill rounds
//   car_sweep.cpp       carSweep: the first sweep, its retries, the fill rounds; the plan's record

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "coverbench/car_sweep.hpp"

namespace coverbench::vehicle_detail {

/// Strokes after the fill rounds (forward-only): at most this many, searched for over at most
/// kStrokeBudget poses in all, kStrokeExpansions each...
constexpr std::size_t kStrokes = 400;
constexpr std::size_t kStrokeBudget = 1000000;
constexpr std::size_t kStrokeExpansions = 20000;
/// ...each a spacing long at least, where at least kStrokeOpen of its cells are unpainted (or
/// kStrokeOpenLast, where the search finds none), and going on by half spacings (up to
/// kStrokeSteps) while kStrokeOpenOn of each step's are. The route to a stroke paints where
/// kStrokeOpenOn of a segment's cells are unpainted.
constexpr double kStrokeOpen = 0.5;
constexpr double kStrokeOpenLast = 0.25;
constexpr double kStrokeOpenOn = 0.3;
constexpr int kStrokeSteps = 80;
/// Poses searched from a stroke's end for a way back to the path (else it counts as a dead end).
constexpr std::size_t kStrokeLoopExpansions = 3000;
/// A stroke the search at cells of R/2 does not find is searched for at cells of R/4, then R/8
/// (searchCarUntil's fineness), up to this fineness.
constexpr int kStrokeFinestSearch = 4;
/// Poses a search over the car's own motions (searchCarRoute) takes at most to reach a row.
constexpr std::size_t kSearchExpansions = 800;
/// A fill round is kept when what it paints more is at least this share of a band one spacing
/// wide along the path it adds (rows paint about 0.8; fill passes, reached by long curves, 0.02-0.09:
/// below 0.03, as on obstacle-free walls where only the corners are left, the round is not kept).
constexpr double kFillMinYield = 0.03;

/// The path's first `waypoints` waypoints (and the segments between them).
inline Path upTo(const Path& path, std::size_t waypoints) {
  Path out = path;
  out.waypoints.resize(waypoints);
  out.tool_on.resize(waypoints - 1);
  if (!out.bulge.empty()) out.bulge.resize(waypoints - 1);
  return out;
}

/// Appends `piece` (which starts where `out` ends) to `out`.
inline void append(Path& out, const Path& piece) {
  for (std::size_t k = 0; k < piece.segments(); ++k) out.arcTo(piece.waypoints[k + 1], piece.bulgeOf(k), piece.tool_on[k]);
}

/// The length of a path, or of its painted segments only.
inline double pathLength(const Path& path, bool painted_only = false) {
  double length = 0.0;
  for (std::size_t k = 0; k < path.segments(); ++k)
    if (path.tool_on[k] || !painted_only) length += segmentLength(path, k);
  return length;
}

/// Whether `cells` (unpainted cells of the reach, cells of the reach) has some reach and at least
/// `share` of it unpainted.
inline bool enoughOpen(std::pair<std::size_t, std::size_t> cells, double share) {
  return cells.second > 0 && static_cast<double>(cells.first) >= share * static_cast<double>(cells.second);
}

/// Whether a fill round that paints `gained` m² more for `driven` m more path is kept: it paints
/// at least kFillMinYield of a band one spacing wide along what it adds (and something).
inline bool worthIt(double gained, double driven, double spacing) {
  return gained > 0.0 && gained >= kFillMinYield * spacing * std::max(driven, 0.0);
}

/// A forward-only car's pass from a to b, each end moved back (by up to `max_cut_a` at a, up to
/// `max_cut_b` at b, in steps of a quarter turn radius) until a turn radius straight ahead of it is
/// free: room to turn out of it, whichever way the pass is driven. Whether the pass still runs at
/// least `min_length` its way (else it is not worth a pass). (car_layout.cpp)
bool leaveRoomToTurn(Workspace& ws, Point& a, Point& b, double rho, double max_cut_a, double max_cut_b,
                     double min_length);

/// The headland rings `loops`, thinned, joined by coverRings on `rings` and driven as the car can
/// (smoothForCar) into out.headland, out.unreached_rings, out.ring_start and out.rings_as_passes
/// (sweepOnce's rings: see there). (car_rings.cpp)
void driveRings(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, double spacing, int rings_as_passes,
                std::size_t ring_start, CarSweep& out);

/// The passes along what the rings' smoothing left undriven (`undriven`): each straight stretch
/// two spacings or longer (for a forward-only car, also a turn radius or longer, ending short of
/// F's edge ahead so that it can turn out of it), and each run of shorter pieces along a line.
/// Appended to `rows`, with `run_pass` saying which are made of runs; returns how many.
/// (car_rings.cpp)
std::size_t addRingPasses(Workspace& ws, const std::vector<std::pair<Point, Point>>& undriven, double spacing,
                          std::vector<CarRow>& rows, std::vector<char>& run_pass);

/// carSweep without its fill rounds: the rings, then `given` and the ring passes, then the passes
/// `fill` (taken last; one the car does not reach is not a row left out). With `from`, no rings:
/// the sweep goes on from the end of that path (a fill round), which it never cuts back.
/// (car_row_sweep.cpp)
CarSweep sweepOnce(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& given,
                   const std::vector<CarRow>& fill, double spacing, const Budget& budget, double line_penalty,
                   const Path* from = nullptr, int rings_as_passes = 0, std::size_t ring_start = 0);

class PaintGrid;

/// Strokes through what out.path leaves unpainted, for a forward-only car (see car_strokes.cpp).
/// `grid` shows what out.path paints (`painted_before`), before and after.
void strokes(Workspace& ws, CarSweep& out, PaintGrid& grid, double painted_before, double spacing, double rho,
             const Budget& budget);

/// A car's transits paint where they pass over enough unpainted reach (kStrokeOpenOn), as a
/// stroke's route does: the path's tool-off segments in order, each against what the path paints
/// and the transits turned on before it. `grid` shows what the path paints. (car_strokes.cpp)
void paintTransits(CarSweep& out, PaintGrid& grid);

}  // namespace coverbench::vehicle_detail
