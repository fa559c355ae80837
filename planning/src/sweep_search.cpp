#include "coverbench/sweep_search.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace coverbench {
namespace {

double normalise(double deg) {
  double a = std::fmod(deg, 180.0);
  if (a < 0.0) a += 180.0;
  a = std::round(a * 100.0) / 100.0;  // hundredths of a degree: equal directions compare equal
  return a >= 180.0 ? 0.0 : a;
}

/// Free intervals of one scanline: inside the boundary and outside every obstacle.
void scanline(double y, const std::vector<Ring>& boundary, const std::vector<Ring>& obstacles, std::vector<double>& xs,
              std::vector<std::pair<double, double>>& blocked, double& length, std::size_t& intervals) {
  auto crossings = [&](const Ring& ring) {
    xs.clear();
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point a = ring[i], b = ring[(i + 1) % ring.size()];
      if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(xs.begin(), xs.end());
  };
  blocked.clear();
  for (const Ring& o : obstacles) {
    crossings(o);
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) blocked.push_back({xs[k], xs[k + 1]});
  }
  std::sort(blocked.begin(), blocked.end());
  for (const Ring& b : boundary) {
    crossings(b);
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      double from = xs[k];
      const double to = xs[k + 1];
      for (const auto& [lo, hi] : blocked) {  // in order: what lies between blocked spans is free
        if (hi <= from || lo >= to) continue;
        if (lo > from) {
          length += lo - from;
          ++intervals;
        }
        from = std::max(from, hi);
      }
      if (to > from) {
        length += to - from;
        ++intervals;
      }
    }
  }
}

/// What the rows of a sweep at `angle_deg` cost, estimated without planning: rows `spacing` apart
/// over the wall minus its obstacles (circles as 16-gons), each row its length plus a connection
/// of `spacing` and two turns, in the search's objective. Ranks directions for the search; only
/// the best are planned.
double estimatedSweepCost(const Problem& problem, const SweepDirection& sweep, double angle_deg) {
  const Wall& wall = *problem.wall;
  const double spacing = problem.tool.tool_width;
  const double t = -angle_deg * M_PI / 180.0;
  std::vector<Ring> boundary{wall.boundary}, obstacles;
  for (const Obstacle& o : wall.obstacles) {
    if (o.type != ObstacleType::Circle) {
      obstacles.push_back(o.polygon);
      continue;
    }
    Ring circle;
    for (int k = 0; k < 16; ++k)
      circle.push_back({o.center.x + o.radius * std::cos(k * M_PI / 8), o.center.y + o.radius * std::sin(k * M_PI / 8)});
    obstacles.push_back(std::move(circle));
  }
  for (Ring& r : boundary) rotatePoints(r, t);
  for (Ring& r : obstacles) rotatePoints(r, t);
  const Box box = boundingBox(boundary.front());
  double length = 0.0, time = 0.0;
  std::size_t intervals = 0;
  std::vector<double> xs;
  std::vector<std::pair<double, double>> blocked;
  for (double y = box.min_y + spacing / 2; y < box.max_y; y += spacing) {
    const double before = length;
    const std::size_t rows_before = intervals;
    scanline(y, boundary, obstacles, xs, blocked, length, intervals);
    // Rows of one scanline, timed as one run each (their split is not known here: share alike).
    if (intervals > rows_before) {
      const double rows = static_cast<double>(intervals - rows_before);
      time += rows * straightRunTime((length - before) / rows, problem.motion);
    }
  }
  const double rows = static_cast<double>(intervals);
  switch (sweep.objective) {
    case SweepDirection::Objective::Time:
      // A row's end: a move of one spacing between two quarter turns.
      return time + rows * (straightRunTime(spacing, problem.motion) +
                            2.0 * (problem.motion.turn_cost_s + rotationTime(M_PI / 2.0, problem.motion)));
    case SweepDirection::Objective::Turns:
      return 2.0 * rows + 1e-9 * length;
    case SweepDirection::Objective::Length:
      break;
  }
  return length + rows * (spacing + 2.0 * sweep.turn_penalty_m);
}

}  // namespace

std::optional<SweepSearch> searchSweepDirection(const Wall& wall, const std::function<std::optional<double>(double)>& cost,
                                                const std::function<bool()>& keep_going, double coarse_step_deg,
                                                double fine_step_deg, std::size_t longest_edges) {
  std::set<double> tried;
  std::optional<SweepSearch> best;
  std::size_t evaluations = 0;
  auto evaluate = [&](double deg) {
    const double a = normalise(deg);
    if (!tried.insert(a).second || !keep_going()) return;
    ++evaluations;
    const std::optional<double> c = cost(a);
    if (!c) return;
    if (!best || *c < best->cost || (*c == best->cost && a < best->angle_deg)) best = SweepSearch{a, *c, 0};
  };
  // Directions of the longest edges of the wall and its obstacles: sweeping along them leaves no
  // sliver rows beside them.
  std::vector<std::pair<double, double>> edges;  // (length, direction)
  auto collect = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point d = ring[(i + 1) % ring.size()] - ring[i];
      edges.push_back({norm(d), std::atan2(d.y, d.x) * 180.0 / M_PI});
    }
  };
  collect(wall.boundary);
  for (const Obstacle& o : wall.obstacles)
    if (o.type != ObstacleType::Circle) collect(o.polygon);
  std::stable_sort(edges.begin(), edges.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; i < std::min(longest_edges, edges.size()); ++i) evaluate(edges[i].second);
  for (double deg = 0.0; deg < 180.0; deg += coarse_step_deg) evaluate(deg);
  if (best) {
    const double centre = best->angle_deg;
    for (double d = -coarse_step_deg + fine_step_deg; d < coarse_step_deg; d += fine_step_deg) evaluate(centre + d);
  }
  if (best) best->evaluations = evaluations;
  return best;
}

double objectiveCost(const Path& path, const Problem& problem, const SweepDirection& sweep) {
  switch (sweep.objective) {
    case SweepDirection::Objective::Time: {
      const Motion m = motion(path, problem.motion, problem.vehicle);
      return m.duration_s + m.turn_cost_s.value_or(0.0);
    }
    case SweepDirection::Objective::Turns:
      return static_cast<double>(motion(path).turns_30) + 1e-9 * sweepCost(path, 0.0);
    case SweepDirection::Objective::Length:
      break;
  }
  return sweepCost(path, sweep.turn_penalty_m);
}

double sweepCost(const Path& path, double turn_penalty_m) {
  double length = 0.0;
  std::size_t turns = 0;
  Point heading{0.0, 0.0};
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    const Point d = path.waypoints[i + 1] - path.waypoints[i];
    const double l = norm(d);
    if (l == 0.0) continue;
    length += l;
    if (norm(heading) > 0.0 && dot(heading, d) < std::cos(M_PI / 6.0) * norm(heading) * l) ++turns;
    heading = d;
  }
  return length + turn_penalty_m * static_cast<double>(turns);
}

const ParamTable<SweepDirection>& sweepDirectionParams() {
  static const ParamTable<SweepDirection> table =
      ParamTable<SweepDirection>()
          .add({"sweep_angle", ParamType::Number, 0.0, 0.0, 180.0, {}, "deg",
                "direction of the passes (rows), counter-clockwise from +x"},
               &SweepDirection::angle_deg)
          .add({"direction_search", ParamType::Bool, false, 0, 0, {}, "",
                "search the sweep direction (5-degree steps and the longest edges, then 1-degree steps, each estimated; "
                "the two best planned); overrides "
                "sweep_angle"},
               &SweepDirection::search)
          .add({"turn_penalty", ParamType::Number, 1.0, 0.0, 1000.0, {}, "m",
                "cost of a turn over 30 degrees in the direction search"},
               &SweepDirection::turn_penalty_m)
          .add({"objective", ParamType::Choice, std::string("length"), 0, 0, {}, "",
                "what the direction search (and a decomposition planner's cell order) minimises: length plus "
                "turn_penalty per turn, the time under the "
                "experiment's time model (motion:), or the turns"},
               &SweepDirection::objective,
               {{"length", SweepDirection::Objective::Length}, {"time", SweepDirection::Objective::Time},
                {"turns", SweepDirection::Objective::Turns}});
  return table;
}

PlanResult planSweep(const Problem& problem, const SweepDirection& sweep, const Budget& budget,
                     const std::function<PlanResult(double)>& plan_at_angle) {
  // Every plan with a path says which direction it swept: the search's choice or sweep_angle.
  const auto plan_at = [&](double angle_deg) {
    PlanResult r = plan_at_angle(angle_deg);
    if (r.hasPath()) r.stats["sweep_angle_deg"] = angle_deg;
    return r;
  };
  if (!sweep.search) return plan_at(sweep.angle_deg);
  // Two stages: every direction of the search is ranked by its estimated cost (rows over the wall,
  // no planning), and only the best few are planned; the cheapest plan by sweepCost wins. Planning
  // every direction cost ~50 plans (570 ms on a 100 m field with 15 buildings at s = 3 m).
  std::vector<std::pair<double, double>> estimates;  // (estimate, angle)
  const auto screened = searchSweepDirection(
      *problem.wall,
      [&](double deg) -> std::optional<double> {
        const double e = estimatedSweepCost(problem, sweep, deg);
        estimates.push_back({e, deg});
        return e;
      },
      [&] { return !budget.expired(); });
  if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the direction search");
  if (!screened) return plan_at(sweep.angle_deg);
  std::stable_sort(estimates.begin(), estimates.end());
  std::optional<PlanResult> best;
  double best_cost = 0.0, best_angle = 0.0;
  std::size_t plans = 0;
  for (std::size_t k = 0; k < estimates.size() && plans < kPlannedDirections; ++k) {
    if (budget.expired()) break;
    PlanResult r = plan_at(estimates[k].second);
    ++plans;
    if (r.status != PlanStatus::Ok) continue;
    const double c = objectiveCost(r.path, problem, sweep);
    if (!best || c < best_cost || (c == best_cost && estimates[k].second < best_angle)) {
      best = std::move(r);
      best_cost = c;
      best_angle = estimates[k].second;
    }
  }
  if (!best) {
    if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the direction search");
    return plan_at(sweep.angle_deg);  // reports why
  }
  best->stats["direction_evaluations"] = static_cast<double>(screened->evaluations);
  best->stats["direction_plans"] = static_cast<double>(plans);
  best->stats["direction_cost"] = best_cost;
  return std::move(*best);
}

}  // namespace coverbench
