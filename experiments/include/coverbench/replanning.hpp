#pragma once
/// Replanning around surprises (docs/replanning.md): a plan is executed along its arc length; at
/// a fraction of it, obstacles nobody planned for appear (scaffolding, a ladder, a cable duct,
/// drawn from the run's seed); the rest of the plan is repaired, either by planning the uncovered
/// remainder again with the same coverage planner or by detouring the affected passes with the
/// problem's transit planner. The repaired path is an ordinary path on the new wall: the metrics
/// engine judges it like any other (nothing here scores it).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "coverbench/path.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// What appears: each kind is an axis-aligned rectangle whose size is drawn from the kind's range
/// (metres), capped to a share of the wall's bounding box so that small walls keep something free.
enum class SurpriseKind {
  Scaffolding,  ///< 1-2.5 m wide, 1-2 m tall (at most 30 % of the wall's width and height)
  Ladder,       ///< 0.4-0.6 m wide, 2-4 m tall (at most 15 % of the width and 60 % of the height)
  Duct,         ///< a cable duct 1.5-4 m long (at most 60 % of the wall) and 0.06-0.12 m thick, either way
};
std::string toString(SurpriseKind kind);
bool parseSurpriseKind(const std::string& name, SurpriseKind& kind);
const std::vector<SurpriseKind>& allSurpriseKinds();

enum class RepairMethod {
  /// Plan the wall again with the obstacles known (the same planner and parameters), keep the
  /// tool-on moves that paint something the executed part did not, and link them from the
  /// robot's position with the transit planner.
  Replan,
  /// Keep the rest of the plan; every move the obstacles block is replaced: a tool-on move by its
  /// free stretches, linked by transits, a tool-off move by a transit.
  Detour,
};
std::string toString(RepairMethod method);
bool parseRepairMethod(const std::string& name, RepairMethod& method);

/// The config section `replanning:`; off when `at` is empty.
struct ReplanningSpec {
  std::vector<double> at;  ///< fractions of the path's length at which obstacles appear, each in (0, 1)
  int obstacles = 1;       ///< how many appear at each fraction
  std::vector<SurpriseKind> kinds = allSurpriseKinds();  ///< drawn from these, uniformly
  std::vector<RepairMethod> repairs{RepairMethod::Replan, RepairMethod::Detour};
  bool enabled() const { return !at.empty(); }
  /// A canonical one-line description (run keys, the database): "at=0.3,0.7 obstacles=2 kinds=... repairs=...".
  std::string describe() const;
};

/// The most obstacles one surprise may hold (a config asking for more is refused).
inline constexpr int kMaxSurpriseObstacles = 20;

/// A path cut at a point of its arc length.
struct PathCut {
  Path executed;   ///< from the start to the cut point (empty when the cut is at the start)
  Path remainder;  ///< from the cut point to the end
  Point position;  ///< the cut point
  double length = 0.0;  ///< the executed length, m
};
/// Replanning cuts, paints and re-routes straight segments: a path's arcs (F's round boundary, a
/// car's turns) are taken as chords within this of them (m), which keeps a planner's margin.
inline constexpr double kReplanChordSagitta = 1e-6;
/// The path as replanning takes it: its arcs as chords (kReplanChordSagitta).
Path straightenedForReplanning(const Path& path);

/// Cuts `path` at `fraction` (0..1) of its length; a segment cut in two keeps its tool state. Here
/// and below a path is taken straightenedForReplanning: both parts are straight.
PathCut cutPath(const Path& path, double fraction);

/// Obstacles that appeared at one fraction of a path.
struct Surprise {
  double fraction = 0.0;
  PathCut cut;
  std::vector<Obstacle> obstacles;  ///< what appeared (labelled by kind), in the order drawn
  std::size_t requested = 0;        ///< how many were asked for; fewer when no place was found
  Wall wall;                        ///< the wall with them
};
/// Draws `spec.obstacles` obstacles for the cut at `fraction` of `path` from `seed` (the run's
/// seed, mixed with the fraction). Each is centred near a point of the path's painted remainder
/// (so it is in the robot's way), within the wall's bounding box, and keeps more than r + c from
/// the robot (it cannot appear where the robot stands); it may stand on what was painted already.
/// Coordinates are rounded to millimetres. A draw that finds no place in 200 tries is given up
/// (`requested` says how many were asked for). Same inputs, same obstacles.
Surprise makeSurprise(const Wall& wall, const ToolParams& tool, const Path& path, double fraction,
                      const ReplanningSpec& spec, std::uint64_t seed);

/// A repaired path: the executed part followed by the repaired remainder. The executed part was
/// driven before the obstacles appeared, so it is judged on the old wall and the repaired part,
/// from waypoint `cut_waypoint` on, on the new one (repairedPart).
struct Repair {
  bool ok = false;      ///< a path was produced (it may still leave parts out: see the counts)
  std::string reason;   ///< why not, or what was left out
  Path path;            ///< executed + repaired remainder
  std::size_t cut_waypoint = 0;  ///< the index in `path` of the cut point (the robot's position then)
  std::size_t kept_moves = 0;         ///< tool-on moves of the plan used (replan: of the new plan)
  std::size_t dropped_moves = 0;      ///< tool-on moves left out (replan: painted already; detour: blocked)
  std::size_t unreachable_moves = 0;  ///< moves whose start no transit reached (left out)
  std::size_t transits = 0;           ///< routed detours with the tool off
  double blocked_m = 0.0;  ///< detour: tool-on length of the remainder the obstacles block (left unpainted)
  /// It knowingly leaves painting out (blocked stretches, unreachable moves).
  bool leftOut() const { return unreachable_moves > 0 || blocked_m > 0.0; }
  /// The path from the cut point on (what was planned after the obstacles appeared).
  Path repairedPart() const;
};

/// Repairs the surprise's remainder by detours, on `problem` (whose wall must be surprise.wall):
/// each tool-on move keeps its free stretches (exact checks, ends found to a micrometre), linked
/// by transits; a tool-off move is routed around what blocks it, and skipped when it ends where
/// an obstacle now stands (a gantry lifts over). What the obstacles block is `blocked_m`.
Repair repairByDetour(const Surprise& surprise, const Problem& problem);

/// Repairs it from `plan`, a plan of `problem` (the surprise's wall) made by the coverage planner:
/// its tool-on moves that paint something the executed part did not are kept in the plan's order
/// and linked from the robot's position with the problem's transit planner. "Something": a cell
/// of a raster of side s / 4 whose centre lies within r of the move and of no executed tool-on
/// move (so a move is dropped only when its whole band, to the raster's resolution, is painted).
Repair repairFromPlan(const Surprise& surprise, const Problem& problem, const Path& plan);

}  // namespace coverbench
