#pragma once
/// Sweep-direction search for any sweep-based planner (seed 003): coarse steps over [0, 180)
/// degrees plus the directions of the longest edges, then fine steps around the best, minimising
/// path length plus a penalty per turn (estimated for every direction, planned for the best).
#include <cstddef>
#include <functional>
#include <optional>

#include "coverbench/param_table.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

struct SweepSearch {
  double angle_deg = 0.0;  ///< the best direction found, in [0, 180)
  double cost = 0.0;
  std::size_t evaluations = 0;
};

/// `cost(angle_deg)` plans at that direction and returns its cost, or nothing when the plan
/// failed. Ties go to the smaller angle, so the result is deterministic. Returns nothing when
/// every direction failed or `keep_going` said stop before any succeeded.
std::optional<SweepSearch> searchSweepDirection(const Wall& wall, const std::function<std::optional<double>(double)>& cost,
                                                const std::function<bool()>& keep_going, double coarse_step_deg = 5.0,
                                                double fine_step_deg = 1.0, std::size_t longest_edges = 4);

/// The sweep direction of a sweep-based planner: the parameter group every sweep planner includes
/// (sweepDirectionParams).
struct SweepDirection {
  /// What the search minimises (`objective`): length plus turn_penalty per turn over 30 degrees,
  /// the time under the problem's time model (its stops and cost per turn included), or the turns.
  enum class Objective { Length, Time, Turns };
  double angle_deg = 0.0;       ///< `sweep_angle`: the passes' direction, counter-clockwise from +x
  bool search = false;          ///< `direction_search`: search it instead
  double turn_penalty_m = 1.0;  ///< `turn_penalty`: what a turn over 30 degrees costs in the search
  Objective objective = Objective::Length;
};
/// The group's parameters: sweep_angle, direction_search, turn_penalty, objective.
const ParamTable<SweepDirection>& sweepDirectionParams();

/// How many of the search's directions are planned: the ones with the lowest estimated cost.
inline constexpr std::size_t kPlannedDirections = 2;

/// The sweep-direction protocol of a sweep-based planner: plans at `sweep.angle_deg`, or, with the
/// search on, ranks every direction of searchSweepDirection by an estimate of its rows' cost
/// (the wall minus its obstacles cut into rows a tool width apart, each row its length, a
/// connection and two turns), plans the kPlannedDirections best, and returns the plan of lower
/// sweepCost (its statistics gain `direction_evaluations`, `direction_plans` and
/// `direction_cost`). `plan_at(angle_deg)` plans at one direction. Every plan returned with a
/// path carries the direction it swept as the statistic `sweep_angle_deg`: planners do not write it.
PlanResult planSweep(const Problem& problem, const SweepDirection& sweep, const Budget& budget,
                     const std::function<PlanResult(double)>& plan_at);

/// Path length plus `turn_penalty_m` metres for every heading change over 30 degrees (a stop on
/// the machine): the cost the search minimises with the objective `length`.
double sweepCost(const Path& path, double turn_penalty_m);
/// The cost the search minimises: sweepCost for `length`; for `time` the path's duration under
/// the problem's time model plus its cost per turn; for `turns` the turns over 30 degrees (length
/// breaking ties).
double objectiveCost(const Path& path, const Problem& problem, const SweepDirection& sweep);

}  // namespace coverbench
