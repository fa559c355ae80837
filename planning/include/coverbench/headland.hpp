#pragma once
/// Boundary loops and the rows inside them, for sweep planners (zigzag and the decomposition
/// planners).
///
/// A loop along a ring of F paints a band one tool width wide centred on that ring. Rows that ran
/// on F's edge would paint that band a second time. So the rows keep one spacing clear of the
/// last loop across their direction (the first row's band meets the loop's band edge to edge) and
/// end `end_inset` spacings inside it along their direction (at 0.5, where the loop's band
/// begins: the row's round end lies in the band, so no sliver is left between row ends; the
/// default 0.6 paints less twice and leaves small scallops). A row runs as far as F reaches
/// within half a spacing either side of it, which keeps the band under an obstacle between two
/// rows painted. What loops and rows still miss can be found exactly afterwards and given short
/// extra passes (coverLeftovers, the planners' fill_leftovers).

#include <cstddef>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/sweep_search.hpp"

namespace coverbench {

class PathBuilder;
class Workspace;

struct Headland {
  std::vector<Ring> loops;  ///< the loop rings, outermost level first (every ring of each level)
  Region inner;             ///< one spacing inside the last loop's outer rings (its extent places the rows)
  Region ends;              ///< where rows may run along their direction: half a spacing inside it
  Box row_span;             ///< where the first and last rows lie: `inner`'s extent, grown to reach F's thin parts beyond it
  Region unpainted;         ///< what the loops leave to the rows: one tool radius inside the last loop (if asked)
};

struct HeadlandOptions {
  double spacing = 0.1;        ///< between rows, and between loops (metres)
  double radius = 0.05;        ///< the tool's radius s / 2 (metres)
  std::size_t loops = 1;       ///< boundary loops
  double end_inset = 0.6;      ///< where rows end: this many spacings inside the last loop, in [0, 1]
  double arc_tolerance = 1e-3; ///< of the offsets (metres)
  bool along_x = true;         ///< rows parallel to x (else to y)
  bool with_unpainted = false; ///< compute Headland::unpainted (for coverLeftovers)
};

/// The loops and row regions of `free`, the part of the workspace's F a planner covers. With no
/// loop, `inner` and `ends` are `free` itself (rows from edge to edge) and `unpainted` is empty
/// (nothing is checked afterwards). Every region lies inside F.
///
/// `end_inset` 0.5 ends a row where the loop's band begins: its round end lies in the band, and
/// nothing is left between row ends. A larger inset paints less twice and leaves small scallops
/// between the ends of rows that no turn joins (zigzag on a 5 m x 5 m wall at s = 0.1 m: 0.5
/// gives overlap 0.0195 and coverage 0.99996 (the four corners), 0.6 gives 0.0157 and 0.99994,
/// 0.8 gives 0.0084 and 0.99958, 1.0 gives 0.0024 and 0.99785; docs/planner_quality.md). Above
/// 0.5, thin parts of F (a corridor too narrow for the deeper inset) keep rows ending at 0.5.
/// The default 0.6 paints 12 % less twice than 0.5 in the default experiment, for a median
/// coverage 0.0001 lower. Below 0.5 rows run into the loop's band, at 0 to its line (within the
/// offsets' tolerance): more paint twice, and with a sprayed fan's profile a more even coat
/// (docs/deposition.md, "With a gun whose flow follows the speed").
Headland headland(const Workspace& ws, const Region& free, const HeadlandOptions& options);

/// A piece smaller than this many squared spacings gets no pass of its own: reaching it would
/// paint more again than it adds. The corner of a rectangle leaves one of (1 - pi/4) / 4 = 0.054.
inline constexpr double kMinLeftoverArea = 0.25;

struct Leftovers {
  std::size_t pieces = 0;          ///< pieces covered by a pass or a loop of their own
  std::size_t unreachable = 0;     ///< pieces no collision-free move reached
  std::size_t small_pieces = 0;    ///< pieces left out on purpose (below kMinLeftoverArea)
  double small_area = 0.0;         ///< their total area (m²)
};

/// Covers what the loops and rows left unpainted: the parts of `unpainted` outside the tool's
/// capsules around the path's tool-on segments from waypoint `from` on. Each piece of at least
/// kMinLeftoverArea spacing² gets one straight pass through its middle along the rows' direction
/// (`along_x`: rows parallel to x, else to y) when the piece is thinner than the tool across it
/// and the pass is free, else a loop along each of its rings (a piece no tool disk fits in is
/// painted entirely by its boundary).
Leftovers coverLeftovers(Workspace& ws, PathBuilder& builder, const Region& unpainted, std::size_t from, double spacing,
                         double radius, bool along_x);

/// The parameter `row_end_inset` (HeadlandOptions::end_inset) as sweep planners declare it.
ParamSpec rowEndInsetParam();
/// The parameter `fill_leftovers` (run coverLeftovers after the rows). Off by default: in the
/// default experiment 7 of 981 sweep-planner runs had a piece worth a pass, and finding the
/// pieces (a union of every painted capsule) cost 85 % of boustrophedon's planning time.
ParamSpec fillLeftoversParam();
/// The parameter `coat_ripple`: 0 (rows `overlap` apart), or the coat's allowed ripple between
/// rows, from which the row spacing follows (evenCoatOverlap).
ParamSpec coatRippleParam();
/// With coat_ripple > 0: sets `overlap` to 1 - d / s, d the widest row spacing whose summed flux
/// profile stays within coat_ripple of its mean (evenSpacing, flux_profile.hpp). Returns why it
/// cannot (empty when it can, or when coat_ripple is 0): the tool has no flux profile, `overlap`
/// was set too, or no spacing down to s/10 is that even.
std::string evenCoatOverlap(const ToolParams& tool, double coat_ripple, double& overlap);
/// The parameter `trigger_speed`: 0 (the tool sprays wherever the path has it on), or a fraction
/// f in (0, 1) of the time model's speed v (Problem::motion) under which the spray is off while
/// the tool accelerates out of or brakes into a stop (switchOffWhileSlow).
ParamSpec triggerSpeedParam();
/// Why `trigger_speed` cannot apply to the problem (empty when it can, or when it is 0): a gantry
/// stops at every change of tool state (to lower or lift its tool), a time model that stops at
/// every waypoint would stop where the spray switches, and a path smoothed for a car after
/// planning stops elsewhere than the planned one.
std::string triggerSpeedCheck(const Problem& problem, double trigger_speed);
/// With trigger_speed f > 0 and a path: switches the spray off where the time model drives the
/// path slower than f v next to a stop (switchOffWhileSlow) and records how much as the
/// statistic `trigger_off_m`.
void applyTriggerSpeed(const Problem& problem, double trigger_speed, PlanResult& result);
/// A row planner's plan (zigzag, boustrophedon, trapezoidal): `coat_ripple` (which may set
/// `overlap`) and `trigger_speed` checked, invalid_input with the reason when they cannot apply;
/// then the sweep direction searched with `plan_at` (planSweep) and the spray switched off where
/// the tool is slow (applyTriggerSpeed).
PlanResult planRows(const Problem& problem, double coat_ripple, double& overlap, double trigger_speed,
                    const SweepDirection& sweep, const Budget& budget, const std::function<PlanResult(double)>& plan_at);
/// The path with the same geometry, and the tool off along every stretch next to a stop (a
/// standstill of the time model: a run's start or end) where `segmentSpeeds` drives it slower
/// than `speed`: from a stop up to where the tool reaches `speed` accelerating, and from where it
/// falls under `speed` braking into the next stop (a run that never reaches it: all of it).
/// Segments are split at those points (an arc into two arcs of its circle); a piece shorter than
/// kMinArcChord takes its neighbour's state. A split is collinear (or continues the arc), so the
/// time model drives the path as before: duration_s is unchanged up to rounding, for any vehicle
/// that does not stop at tool-state changes (not a gantry) and a time model that does not stop at
/// every waypoint. `off_m` (if given) receives the length switched off.
Path switchOffWhileSlow(const Path& path, const MotionLimits& limits, const VehicleModel& vehicle, double speed,
                        double* off_m = nullptr);
/// The statistics leftover_passes, leftover_small_pieces and leftover_small_area_m2.
void recordLeftovers(PlanResult& result, const Leftovers& left);

}  // namespace coverbench
