// The one way a planning problem is made (problem_builder.hpp).
#include "coverbench/problem_builder.hpp"

#include "coverbench/limits.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/transit_planners.hpp"

#include <stdexcept>

namespace coverbench {

namespace {

/// Every declared parameter is present with a value of its type, and nothing else is given: the
/// entrances read values with the codec, so a miss here is a bug of the entrance, not of input.
void checkParams(const PlannerInfo& planner, const Params& params) {
  for (const ParamSpec& spec : planner.params) {
    const auto it = params.all().find(spec.name);
    if (it == params.all().end()) throw std::logic_error("parameter '" + spec.name + "' of " + planner.name + " was not resolved");
    if (it->second.index() != spec.default_value.index())
      throw std::logic_error("parameter '" + spec.name + "' of " + planner.name + " has a value of another type");
  }
  for (const auto& [name, value] : params.all()) paramSpec(planner, name, "parameters");
}

}  // namespace

Problem buildProblem(const PlannerInfo& planner, ProblemInputs inputs, const std::string& source) {
  if (!inputs.wall) throw std::logic_error("a problem needs a wall");
  validateToolForWall(inputs.tool, *inputs.wall, source);
  validateVehicle(inputs.vehicle, source, "vehicle");
  if (inputs.tool.turnsWithHeading() && inputs.vehicle.isCar())
    throw InputError(source, "tool.shape", "a " + toString(inputs.tool.shape) +
                                               " tool is not built for a car yet: the arcs it drives (docs/metrics.md#tool-shapes); use a disk");
  if (!findTransitPlanner(inputs.transit.planner))
    throw InputError(source, "transit", "'" + inputs.transit.planner + "' is not a transit planner");
  if (inputs.transit.iterations < 1 || inputs.transit.iterations > kMaxTransitIterations)
    throw InputError(source, "transit.iterations", "must be from 1 to " + std::to_string(kMaxTransitIterations));
  validateTimeLimit(inputs.transit.time_cap_s, source, "transit.time_cap_s");
  if (inputs.memory_limit_bytes == 0) throw InputError(source, "memory_limit", "must be positive");
  checkParams(planner, inputs.params);
  Problem problem;
  problem.wall = inputs.wall;
  problem.tool = inputs.tool;
  problem.vehicle = inputs.vehicle;
  problem.transit = std::move(inputs.transit);
  problem.motion = inputs.motion;
  problem.params = std::move(inputs.params);
  problem.seed = inputs.seed;
  problem.memory_limit_bytes = inputs.memory_limit_bytes;
  // A line or rectangle tool is scored on straight moves only: planners leave F's round boundary
  // as chords.
  problem.straight_segments_only = problem.tool.turnsWithHeading();
  return problem;
}

}  // namespace coverbench
