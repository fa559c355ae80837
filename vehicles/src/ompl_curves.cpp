// OMPL's Dubins and Reeds-Shepp curves for the car: one of the two translation units that include
// OMPL (the other is transits/src/ompl_transit.cpp; third_party_notes/ompl.md), both built into the
// plug-in libcoverbench_ompl.so (ompl_curves_plugin.hpp), which links OMPL and nothing of ours.
#include <ompl/base/spaces/DubinsStateSpace.h>
#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "ompl_curves_plugin.hpp"

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

namespace {

/// OMPL's shortest Reeds-Shepp curve. A state space (and its two states) is kept per thread and
/// turn radius: building one per call was most of what a curve cost, and the sweep measures tens
/// of thousands. Curves solved are kept too, by their exact poses and radius, in a table of
/// kKept slots (a pair's slot by a hash of its numbers; a newer pair takes the slot over): the
/// sweep builds the curve whose length it just measured, and the car's route search builds the
/// curve on to the goal from the pose whose estimate it measured when it reached that pose.
ob::ReedsSheppStateSpace::ReedsSheppPath reedsShepp(Pose from, Pose to, double radius) {
  struct Kept {
    bool used = false;
    Pose from, to;
    double radius = 0.0;
    ob::ReedsSheppStateSpace::ReedsSheppPath path;
  };
  constexpr std::size_t kKept = 4096;
  thread_local std::vector<Kept> kept(kKept);
  std::uint64_t hash = 0x9e3779b97f4a7c15ULL;
  for (const double v : {from.at.x, from.at.y, from.heading, to.at.x, to.at.y, to.heading, radius}) {
    hash ^= std::bit_cast<std::uint64_t>(v) + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2);
    hash *= 0xff51afd7ed558ccdULL;
  }
  Kept& slot = kept[(hash ^ (hash >> 29)) % kKept];
  if (slot.used && slot.radius == radius && slot.from.at == from.at && slot.from.heading == from.heading &&
      slot.to.at == to.at && slot.to.heading == to.heading)
    return slot.path;
  struct Cached {
    double radius = 0.0;
    std::unique_ptr<ob::ReedsSheppStateSpace> space;
    ob::SE2StateSpace::StateType* a = nullptr;
    ob::SE2StateSpace::StateType* b = nullptr;
    ~Cached() { release(); }
    void release() {
      if (!space) return;
      space->freeState(a);
      space->freeState(b);
      space.reset();
    }
  };
  thread_local Cached cached;
  if (!cached.space || cached.radius != radius) {
    cached.release();
    cached.space = std::make_unique<ob::ReedsSheppStateSpace>(radius);
    cached.radius = radius;
    cached.a = cached.space->allocState()->as<ob::SE2StateSpace::StateType>();
    cached.b = cached.space->allocState()->as<ob::SE2StateSpace::StateType>();
  }
  cached.a->setXY(from.at.x, from.at.y);
  cached.a->setYaw(from.heading);
  cached.b->setXY(to.at.x, to.at.y);
  cached.b->setYaw(to.heading);
  slot = {true, from, to, radius, cached.space->reedsShepp(cached.a, cached.b)};
  return slot.path;
}

std::vector<CurvePrimitive> pluginPrimitives(Pose from, Pose to, double radius) {
  const ob::ReedsSheppStateSpace::ReedsSheppPath p = reedsShepp(from, to, radius);
  std::vector<CurvePrimitive> out;
  for (int i = 0; i < 5; ++i) {
    const auto t = p.type_[i];
    if (t == ob::ReedsSheppStateSpace::RS_NOP || p.length_[i] == 0.0) continue;
    out.push_back({t == ob::ReedsSheppStateSpace::RS_LEFT ? 'L' : t == ob::ReedsSheppStateSpace::RS_RIGHT ? 'R' : 'S', p.length_[i]});
  }
  return out;
}

double pluginLength(Pose from, Pose to, double radius) { return reedsShepp(from, to, radius).length() * radius; }

double pluginDubinsLength(Pose from, Pose to, double radius) {
  ob::DubinsStateSpace space(radius, false);
  return withStates(space, from, to, [&](auto* a, auto* b) { return space.dubins(a, b).length() * radius; });
}

}  // namespace
}  // namespace coverbench

extern "C" __attribute__((visibility("default"))) const void* coverbench_ompl_curves_plugin(const void*) {
  using namespace coverbench;
  static const vehicle_detail::OmplCurvesApi api{vehicle_detail::kOmplCurvesAbi, &pluginPrimitives, &pluginLength,
                                                 &pluginDubinsLength};
  return &api;
}

