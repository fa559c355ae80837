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
                "search the sweep direction (5-degree steps and the longest edges, then 1-degree steps); overrides "
                "sweep_angle"},
               &SweepDirection::search)
          .add({"turn_penalty", ParamType::Number, 1.0, 0.0, 1000.0, {}, "m",
                "cost of a turn over 30 degrees in the direction search"},
               &SweepDirection::turn_penalty_m);
  return table;
}

PlanResult planSweep(const Problem& problem, const SweepDirection& sweep, const Budget& budget,
                     const std::function<PlanResult(double)>& plan_at) {
  if (!sweep.search) return plan_at(sweep.angle_deg);
  const double penalty = sweep.turn_penalty_m;
  const auto search = searchSweepDirection(
      *problem.wall,
      [&](double deg) -> std::optional<double> {
        const PlanResult r = plan_at(deg);
        if (r.status != PlanStatus::Ok) return std::nullopt;
        return sweepCost(r.path, penalty);
      },
      [&] { return !budget.expired(); });
  if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out in the direction search");
  if (!search) return plan_at(sweep.angle_deg);  // reports why
  PlanResult result = plan_at(search->angle_deg);
  result.stats["direction_evaluations"] = static_cast<double>(search->evaluations);
  result.stats["direction_cost"] = search->cost;
  return result;
}

}  // namespace coverbench
