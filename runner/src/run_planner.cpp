// Running one planner on one problem: the budget, the wall's start and end, and the car (a planner
// plans for a tool that turns on the spot unless it plans for the car itself; the runner smooths).
#include "coverbench/run_planner.hpp"

#include "coverbench/car.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/clearance.hpp"
#include "coverbench/region_ops.hpp"
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

/// Begins the path at the wall's start and ends it at its end, each reached with the tool off
/// (straight when free, lifted for a gantry, else along the problem's transit planner's route).
/// A start or end outside F is joined to the nearest point of F by an approach leg (path.hpp:
/// kApproachLegSlack), when `approach_legs` allows it; one no such leg or move reaches makes the
/// result a failure that says which and where F is nearest.
void attachEnds(const Problem& problem, PlanResult& result, bool approach_legs) {
  const Wall& wall = *problem.wall;
  if ((!wall.start && !wall.end) || !result.hasPath() || result.path.waypoints.empty()) return;
  Workspace ws(wall, problem);
  // Where the path proper begins and ends: the start and the end, or the points of F nearest them.
  std::optional<Point> first = wall.start, last = wall.end;
  const double reach = problem.tool.radius() + problem.tool.clearance + kApproachLegSlack;
  for (const auto& [point, name, inner] : {std::tuple{wall.start, "start", &first}, std::tuple{wall.end, "end", &last}})
    if (point && !inFree(ws.free(), *point)) {
      const Point near = nearestFreePoint(ws.free(), *point);
      const double d = distance(*point, near);
      if (d <= 1e-9) continue;  // on F's edge, where paths run too
      const std::string where = std::string(name) + " " + pointText(*point) + " is where the tool's centre may not be (" +
                                threeDigits(d) + " m outside F); the nearest point of F is " + pointText(near);
      if (!approach_legs) {
        result = PlanResult::failure(PlanStatus::InvalidInput, where + ", and a car is not given an approach leg to it");
        return;
      }
      if (d > reach) {
        result = PlanResult::failure(PlanStatus::InvalidInput, where + ", farther than an approach leg reaches (r + c + " +
                                                                   threeDigits(kApproachLegSlack) + " m = " + threeDigits(reach) + " m)");
        return;
      }
      // The leg's centre line must stay in the wall and off every obstacle (the judges' rule).
      const ClearanceField field(wall);
      const Point nudged = *point + (near - *point) * (std::fmin(kValidityTolerance, d / 2.0) / d);
      if (!field.measure(nudged, near).inside || field.measure(*point, near).obstacle_distance <= 0.0) {
        result = PlanResult::failure(PlanStatus::InvalidInput, where + ", and the straight approach leg to it crosses an obstacle or the wall's edge");
        return;
      }
      *inner = near;
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
  std::size_t approaches = 0;
  if (wall.start && !(*first == *wall.start)) {  // the approach leg into F
    out.moveTo(*wall.start, false);
    out.moveTo(*first, false);
    legs_m += distance(*wall.start, *first);
    ++approaches;
  }
  if (first && !leg(*first, planned.waypoints.front(), "the start", *wall.start)) return;
  append(planned);
  if (last && !leg(planned.waypoints.back(), *last, "the end", *wall.end)) return;
  if (wall.end && !(*last == *wall.end)) {  // the approach leg out of F
    out.moveTo(*wall.end, false);
    legs_m += distance(*last, *wall.end);
    ++approaches;
  }
  result.path = std::move(out);
  result.stats["start_end_legs_m"] = legs_m;  // the tool-off moves from the start and to the end
  if (approaches > 0) result.stats["approach_legs"] = static_cast<double>(approaches);
}

}  // namespace

namespace {

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
      result = planner.make()->plan(problem, budget);
      attachEnds(problem, result, true);
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
  return j;
}

}  // namespace coverbench
