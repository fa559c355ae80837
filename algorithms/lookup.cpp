// Finding a planner by name: the registered ones (registry.cpp) and those added beside them
// (planners outside the tree, test planners).
#include "coverbench/registry.hpp"

#include <deque>

namespace coverbench {

namespace {

/// Planners added by name beside the registered ones: planners outside the tree and test planners.
std::deque<PlannerInfo>& addedPlanners() {  // a deque: references stay valid as it grows
  static std::deque<PlannerInfo> planners;
  return planners;
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
  throw InputError(source, shownBytes(name), "unknown planner (registered: " + known + ")");
}

}  // namespace coverbench
