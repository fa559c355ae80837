// What planning/include/coverbench/planner.hpp declares: the names of parameter values and plan
// statuses. Here, in the planning toolkit, so that every
// library that uses them (the sweep search, the planners, the runner) finds them below itself.
#include "coverbench/planner.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace coverbench {

std::string toString(const ParamValue& value) {
  struct Visitor {
    std::string operator()(double d) const {
      // Ten significant digits as before (so keys of such values stay), more when ten do not read
      // back: two values that differ in the eleventh digit are two configurations.
      char buf[64];
      for (int digits = 10; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, d);
        if (std::strtod(buf, nullptr) == d) break;
      }
      return buf;
    }
    std::string operator()(long long i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{}, value);
}

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
