// OMPL's sampling-based planners as transit planners: one of the two translation units that
// include OMPL (3-4 s of compile time; the other is vehicles/src/ompl_curves.cpp; third_party_notes/ompl.md),
// both built into the plug-in libcoverbench_ompl.so (ompl_plugin.hpp): it links OMPL and nothing
// of ours, and checks states and motions with the host's free test.
#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <stdexcept>

#include "ompl_plugin.hpp"

namespace coverbench {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

Point pointOf(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return {v->values[0], v->values[1]};
}

/// A motion is valid when the straight move is free: the exact check, no sampling along it.
class ExactMotionValidator final : public ob::MotionValidator {
 public:
  ExactMotionValidator(const ob::SpaceInformationPtr& si, transit_detail::FreeTest is_free, const void* router)
      : ob::MotionValidator(si), is_free_(is_free), router_(router) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool ok = is_free_(router_, pointOf(s1), pointOf(s2));
    ok ? ++valid_ : ++invalid_;
    return ok;
  }
  /// Reports no valid part of an invalid motion (the first state), which planners accept.
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    const bool ok = checkMotion(s1, s2);
    if (!ok) {
      if (last_valid.first) si_->copyState(last_valid.first, s1);
      last_valid.second = 0.0;
    }
    return ok;
  }

 private:
  transit_detail::FreeTest is_free_;
  const void* router_;
};

/// PRM* whose roadmap grows for a number of iterations in this thread, then answers the query
/// with the shortest path through it. (OMPL's PRM::solve checks for a solution in a second thread
/// and alternates growing and expanding by wall-clock time: not repeatable.)
class RepeatablePrmStar final : public og::PRMstar {
 public:
  using og::PRMstar::PRMstar;
  ob::PathPtr query(const ob::State* start, const ob::State* goal, const ob::PlannerTerminationCondition& ptc) {
    setup();
    growRoadmap(ptc);
    const Vertex s = addMilestone(si_->cloneState(start));
    const Vertex g = addMilestone(si_->cloneState(goal));
    if (!sameComponent(s, g)) return nullptr;
    return constructSolution(s, g);
  }
};

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si) {
  if (name == "rrtstar") return std::make_shared<og::RRTstar>(si);
  if (name == "informed-rrtstar") return std::make_shared<og::InformedRRTstar>(si);
  if (name == "bitstar") return std::make_shared<og::BITstar>(si);
  throw std::invalid_argument("no sampling transit planner named " + name);
}

SampledRoute route(const TransitSpec& spec, transit_detail::FreeTest is_free, const void* router, const Box& bounds,
                   std::uint64_t query_seed, Point a, Point b) {
  // Every OMPL random generator made from here on is seeded from this query's seed. (OMPL
  // complains, silenced when the plug-in is opened, when seeds were drawn before: the ones drawn
  // now are repeatable.)
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(query_seed % 4294967291ULL) + 1U);

  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds box(2);
  box.setLow(0, bounds.min_x);
  box.setHigh(0, bounds.max_x);
  box.setLow(1, bounds.min_y);
  box.setHigh(1, bounds.max_y);
  space->setBounds(box);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([is_free, router](const ob::State* s) {
    const Point p = pointOf(s);
    return is_free(router, p, p);
  });
  si->setMotionValidator(std::make_shared<ExactMotionValidator>(si, is_free, router));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
  start[0] = a.x;
  start[1] = a.y;
  goal[0] = b.x;
  goal[1] = b.y;
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal);
  pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));

  // Iterations, not time, end a query; the cap only stops a runaway one (and is reported).
  long long calls = 0;
  bool capped = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(spec.time_cap_s);
  const long long budget = spec.iterations;
  const ob::PlannerTerminationCondition ptc([&] {
    if (++calls > budget) return true;
    if ((calls & 63) == 0 && std::chrono::steady_clock::now() > deadline) capped = true;
    return capped;
  });

  ob::PathPtr path;
  if (spec.planner == "prmstar") {
    RepeatablePrmStar prm(si);
    prm.setProblemDefinition(pdef);
    path = prm.query(start.get(), goal.get(), ptc);
  } else {
    ob::PlannerPtr planner = makePlanner(spec.planner, si);
    planner->setProblemDefinition(pdef);
    planner->setup();
    planner->solve(ptc);
    if (pdef->hasExactSolution()) path = pdef->getSolutionPath();
  }
  SampledRoute out;
  out.time_capped = capped;
  if (!path) return out;
  const auto& states = path->as<og::PathGeometric>()->getStates();
  std::vector<Point> points;
  points.reserve(states.size());
  for (const ob::State* s : states) points.push_back(pointOf(s));
  if (points.size() < 2 || !(points.front() == a) || !(points.back() == b)) return out;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)  // never trust a planner's claim
    if (!is_free(router, points[i], points[i + 1])) return out;
  out.route = std::move(points);
  return out;
}

}  // namespace
}  // namespace coverbench

extern "C" __attribute__((visibility("default"))) const void* coverbench_ompl_transit_plugin(const void*) {
  using namespace coverbench;
  static const transit_detail::OmplTransitApi api = [] {
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    return transit_detail::OmplTransitApi{transit_detail::kOmplTransitAbi, &route};
  }();
  return &api;
}
