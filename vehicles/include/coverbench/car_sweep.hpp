#pragma once
/// Planning for a car from the start (docs/vehicles.md, "Planning for a car: headlands and
/// turn-aware rows"): headland rings deep enough to turn in, painted first and driven as the car
/// can (smoothForCar), then rows inside them in an order whose every link is a Dubins or
/// Reeds-Shepp curve that stays in F, chosen by the curves' lengths.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/car.hpp"
#include "coverbench/headland.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {

/// What a sweep planner does for a car (its parameter `car_plan`): plan for the car itself
/// (headland rings and turn-aware rows, then fill rounds: the default), the same without the fill
/// rounds, or plan for a tool that turns on the spot and have runPlanner smooth the path (the
/// baseline every planner has).
enum class CarPlan { Headland, HeadlandNoFill, Smoothed };
/// The parameter `car_plan`, as sweep planners declare it (PlannerInfo::plans_for_car).
ParamSpec carPlanParam();
inline const std::vector<std::pair<std::string, CarPlan>>& carPlanChoices() {
  static const std::vector<std::pair<std::string, CarPlan>> choices{
      {"headland", CarPlan::Headland}, {"headland_no_fill", CarPlan::HeadlandNoFill}, {"smoothed", CarPlan::Smoothed}};
  return choices;
}

/// The problem for a tool that turns on the spot whose path will be smoothed for the car
/// (runPlanner does the smoothing): what `car_plan: smoothed` plans.
Problem asHolonomic(const Problem& problem);

/// How many headland rings a car needs and where rows end (HeadlandOptions::loops, end_inset):
/// rows end at least one turn radius inside F's edge, so a turn beyond a row's end fits, and the
/// rings paint everything between (the rows' round ends reach into the last ring's band).
struct CarHeadlandLayout {
  std::size_t loops = 1;
  double end_inset = 0.5;  ///< spacings inside the last ring
};
CarHeadlandLayout carHeadlandLayout(double spacing, double turn_radius);

/// The headland a sweep planner lays out for a car: at least `loops` rings and as many as the turn
/// radius needs, rows ending at least `end_inset` spacings inside the last (carHeadlandLayout),
/// offsets drawn with chords of `arc_tolerance`, rows along x or along y.
HeadlandOptions carHeadlandOptions(const Problem& problem, double spacing, std::size_t loops, double end_inset,
                                   double arc_tolerance, bool along_x);

/// CarRow::cell of a row that belongs to no cell of an order.
inline constexpr std::size_t kAnyCell = static_cast<std::size_t>(-1);

/// One row: a straight pass from a to b (or b to a), both ends in F; `line` numbers the rows'
/// lines (parallel, one spacing apart), from one side.
struct CarRow {
  Point a, b;
  std::size_t line = 0;
  bool row = true;  ///< false: a pass along an obstacle's edge (carHolePasses), no line
  /// The place of the row's cell in a planner's cell order (a cell decomposition's tour): the
  /// sweep takes the rows of the first cell in that order with rows left it may enter, and rows
  /// of no cell (kAnyCell), before any other row, as long as it reaches one of them.
  std::size_t cell = kAnyCell;
};

/// The headland round the obstacles, for a car: a ring round a window turns round its corners
/// tighter than any car (r + c + depth), so each hole ring of `loops` that has straight edges (2
/// spacings or longer) is replaced by passes along those edges, each extended straight past the
/// corner (up to 0.5 m, as far as it stays in F) so that it paints the corner and leaves room to
/// turn; for a forward-only car each end then moves back (up to a turn radius behind the corner)
/// until a turn radius straight ahead of it is free, and a pass left shorter than 2 spacings is
/// dropped. Those rings are taken out of `loops`. Rings without straight edges (round obstacles)
/// stay rings.
std::vector<CarRow> carHolePasses(Workspace& ws, std::vector<Ring>& loops, double spacing);

/// The order a car takes a stack of `m` rows on consecutive lines in, entering at line `p` (0 is
/// the line at the end of the stack it enters from), so that each row's U-turn to the next spans
/// at least `k` lines (k spacings of at least twice the turn radius: a half circle and a straight,
/// no loop). Blocks of at least 2k + 1 lines, all but the last of odd size b = 2h - 1, each
/// entered at its line p and left from its line p + h, h - 1 below the next block's line p; every
/// link spans h - 1 or h lines (or, in an even last block of 2g, g - 1 or g; in a last block of
/// exactly 2k, entered at its line k - 1, k or k + 1). Not `whole`: blocks of exactly 2k + 1 (the
/// last 2k + 2, or 2k as above), and the lines beyond them left out of the order. Empty when m <
/// 2k + 1 or p >= k (the sweep then takes those rows nearest first).
std::vector<std::size_t> carBlockOrder(std::size_t m, std::size_t k, std::size_t p = 0, bool whole = true);

struct CarSweep {
  Path path;
  CarSmoothing headland;        ///< the rings as the car drives them
  std::size_t rows = 0;         ///< rows given, and passes along what the rings' smoothing skipped
  std::size_t ring_passes = 0;  ///< of them, passes along what the rings' smoothing skipped
  std::size_t fill_passes = 0;  ///< passes of the fill round driven (not in `rows`)
  std::size_t strokes = 0;      ///< strokes driven after the fill rounds
  std::size_t painted_transits = 0;  ///< tool-off segments turned on where they pass over unpainted reach
  std::size_t unreached = 0;    ///< rows left out (said in `reason`): not reached, or dead ends both ways
  /// Of them, rows the car would be stuck in from either end: a forward-only car finds no loop
  /// from either end's exit (carCanLoop), or the car drove in and no curve, route or search took
  /// it on (a backtrack), both ways. The rest no curve or route reached.
  std::size_t dead_both_ways = 0;
  std::size_t unreached_rings = 0;  ///< rings no transit reached (coverRings)
  std::size_t links = 0;        ///< rows reached by one curve
  std::size_t routed = 0;       ///< rows reached along a route round obstacles, smoothed for the car
  std::size_t searched = 0;     ///< rows reached along a route searched over the car's motions
  std::size_t cusps = 0;        ///< reversals in the links (a Reeds-Shepp car)
  std::size_t backtracks = 0;   ///< rows driven into and given up (no curve left them)
  double undriven_m = 0.0;      ///< row length a routed link's turn replaced (tool off)
  bool timed_out = false;
  /// The budget ran out before the retries and fill rounds that follow the first sweep (carSweep)
  /// were done: the plan is what it had by then (partial, said in `reason`).
  bool rounds_timed_out = false;
  /// The rings were not driven first: from their end no row was reached, so they became passes
  /// ordered with the rows, the car starting along their longest segment the way they drive it
  /// (1) or the other way (2); 0: the rings first.
  int rings_as_passes = 0;
  /// The rings start at their first ring's ring_start-th longest edge (from 0, the longest): the
  /// car started in a pocket from the default start (carSweep); 0: the default.
  std::size_t ring_start = 0;
  /// A forward-only car's last row is one it cannot come out of (the path ends there).
  bool ended_in_dead_end = false;
  std::size_t dead_end_from = 0;  ///< then: the path's waypoints before the curve into that row
  CarRow dead_end_row;            ///< and that row
  bool dead_end_fill = false;     ///< it is a fill pass (counted in fill_passes, not in rows)
  std::string reason;
};

/// Drives the rings `loops` (joined by coverRings on `rings`, an empty builder of `ws`, the
/// problem's workspace) smoothed for the car (smoothForCar; where the car stops before half their
/// length, they start again at their first ring's longest edge, `rings` rebuilt so), then every
/// row it can, and a pass along each straight stretch of ring the smoothing skipped (ring
/// passes). Rows are taken along any direction they run in (all parallel). From where the car
/// is: the row end whose curve (Dubins for a forward-only car, Reeds-Shepp when it reverses) is
/// shortest, plus `line_penalty` times the spacing for each line the row lies above the lowest
/// unpainted line beside it (so the rows are taken in blocks, skipping as far as a turn needs and
/// coming back, not in sweeps across the whole wall), among the rows of the first cell of a cell
/// order (CarRow::cell) first when one is given; the curve is taken only if it lies in F
/// (pathFree). A forward-only car that enters a stack of rows (rows of one cell on consecutive
/// lines, each the only one beside the next, ends within a turn radius) at one of its first k
/// lines from either end takes the stack in carBlockOrder while those curves are free. When no
/// curve is free, a route round the obstacles (the workspace's transit planner) smoothed for the
/// car, or else, for the nearest rows, a route searched over the car's own motions
/// (searchCarRoute); when none leaves a row, the car goes back one row and marks that way in as a
/// dead end. Where the rings end facing F's edge, their last stretch is cut short until a curve
/// leaves it. Where no row is reached from where they end, the sweep is planned again with the
/// rings as passes taken with the rows, the car starting along their longest segment (either way;
/// CarSweep::rings_as_passes), kept when it paints more. A forward-only car that leaves most rows
/// out and starts in a pocket (a search of its motions from its first pose finds fewer than 5,000
/// poses) is planned for again with the rings started at their first ring's next longest edges
/// until one starts out of a pocket (CarSweep::ring_start), kept when it paints more. Then (`fill`) fill rounds: what the path leaves unpainted is found on a raster (cells of a
/// fifth of a spacing), each piece of it gets passes along its long axis, and the sweep goes on
/// through them from where it ended (or, where it cannot, is planned again with them taken last),
/// kept when it paints more. The result is checked for the car's rules (std::logic_error on a
/// slip).
CarSweep carSweep(Workspace& ws, PathBuilder& rings, const std::vector<Ring>& loops, const std::vector<CarRow>& rows,
                  double spacing, const Budget& budget, bool fill = true, double line_penalty = 0.5);

/// A sweep planner's plan for a car from its sweep (carSweep, whose rings `rings` built): the path
/// turned back into the wall's frame by `angle` (radians), `headland_rings`, the outcome
/// (recordOutcome), the sweep's statistics, status and reason (recordCarSweep), and planned_for_car.
PlanResult carSweepPlan(const CarSweep& sweep, const PathBuilder& rings, std::size_t headland_rings, double angle,
                        std::size_t free_components);

/// The plan's statistics (car_rows, car_rows_unreached, car_rows_dead_both_ways, car_links, car_routed_links,
/// car_searched_links, car_ends_in_dead_end, car_rings_stopped, car_cusps, car_backtracks,
/// car_ring_fillets, car_ring_turns, car_ring_searched_skips, car_ring_passes,
/// car_skipped_segments, car_undriven_m), its
/// status (Partial when rows were left out or time ran out) and its reason.
void recordCarSweep(PlanResult& result, const CarSweep& sweep);

}  // namespace coverbench
