// Finding a registered planner by name, resolving its parameters, and running it under a budget.
// (Params and the toString functions of planner.hpp are the planning library's: planning/src/planner.cpp.)
#include "coverbench/registry.hpp"

#include "coverbench/car.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/clearance.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <exception>
#include <optional>
#include <tuple>

namespace coverbench {

namespace {

/// Planners added by name beside the registered ones: planners outside the tree and test planners.
std::deque<PlannerInfo>& addedPlanners() {  // a deque: references stay valid as it grows
  static std::deque<PlannerInfo> planners;
  return planners;
}

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

const PlannerInfo* lookupPlanner(const std::string& name) {
  for (const PlannerInfo& p : registeredPlanners())
    if (p.name == name) return &p;
  for (const PlannerInfo& p : addedPlanners())
    if (p.name == name) return &p;
  return nullptr;
}

void addPlannerForTesting(PlannerInfo info) {
  for (const PlannerInfo& p : registeredPlanners())
    if (p.name == info.name) return;  // never shadows a registered planner
  for (PlannerInfo& p : addedPlanners())
    if (p.name == info.name) {
      p = std::move(info);
      return;
    }
  addedPlanners().push_back(std::move(info));
}

const PlannerInfo& addPlanner(PlannerInfo info, const std::string& source) {
  for (const PlannerInfo& p : registeredPlanners())
    if (p.name == info.name) throw InputError(source, "name", "'" + info.name + "' is a registered planner's name");
  for (PlannerInfo& p : addedPlanners())
    if (p.name == info.name) return p = std::move(info);
  addedPlanners().push_back(std::move(info));
  return addedPlanners().back();
}

const PlannerInfo& findPlanner(const std::string& name, const std::string& source) {
  if (const PlannerInfo* p = lookupPlanner(name)) return *p;
  std::string known;
  for (const PlannerInfo& p : registeredPlanners()) known += (known.empty() ? "" : ", ") + p.name;
  throw InputError(source, name, "unknown planner (registered: " + known + ")");
}

namespace {

ParamValue parseValue(const ParamSpec& spec, const std::string& text, const std::string& source) {
  const std::string field = spec.name;
  auto fail = [&](const std::string& problem) -> ParamValue { throw InputError(source, field, problem); };
  switch (spec.type) {
    case ParamType::Number: {
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(v)) return fail("'" + text + "' is not a finite number");
      if (v < spec.min || v > spec.max)
        return fail(text + " is out of range [" + toString(spec.min) + ", " + toString(spec.max) + "]" +
                    (spec.unit.empty() ? "" : " " + spec.unit));
      return v;
    }
    case ParamType::Integer: {
      char* end = nullptr;
      const long long v = std::strtoll(text.c_str(), &end, 10);
      if (text.empty() || *end != '\0') return fail("'" + text + "' is not an integer");
      if (static_cast<double>(v) < spec.min || static_cast<double>(v) > spec.max)
        return fail(text + " is out of range [" + toString(spec.min) + ", " + toString(spec.max) + "]");
      return v;
    }
    case ParamType::Bool:
      if (text == "true" || text == "1" || text == "on") return true;
      if (text == "false" || text == "0" || text == "off") return false;
      return fail("'" + text + "' is not a boolean (true or false)");
    case ParamType::Choice:
      for (const std::string& c : spec.choices)
        if (c == text) return text;
      {
        std::string list;
        for (const std::string& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
        return fail("'" + text + "' is not one of: " + list);
      }
  }
  return fail("unsupported parameter type");
}

}  // namespace

Params resolveParams(const PlannerInfo& planner, const std::vector<std::pair<std::string, std::string>>& settings,
                     const std::string& source) {
  Params params;
  for (const ParamSpec& spec : planner.params) params.set(spec.name, spec.default_value);
  for (const auto& [key, value] : settings) {
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& s : planner.params)
      if (s.name == key) spec = &s;
    if (!spec) {
      std::string known;
      for (const ParamSpec& s : planner.params) known += (known.empty() ? "" : ", ") + s.name;
      throw InputError(source, key,
                       "planner '" + planner.name + "' has no such parameter (it has: " +
                           (known.empty() ? "none" : known) + ")");
    }
    params.set(key, parseValue(*spec, value, source));
  }
  return params;
}

PlanResult runPlanner(const PlannerInfo& planner, const Problem& problem, const Budget& budget) {
  const auto start = std::chrono::steady_clock::now();
  PlanResult result;
  try {
    if (problem.vehicle.isCar()) {
      // Planners plan for a tool that turns on the spot and the car drives their path smoothed
      // (vehicles/include/coverbench/car.hpp): corners rounded or turned, what it cannot reach left
      // out and said. A planner that plans for the car itself (PlannerInfo::plans_for_car) is given
      // the car and says whether it did (PlanResult::planned_for_car).
      const Problem holonomic = asHolonomic(problem);
      result = planner.make()->plan(planner.plans_for_car ? problem : holonomic, budget);
      if (result.planned_for_car && result.hasPath() && (problem.wall->start || problem.wall->end))
        result = PlanResult::failure(PlanStatus::InvalidInput,
                                     "a plan made for the car itself (car_plan: headland) does not take a wall's start or "
                                     "end yet; use car_plan: smoothed");
      if (!result.planned_for_car) attachEnds(holonomic, result, false);  // smoothing reads only moves inside F
      if (!result.planned_for_car && result.hasPath()) {
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

}  // namespace coverbench
