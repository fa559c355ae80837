#pragma once
/// The planner registry: every planner by name (the list itself is algorithms/registry.cpp; a
/// planner's parameters are read and written by param_codec.hpp, run by runner/run_planner.hpp).

#include <string>
#include <vector>

#include "coverbench/param_codec.hpp"
#include "coverbench/planner.hpp"

namespace coverbench {

/// Every registered planner, in registration order.
const std::vector<PlannerInfo>& registeredPlanners();

/// The planner called `name` among the registered ones and those added for testing; nullptr if
/// there is none.
const PlannerInfo* lookupPlanner(const std::string& name);

/// Adds (or replaces, by name) a planner that only tests use (e.g. one that crashes, to test the
/// runner): found by name like a registered one, but never listed by registeredPlanners() nor
/// run by `planners: [all]`; it never shadows a registered planner.
void addPlannerForTesting(PlannerInfo info);

/// Adds a planner from outside the tree (an external planner's manifest, `source`), found by name
/// like a registered one but not run by `planners: [all]`. The same name again replaces it (a
/// manifest loaded twice); a registered planner's name is refused (InputError naming `source`).
const PlannerInfo& addPlanner(PlannerInfo info, const std::string& source);

/// The planner called `name`; throws InputError (naming `source`) if there is none.
const PlannerInfo& findPlanner(const std::string& name, const std::string& source = "--planner");

}  // namespace coverbench
