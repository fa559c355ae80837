#pragma once
/// Planning for a car (docs/vehicles.md): the shortest curve between two poses from OMPL's
/// Dubins and Reeds-Shepp state spaces as a path of arcs and lines, checks of arcs against the
/// free region, and the smoothing that makes any planner's path drivable by a car.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/boundary_arcs.hpp"  // arcFree, pathFree
#include "coverbench/path.hpp"

namespace coverbench {

class Workspace;

/// Turns are planned on a radius this much above the car's (relative), so that ending a curve
/// exactly on its target (moving the last arc's end by rounding) never makes an arc tighter.
inline constexpr double kCarRadiusSlack = 1e-4;

/// A position and a heading (radians).
struct Pose {
  Point at;
  double heading = 0.0;
};

/// One piece of a car's curve: a turn left ('L') or right ('R') by `amount` radians, or a straight
/// ('S') of `amount` turn radii; negative: driven backwards.
struct CurvePrimitive {
  char kind = 'S';
  double amount = 0.0;
};
/// OMPL's shortest Reeds-Shepp curve (vehicles/src/ompl_curves.cpp).
std::vector<CurvePrimitive> reedsSheppPrimitives(Pose from, Pose to, double radius);
/// The length of OMPL's shortest Dubins curve, for cross-checking ours (tests only: OMPL's Dubins
/// aborts the process on an internal assertion for some pairs of poses tens of radii apart, in
/// Debian's build, so curves are not made with it).
double omplDubinsLength(Pose from, Pose to, double radius);

/// The shortest curve a car of turn radius `radius` drives from `from` to `to`: Dubins when it
/// goes forward only (the six words of Dubins 1957 in closed form, Shkel & Lumelsky 2001; each
/// candidate driven out and kept only if it arrives), Reeds-Shepp when it may reverse (cusps where
/// it does; OMPL's ReedsSheppStateSpace). Returned as a path of lines and arcs (each arc at most a
/// quarter circle) from from.at to exactly to.at, every segment with tool state `tool`; empty
/// when no curve arrives within 1e-9 m and rad.
Path carCurve(Pose from, Pose to, double radius, bool reverse, bool tool);
/// carCurve's curve into `out` (emptied first, its room kept: searches build one at every pose
/// they take); false, with `out` empty, when there is none.
bool carCurveInto(Pose from, Pose to, double radius, bool reverse, bool tool, Path& out);
/// The length of that curve (m), without building it: what turn-aware orders compare. Infinite
/// when there is none.
double carCurveLength(Pose from, Pose to, double radius, bool reverse);
/// A route a car of turn radius `radius` drives from `from` to `to` staying in F (tool off), when
/// no single curve is free: a search over its own motions (hybrid A*: arcs of curvature 0, ±1/2R
/// and ±1/R, pi R / 8 long, from continuous poses; the best cost kept per R/2 cell and 15-degree
/// heading; guided by twice the obstacle-free curve's length; the shortest curve to `to` tried
/// from each pose taken, and taken when free).
/// Backing up (a reversing car) costs half as much again as driving on. Empty when no route was
/// found within `max_expansions` poses. Adds the poses it took to `*used` when given.
Path searchCarRoute(const Workspace& ws, Pose from, Pose to, double radius, bool reverse, std::size_t max_expansions,
                    std::size_t* used = nullptr);
/// A pose's cell (`cell` wide) and heading bin (of `headings`) as one key: what the search tells
/// poses apart by.
std::int64_t poseKey(Pose p, double cell, int headings);
/// The same search (forward-only, by cost alone) from `from` to the first pose `finish` takes:
/// `finish(pose, last)` returns true with the last piece to append (starting at that pose) in
/// `last`. The route (tool off) and that piece as they come, or an empty path. `fineness` k makes
/// the cells R/(2k), the headings told apart 24k and the motions pi R / (8k) long.
Path searchCarUntil(const Workspace& ws, Pose from, double radius, std::size_t max_expansions,
                    const std::function<bool(Pose, Path&)>& finish, std::size_t* used = nullptr, int fineness = 1);
/// Whether a forward-only car at `from` can reach, within `max_expansions` poses of the same
/// search, a pose from which it could circle at radius `radius` (left or right) staying in F: a
/// pose it can drive on from forever. A pose that cannot is in a dead end: the car only leaves
/// it by ending its path there.
bool carCanLoop(const Workspace& ws, Pose from, double radius, std::size_t max_expansions);
/// OMPL's shortest Reeds-Shepp curve's length (m).
double reedsSheppLength(Pose from, Pose to, double radius);

/// A car may go on from heading `end` at `start`: the same heading (within kCarHeadingTolerance
/// / 2), or, when it reverses, the opposite (a cusp). The rule checkDrivable applies at waypoints.
bool headingsJoin(double end, double start, bool reverse);
/// The reversals (cusps) at a path's waypoints: heading changes of more than a quarter turn.
std::size_t cusps(const Path& path);
/// The heading a path starts with (an arc's: its chord's turned back by half its angle). The path
/// must have a segment.
double startHeading(const Path& path);

/// Where a path ends and the heading it ends with (an arc's: its chord's turned on by half its
/// angle). The path must have a segment.
Pose endPose(const Path& path);

/// Checks the car's rules on `path` (every arc at least the turn radius, the heading continuous
/// or, for a car that reverses, reversed at a cusp): std::logic_error on the first break. What a
/// planner for a car calls on its finished path, so that a slip fails the plan rather than hand
/// over a path the car cannot drive (the judges check again).
void checkDrivable(const Path& path, const VehicleModel& car, const char* who);


/// A planner's path made drivable by the workspace's car.
struct CarSmoothing {
  Path path;
  std::size_t fillets = 0;    ///< corners rounded by an arc of the turn radius
  std::size_t turns = 0;      ///< corners (and runs of short segments) replaced by a Dubins / Reeds-Shepp curve
  std::size_t cusps = 0;      ///< reversals in those curves (a Reeds-Shepp car's three-point turns)
  std::size_t skipped = 0;    ///< segments left out because no curve reached past them
  std::size_t searched = 0;   ///< skips made along a route searched over the car's own motions
  double cut_m = 0.0;         ///< length of the planner's tool-on segments not driven (cut back or skipped)
  bool stopped = false;       ///< no curve reached any later segment: the path ends early
  /// The path's painted pieces that skips and a stop left undriven (straight pieces, in order).
  std::vector<std::pair<Point, Point>> undriven;
  std::string reason;         ///< what was left out, for the plan's reason
};

/// Makes `path` drivable by the car of `ws` (its vehicle; docs/vehicles.md): a forward-only car
/// first drops spurs (out and straight back). Then each corner is rounded by an arc of the turn
/// radius where that arc is free and fits its two segments (a car that reverses instead drives
/// into a corner of 60 degrees or more, backs out and backs into it along the next segment, so
/// that the corner is painted); else replaced by the shortest Dubins / Reeds-Shepp curve from a
/// point moved back before the corner to a point moved on after it (0 to 3 turn radii each, past
/// any corners between), the first that is free and does not loop (a car that reverses also
/// backs out first); else skipped, tool off, to the nearest point a free curve reaches on a later
/// segment, its start or up to 4 radii into it (from the corner or up to 8 radii before it), or,
/// where that would leave more than 1 m of painting, along a route searched over the car's own
/// motions (searchCarRoute) to the next long segments; else the car backs off to where it was 1,
/// 2, 4, ... steps before and skips from there; else the path ends (`stopped`). Every piece is checked (arcFree), and the result is
/// checked for the car's rules (std::logic_error on a slip). Painting continues through a turn
/// only where the path it replaces was painted all along.
CarSmoothing smoothForCar(const Workspace& ws, const Path& path);

}  // namespace coverbench
