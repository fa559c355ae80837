#pragma once
/// What every planner needs about one problem: the free centre region F, exact segment checks,
/// shortest collision-free transits, and a path builder that never writes an unchecked move.
///
/// F = erode(boundary, r) minus dilate(obstacles, r + c), r = s / 2. `free()` is a polygonal
/// inner approximation of F: its boundary lies between kFreeSpaceMargin - kArcTolerance - 1e-6 m
/// and kFreeSpaceMargin + 1e-6 m inside the exact F, so any path drawn inside it is valid and
/// it misses at most a band of kFreeSpaceMargin along F's boundary.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/clearance.hpp"
#include "coverbench/free_region.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/transit_router.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// What a problem's transit planner did, for the plan's statistics (recordOutcome). Only sampling
/// planners keep them; `visibility` is the reference they are measured against.
struct TransitStats {
  std::size_t queries = 0;
  std::size_t failures = 0;     ///< queries with no route within the iterations
  std::size_t time_capped = 0;  ///< queries stopped by the wall-clock cap (not repeatable)
  double length = 0.0;          ///< total length of the routes found, m
  double shortest = 0.0;        ///< the visibility routes' total length for the same queries, m
  double ms = 0.0;              ///< time spent in the sampling planner (measured)
};

/// The geometry of one problem, built once and shared by a planner's stages.
class Workspace {
 public:
  Workspace(const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle = {},
            const TransitSpec& transit = {}, std::uint64_t seed = 0);
  /// The problem's tool, vehicle, transit planner and seed, on `wall` (the problem's, or turned).
  Workspace(const Wall& wall, const Problem& problem)
      : Workspace(wall, problem.tool, problem.vehicle, problem.transit, problem.seed) {}
  ~Workspace();
  const Wall& wall() const { return wall_; }
  const ToolParams& tool() const { return tool_; }
  const VehicleModel& vehicle() const { return vehicle_; }
  const TransitSpec& transitSpec() const { return transit_; }
  const TransitStats& transitStats() const { return transit_stats_; }
  /// A collision-free route a, ..., b with the problem's transit planner (nullopt: none found).
  std::optional<std::vector<Point>> route(Point a, Point b);
  const Region& free() const { return free_; }
  const ClearanceField& field() const { return field_; }
  TransitRouter& router() { return router_; }

 private:
  Wall wall_;
  ToolParams tool_;
  VehicleModel vehicle_;
  TransitSpec transit_;
  std::uint64_t seed_;
  ClearanceField field_;
  Region free_;
  TransitRouter router_;
  std::unique_ptr<SamplingTransit> sampling_;  // made at the first query
  TransitStats transit_stats_;
};

/// Appends moves to a path, checking every straight move and routing around obstacles when a
/// straight move is not free.
class PathBuilder {
 public:
  explicit PathBuilder(Workspace& workspace) : ws_(&workspace) {}

  bool empty() const { return path_.waypoints.empty(); }
  Point current() const { return path_.waypoints.back(); }
  /// Starts the path (or teleports nowhere: only valid on an empty path).
  void start(Point p) { path_.moveTo(p, false); }
  /// Moves along points known to lie in the free region (e.g. a ring of `free()`), tool state
  /// as given. The first point must be the current position or reachable straight from it.
  void follow(const std::vector<Point>& points, bool tool_on);
  /// Moves to `to`: straight if free (tool as `tool_on_if_straight`); else, when the vehicle lifts
  /// its tool (gantry), straight with the tool lifted (off); else along the shortest route with
  /// the tool off. Returns false (and leaves the path unchanged) if `to` is unreachable. A lifted
  /// move between two points of F stays in the wall's bounding box, which is convex.
  bool moveTo(Point to, bool tool_on_if_straight);
  /// How many moves so far went along a routed detour with the tool off.
  std::size_t transits() const { return transits_; }
  /// How many moves so far crossed what is not free with the tool lifted (gantry only).
  std::size_t liftedCrossings() const { return lifted_; }
  const Workspace& workspace() const { return *ws_; }
  Path take() { return std::move(path_); }
  const Path& path() const { return path_; }

 private:
  Workspace* ws_;
  Path path_;
  std::size_t transits_ = 0;
  std::size_t lifted_ = 0;
};

/// Covers each ring with one closed loop (tool on), visiting rings in greedy nearest order and
/// starting each loop at its vertex nearest to the current position. The move onto a loop keeps
/// the tool on when it is straight and no longer than `max_painted_link`. Returns the number of
/// rings that could not be reached.
std::size_t coverRings(PathBuilder& builder, std::vector<Ring> rings, double max_painted_link);

/// Of the `passes` not yet `done`, the one with an end nearest `at` (the first such on ties,
/// its first end before its second), marked done; and whether it is taken from its second end.
std::pair<std::size_t, bool> takeNearestPass(const std::vector<std::pair<Point, Point>>& passes, std::vector<bool>& done,
                                             Point at);

/// Corners of a painted polyline at least this wide (radians) count as straight: no spur.
inline constexpr double kStraightCorner = M_PI - 0.09;

/// The tip of an out-and-back spur at the corner `v` of a painted polyline prev -> v -> next whose
/// angle between the two segments is `angle` (< pi). Turning there, the disk leaves a curved
/// triangle unpainted beyond the corner, on the outside of the turn; a spur of
/// r / sin(angle / 2) - r along the outward bisector reaches its far point. The spur is kept only
/// when free (exact check), shortened by halves otherwise (three tries); a corner sharper than
/// 30 degrees gets a spur of at most 2 r. nullopt: no free spur (or a degenerate corner).
std::optional<Point> cornerSpurTip(Point prev, Point v, Point next, double angle, double r, const TransitRouter& router);

/// The path with an out-and-back spur (tool on) at every corner between two tool-on segments that
/// is sharper than kStraightCorner (cornerSpurTip), and one of r straight on at both ends of every
/// run of tool-on segments (it reaches the far corners of a cell of side 2 r whose centre the run
/// ends at), where free (shortened by halves otherwise); `spurs` counts them.
Path withCornerSpurs(const Path& path, double r, const TransitRouter& router, std::size_t& spurs);
/// The parameter `corner_spurs` (withCornerSpurs on the finished path) as grid planners declare it.
/// Off by default, so their default results stay as they were.
ParamSpec cornerSpursParam();

/// The reason an ok plan gives for what it left out: the free components it did not cover (all
/// but the largest, when `covered_components` is 1), and parts (rings, rows) no collision-free
/// transit reached. Empty when nothing was left out.
std::string partialCoverageNote(std::size_t free_components, std::size_t covered_components,
                                std::size_t unreachable_parts);

/// Records what every planner built on PathBuilder reports the same way: the statistics
/// `routed_transits` (and, for a vehicle that lifts its tool, `lifted_crossings`; for a sampling
/// transit planner, `transit_*` and the measured `transit` time), the typed fields
/// free_components, covered_components (coveredPart's) and unreachable_parts, the reason above,
/// and status Partial for an Ok plan that left parts out.
void recordOutcome(PlanResult& result, const PathBuilder& builder, std::size_t free_components,
                   std::size_t unreachable_parts);

/// Up to `count` transit queries that need a detour, for measuring transit planners (tests and
/// bench/transit_bench.cpp): points of a grid of about 12 x 12 over the wall's bounding box that lie
/// in F's largest component, paired (in a fixed order) where the straight move between them is not
/// free, each with its visibility route (TransitRouter). Deterministic.
struct DetourQuery {
  Point a, b;
  double shortest = 0.0;  ///< length of the visibility route, m
};
std::vector<DetourQuery> detourQueries(Workspace& ws, std::size_t count);

/// The connected components of a region, largest area first (ties broken by position, so the
/// order is deterministic).
std::vector<PolygonWithHoles> componentsByArea(const Region& region);

/// The part of F a planner covers, given its components by area: all of them when the vehicle
/// lifts its tool across what separates them (gantry), else the largest (the others cannot be
/// reached without leaving F).
Region coveredPart(const std::vector<PolygonWithHoles>& components, const VehicleModel& vehicle);

}  // namespace coverbench
