// OMPL's Dubins and Reeds-Shepp curves for the car: one of the two translation units that include
// OMPL (the other is transits/src/ompl_transit.cpp; third_party_notes/ompl.md).
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include "coverbench/car.hpp"

namespace coverbench {

namespace ob = ompl::base;

namespace {

/// Calls f(state of `from`, state of `to`) on states of `space`, freed after.
template <class Space, class F>
auto withStates(Space& space, Pose from, Pose to, F&& f) {
  auto* a = space.allocState()->template as<ob::SE2StateSpace::StateType>();
  auto* b = space.allocState()->template as<ob::SE2StateSpace::StateType>();
  a->setXY(from.at.x, from.at.y);
  a->setYaw(from.heading);
  b->setXY(to.at.x, to.at.y);
  b->setYaw(to.heading);
  auto result = f(a, b);
  space.freeState(a);
  space.freeState(b);
  return result;
}

}  // namespace

std::vector<CurvePrimitive> reedsSheppPrimitives(Pose from, Pose to, double radius) {
  ob::ReedsSheppStateSpace space(radius);
  const ob::ReedsSheppStateSpace::ReedsSheppPath p = withStates(space, from, to, [&](auto* a, auto* b) { return space.reedsShepp(a, b); });
  std::vector<CurvePrimitive> out;
  for (int i = 0; i < 5; ++i) {
    const auto t = p.type_[i];
    if (t == ob::ReedsSheppStateSpace::RS_NOP || p.length_[i] == 0.0) continue;
    out.push_back({t == ob::ReedsSheppStateSpace::RS_LEFT ? 'L' : t == ob::ReedsSheppStateSpace::RS_RIGHT ? 'R' : 'S', p.length_[i]});
  }
  return out;
}

double reedsSheppLength(Pose from, Pose to, double radius) {
  ob::ReedsSheppStateSpace space(radius);
  return withStates(space, from, to, [&](auto* a, auto* b) { return space.reedsShepp(a, b).length() * radius; });
}

double omplDubinsLength(Pose from, Pose to, double radius) {
  ob::DubinsStateSpace space(radius, false);
  return withStates(space, from, to, [&](auto* a, auto* b) { return space.dubins(a, b).length() * radius; });
}

}  // namespace coverbench

