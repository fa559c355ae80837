// What planning/include/coverbench/planner.hpp declares: a planner's resolved parameters and the
// names of parameter values and plan statuses. Here, in the planning toolkit, so that every
// library that uses them (the sweep search, the planners, the runner) finds them below itself.
#include "coverbench/planner.hpp"

#include <cstdio>
#include <stdexcept>

namespace coverbench {

const ParamValue& Params::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("parameter '" + name + "' is not declared");
  return it->second;
}
double Params::number(const std::string& name) const { return std::get<double>(get(name)); }
long long Params::integer(const std::string& name) const { return std::get<long long>(get(name)); }
bool Params::flag(const std::string& name) const { return std::get<bool>(get(name)); }
const std::string& Params::choice(const std::string& name) const { return std::get<std::string>(get(name)); }

std::string toString(const ParamValue& value) {
  struct Visitor {
    std::string operator()(double d) const {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.10g", d);
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
  }
  return "error";
}

}  // namespace coverbench
