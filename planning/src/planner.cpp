// What planning/include/coverbench/planner.hpp declares: the names of plan statuses. Here, in the
// planning toolkit, so that every library that uses them finds them below itself.
#include "coverbench/planner.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace coverbench {

std::string toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::Ok: return "ok";
    case PlanStatus::Partial: return "partial";
    case PlanStatus::NoReachableArea: return "no_reachable_area";
    case PlanStatus::InvalidInput: return "invalid_input";
    case PlanStatus::Timeout: return "timeout";
    case PlanStatus::Error: return "error";
    case PlanStatus::Crash: return "crash";
    case PlanStatus::MemoryLimit: return "memory_limit";
    case PlanStatus::InvalidOutput: return "invalid_output";
  }
  return "error";
}

}  // namespace coverbench
