// Running one planner on one problem: the budget, the wall's start and end, and the car (a planner
// plans for a tool that turns on the spot unless it plans for the car itself; the runner smooths).
#include "coverbench/run_planner.hpp"

#include "coverbench/car.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/clearance.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/transit_router.hpp"
#include "coverbench/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <optional>
#include <tuple>

namespace coverbench {

namespace {

bool inFree(const Region& free, Point p) {
  for (const PolygonWithHoles& poly : free)
    if (pointInPolygon(poly, p)) return true;
  return false;
}

/// The point of F nearest to `p` (on its edges), for messages.
Point nearestFreePoint(const Region& free, Point p) {
  Point best = p;
  double best_d = INFINITY;
  for (const PolygonWithHoles& poly : free)
    for (const Ring& ring : allRings(Region{poly}))
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point a = ring[i], b = ring[(i + 1) % ring.size()], d = b - a;
        const double len2 = dot(d, d);
        const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
        const Point q = a + d * t;
        if (distance(p, q) < best_d) best_d = distance(p, q), best = q;
      }
  return best;
}

std::string pointText(Point p) { return "(" + shortNumber(p.x) + ", " + shortNumber(p.y) + ")"; }

std::string threeDigits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// Room the depot leg's router needs between a point and the wall's edge or an obstacle (its
/// moves keep kPlanningMargin).
constexpr double kDepotRoom = 4.0 * kPlanningMargin;

/// A point within 1 mm of `depot` with kDepotRoom around it, joined to the depot by a depot
/// segment, preferring the direction of `toward`: where the router takes over from a depot on the
/// wall's edge. The depot itself when it has the room; nullopt when no such point is found.
std::optional<Point> offTheEdge(const ClearanceField& field, Point depot, Point toward) {
  auto roomy = [&](Point p) {
    const SegmentClearance c = field.measure(p, p, kDepotRoom);
    return c.inside && c.boundary_distance >= kDepotRoom && c.obstacle_distance >= kDepotRoom;
  };
  if (roomy(depot)) return depot;
  const double base = std::atan2(toward.y - depot.y, toward.x - depot.x);
  for (double step = 1e-5; step <= 1e-3; step *= 4.0)
    for (int j = 0; j < 64; ++j) {  // directions by their angle from `toward`: 0, +1, -1, +2, ... (x pi / 32)
      const double angle = base + ((j + 1) / 2) * (j % 2 == 1 ? 1.0 : -1.0) * M_PI / 32.0;
      const Point q = depot + Point{std::cos(angle), std::sin(angle)} * step;
      if (roomy(q) && depotSegment(field, depot, q)) return q;
    }
  return std::nullopt;
}

/// Why no path may begin or end at `depot` ("lies outside the wall", "lies in obstacle ..."), or
/// "" when it lies in the closed wall off every obstacle.
std::string misplacedDepot(const ClearanceField& field, Point depot) {
  const Wall& wall = field.wall();
  if (!pointInRing(depot, wall.boundary) && distanceSegmentRingEdges(depot, depot, wall.boundary) > kValidityTolerance)
    return "lies outside the wall";
  const SegmentClearance at = field.measure(depot, depot);
  if (at.obstacle_distance > 0.0) return "";
  const Obstacle& o = wall.obstacles[static_cast<std::size_t>(at.nearest_obstacle)];
  return "lies in " + (o.label.empty() ? "obstacles[" + std::to_string(at.nearest_obstacle) + "]" : "obstacle \"" + o.label + "\"") +
         " (inside it or on its edge), where the tool's centre may never be";
}

/// The depot leg (path.hpp: depot legs) from `depot`, outside F and off every obstacle, to
/// `near`, the nearest point of F: the straight move when the rule allows it, else the shortest
/// route whose centre line stays in the wall and off the obstacles (the visibility router for a
/// tool of width 0). Empty when no such route joins them.
std::vector<Point> depotLeg(const ClearanceField& field, Point depot, Point near) {
  if (depotSegment(field, depot, near)) return {depot, near};
  const std::optional<Point> off = offTheEdge(field, depot, near);
  TransitRouter router(field, ToolParams{0.0, 0.0});
  const std::optional<std::vector<Point>> route = off ? router.route(*off, near) : std::nullopt;
  std::vector<Point> leg{depot};
  if (route) leg.insert(leg.end(), route->begin() + (*off == depot ? 1 : 0), route->end());
  for (std::size_t i = 0; route && i + 1 < leg.size(); ++i)
    if (!depotSegment(field, leg[i], leg[i + 1])) leg.clear();
  if (!route) leg.clear();
  return leg;
}

/// Begins the path at the wall's start and ends it at its end, each reached with the tool off
/// (straight when free, lifted for a gantry, else along the problem's transit planner's route).
/// A start or end outside F is joined to the nearest point of F by a depot leg (path.hpp: depot
/// legs), when `depot_legs` allows it; one no such leg joins makes the result a failure that says
/// which, why and where F is nearest.
void attachEnds(const Problem& problem, PlanResult& result, bool depot_legs) {
  const Wall& wall = *problem.wall;
  if ((!wall.start && !wall.end) || !result.hasPath() || result.path.waypoints.empty()) return;
  Workspace ws(wall, problem);
  // Where the path proper begins and ends: the start and the end, or the points of F nearest them,
  // and the depot legs to those (from the start; to the end, reversed below).
  std::optional<Point> first = wall.start, last = wall.end;
  std::vector<Point> legs[2];
  for (int k = 0; k < 2; ++k) {
    const std::optional<Point> point = k == 0 ? wall.start : wall.end;
    if (!point || inFree(ws.free(), *point)) continue;
    const Point near = nearestFreePoint(ws.free(), *point);
    const double d = distance(*point, near);
    if (d <= 1e-9) continue;  // on F's edge, where paths run too
    const std::string where = std::string(k == 0 ? "start " : "end ") + pointText(*point) +
                              " is where the tool's centre may not be (" + threeDigits(d) +
                              " m outside F); the nearest point of F is " + pointText(near);
    const std::string misplaced = misplacedDepot(ws.field(), *point);
    if (!misplaced.empty()) {
      result = PlanResult::failure(PlanStatus::InvalidInput, std::string(k == 0 ? "start " : "end ") + pointText(*point) + " " + misplaced);
      return;
    }
    if (!depot_legs) {
      result = PlanResult::failure(PlanStatus::InvalidInput, where + ", and a car is not given a depot leg to it");
      return;
    }
    legs[k] = depotLeg(ws.field(), *point, near);
    if (legs[k].empty()) {
      result = PlanResult::failure(PlanStatus::InvalidInput,
                                   where + ", and no tool-off route with its centre in the wall and off the obstacles joins them");
      return;
    }
    (k == 0 ? first : last) = near;
  }
  const Path planned = std::move(result.path);
  Path out;
  auto append = [&](const Path& part) {
    for (std::size_t i = 0; i + 1 < part.waypoints.size(); ++i) {
      if (out.waypoints.empty()) out.moveTo(part.waypoints[i], false);
      out.arcTo(part.waypoints[i + 1], part.bulgeOf(i), part.tool_on[i]);
    }
    if (out.waypoints.empty() && !part.waypoints.empty()) out.moveTo(part.waypoints.front(), false);
  };
  double legs_m = 0.0;
  auto leg = [&](Point from, Point to, const char* what, Point shown) {
    PathBuilder b(ws);
    b.start(from);
    if (!b.moveTo(to, false)) {
      result = PlanResult::failure(PlanStatus::InvalidInput, std::string("no tool-off move connects ") + what + " " +
                                                                 pointText(shown) +
                                                                 " with the path (they lie in different parts of F)");
      return false;
    }
    for (std::size_t i = 0; i < b.path().segments(); ++i) legs_m += segmentLength(b.path(), i);
    append(b.path());
    return true;
  };
  double depot_m = 0.0;
  auto depot = [&](const std::vector<Point>& points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      out.moveTo(points[i], false);
      if (i > 0) depot_m += distance(points[i - 1], points[i]);
    }
  };
  depot(legs[0]);
  if (first && !leg(*first, planned.waypoints.front(), "the start", *wall.start)) return;
  append(planned);
  if (last && !leg(planned.waypoints.back(), *last, "the end", *wall.end)) return;
  std::reverse(legs[1].begin(), legs[1].end());
  depot(legs[1]);
  result.path = std::move(out);
  // The tool-off moves from the start and to the end, depot legs included.
  result.stats["start_end_legs_m"] = legs_m + depot_m;
  const std::size_t depots = !legs[0].empty() + !legs[1].empty();
  if (depots > 0) {
    result.stats["depot_legs"] = static_cast<double>(depots);
    result.stats["depot_length"] = depot_m;
  }
}

}  // namespace

namespace {

/// The problem with its rectangle tool's circumscribed disk (circumscribedDisk) in its place.
Problem withCircumscribedDisk(const Problem& problem) {
  Problem disk = problem;
  disk.tool = circumscribedDisk(problem.tool);
  return disk;
}

/// Whether a planner drives the problem's car itself: it plans for cars and its `car_plan` (if
/// it declares one) is not `smoothed`. The one place this is decided.
bool plansForTheCar(const PlannerInfo& planner, const Problem& problem) {
  if (!planner.plans_for_car) return false;
  const auto it = problem.params.all().find(carPlanParam().name);
  return it == problem.params.all().end() || it->second != ParamValue(std::string("smoothed"));
}

/// The path of a planner that planned for a tool turning on the spot, smoothed for the car
/// (vehicles/include/coverbench/car.hpp): corners rounded or turned, what it cannot reach left out
/// and said (partial).
void smoothForTheCar(const Problem& problem, PlanResult& result) {
  const Workspace ws(*problem.wall, problem);
  const CarSmoothing car = smoothForCar(ws, result.path);
  result.path = car.path;
  result.stats["car_fillets"] = static_cast<double>(car.fillets);
  result.stats["car_turns"] = static_cast<double>(car.turns);
  result.stats["car_cusps"] = static_cast<double>(car.cusps);
  result.stats["car_skipped_segments"] = static_cast<double>(car.skipped);
  result.stats["car_searched_skips"] = static_cast<double>(car.searched);
  result.stats["car_undriven_m"] = car.cut_m;
  if (car.skipped > 0 || car.stopped) result.status = PlanStatus::Partial;
  if (!car.reason.empty()) result.reason += (result.reason.empty() ? "" : "; ") + car.reason;
}

/// A car's plan: made by the planner for the car itself, or for a tool that turns on the spot and
/// then smoothed (with the wall's ends attached before, as smoothing reads only moves inside F).
PlanResult planForCar(const PlannerInfo& planner, const Problem& problem, const Budget& budget) {
  const Problem holonomic = asHolonomic(problem);
  PlanResult result = planner.make()->plan(plansForTheCar(planner, problem) ? problem : holonomic, budget);
  if (result.planned_for_car) {  // checked drivable by the planner's car sweep
    if (result.hasPath() && (problem.wall->start || problem.wall->end))
      return PlanResult::failure(PlanStatus::InvalidInput,
                                 "a plan made for the car itself (car_plan: headland) does not take a wall's start or "
                                 "end yet; use car_plan: smoothed");
    return result;
  }
  attachEnds(holonomic, result, false);
  if (result.hasPath()) smoothForTheCar(problem, result);
  return result;
}

}  // namespace

PlanResult runPlanner(const PlannerInfo& planner, const Problem& problem, const Budget& budget) {
  const auto start = std::chrono::steady_clock::now();
  PlanResult result;
  try {
    if (problem.vehicle.isCar()) {
      result = planForCar(planner, problem, budget);
    } else {
      // An in-tree planner that plans for disks plans a rectangle for its circumscribed disk (an
      // external one is sent the rectangle, or under protocol 1 the disk's width); a depot leg
      // ends in F, where the tool fits in every heading: for a rectangle, in its disk's F.
      const std::optional<Problem> disk =
          problem.tool.isRectangle() ? std::optional<Problem>(withCircumscribedDisk(problem)) : std::nullopt;
      const bool for_disk = disk && !planner.plans_line_tool && planner.external_manifest.empty() &&
                            !planner.plans_shapes;
      result = planner.make()->plan(for_disk ? *disk : problem, budget);
      attachEnds(disk ? *disk : problem, result, true);
    }
  } catch (const std::exception& e) {
    result = PlanResult::failure(PlanStatus::Error, std::string("planner threw: ") + e.what());
  } catch (...) {
    result = PlanResult::failure(PlanStatus::Error, "planner threw an unknown exception");
  }
  result.plan_time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!result.hasPath()) result.path = Path{};
  return result;
}

RunStatus runStatusOf(PlanStatus status) {
  switch (status) {
    case PlanStatus::Ok: return RunStatus::Ok;
    case PlanStatus::Partial: return RunStatus::Partial;
    case PlanStatus::NoReachableArea: return RunStatus::NoReachableArea;
    case PlanStatus::InvalidInput: return RunStatus::InvalidInput;
    case PlanStatus::Timeout: return RunStatus::Timeout;
    case PlanStatus::Error: return RunStatus::Error;
    case PlanStatus::Crash: return RunStatus::Crash;
    case PlanStatus::MemoryLimit: return RunStatus::MemoryLimit;
    case PlanStatus::InvalidOutput: return RunStatus::InvalidOutput;
  }
  return RunStatus::Error;
}

std::string toolShapeNote(const PlannerInfo& planner, const ToolParams& tool, const PlanResult& result) {
  if (!tool.turnsWithHeading() || planner.plans_line_tool || result.planned_for_shape) return "";
  // Said of a path, and of a failure to find room (the disk may not fit where the shape would).
  if (!result.hasPath() && result.status != PlanStatus::NoReachableArea) return "";
  if (!planner.external_manifest.empty())
    return planner.name + " is an external planner: it was sent the " + toString(tool.shape) +
           " under protocol 2, its circumscribed disk's width under protocol 1; the path is scored as a " +
           toString(tool.shape);
  if (tool.isLine())
    return "planned for the line tool's circumscribed disk (diameter s): " + planner.name +
           " plans for disks; the line's path is scored as a line";
  char diameter[32];
  std::snprintf(diameter, sizeof diameter, "%.4g", circumscribedDisk(tool).tool_width);
  return "planned for the rectangle tool's circumscribed disk (diameter sqrt(s^2 + d^2) = " + std::string(diameter) +
         " m): " + planner.name + " plans for disks; the rectangle's path is scored as a rectangle";
}


JudgedPlan planAndJudge(const PlannerInfo& planner, const Problem& problem, const Budget& budget) {
  JudgedPlan j;
  j.result = runPlanner(planner, problem, budget);
  j.verdict = runStatusOf(j.result.status);
  j.reason = j.result.reason;
  try {
    j.metrics = computeMetrics(*problem.wall, problem.tool, j.result.path, problem.vehicle);
  } catch (const std::exception& e) {  // beyond the scoring limits (docs/metrics.md)
    j.not_scored = "the path " + (dynamic_cast<const InputError*>(&e) ? static_cast<const InputError&>(e).problem()
                                                                      : std::string(e.what()));
    if (j.result.hasPath()) {
      j.verdict = RunStatus::MetricsError;
      j.reason = "the path could not be scored: " + j.not_scored;
    }
    return j;
  }
  if (j.result.hasPath() && !j.metrics.validity.valid) {
    j.verdict = RunStatus::InvalidOutput;
    j.reason = describeViolations(j.metrics.validity, problem.tool.clearance) +
               (j.result.reason.empty() ? "" : "; the planner said: " + j.result.reason);
  }
  j.reason = withNote(j.reason, coatNotScoredNote(j.metrics));
  j.reason = withNote(j.reason, toolShapeNote(planner, problem.tool, j.result));
  return j;
}

}  // namespace coverbench
