#pragma once
/// The one way a planning problem is made. Every entrance (the command line, an experiment's run,
/// the conformance suite, Python, the server) gathers what it was given here and receives a
/// `Problem` checked one way: the tool against the wall (validateToolForWall), the vehicle
/// (validateVehicle), the transit planner's budget, the memory limit, and the parameters (every
/// declared one present, of its declared type; the codec, param_codec.hpp, read them).
#include <cstddef>
#include <cstdint>
#include <string>

#include "coverbench/external_planner.hpp"
#include "coverbench/planner.hpp"

namespace coverbench {

/// What an entrance gives: the wall (it must outlive the problem), the tool, the vehicle, the
/// transit planner, the clock (`motion`), the planner's resolved parameters, the seed and the
/// memory limit of a planner's own processes. The wall's start and end are the wall's.
struct ProblemInputs {
  const Wall* wall = nullptr;
  ToolParams tool;
  VehicleModel vehicle;
  TransitSpec transit;
  MotionLimits motion;
  Params params;
  std::uint64_t seed = 0;
  std::size_t memory_limit_bytes = external::kDefaultMemoryLimitBytes;
};

/// The problem `planner` is given for `inputs`. Throws InputError naming `source` (the file or
/// flag the inputs came from) and the field for an input out of its limits.
Problem buildProblem(const PlannerInfo& planner, ProblemInputs inputs, const std::string& source);

}  // namespace coverbench
