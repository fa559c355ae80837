#pragma once
/// Transit planners: how a planner's tool-off detours around obstacles are found (docs/transits.md).
///
/// `visibility` is the shortest path on TransitRouter's visibility graph (the default: every result
/// before transit planners is this); its nodes circumscribe F's round corners, so along an arc it
/// can be up to 4 / pi longer than the true shortest path (docs/transits.md). The others are OMPL's sampling-based planners over F, in one
/// translation unit (transits/src/ompl_transit.cpp; this header does not include OMPL): their states
/// are checked with our exact geometry (a point is valid when the tool disk there keeps the
/// clearance, a motion when the straight move is free: TransitRouter::isFree, no sampling along
/// it), so every route they return is valid. A route is a pure function of its query, the
/// planner, its iteration budget and the problem's seed: planners stop after a number of
/// iterations, not after a time (a wall-clock cap only stops a runaway query, and says so).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"  // TransitSpec

namespace coverbench {

class TransitRouter;

/// What every sampling planner's route stays within, as a multiple of the visibility route, on
/// the conformance walls at the default iterations (tests/transits/transit_planners_test.cpp; measured
/// factors per planner in docs/transits.md).
inline constexpr double kSamplingTransitFactor = 1.3;

/// A registered transit planner.
struct TransitPlannerInfo {
  std::string name;
  std::string summary;
  std::string reference;
  bool sampling = false;  ///< OMPL's: takes iterations and the seed
};
/// Every transit planner, `visibility` first.
const std::vector<TransitPlannerInfo>& transitPlanners();
/// The planner named `name`, or nullptr.
const TransitPlannerInfo* findTransitPlanner(const std::string& name);

/// One query's answer from a sampling planner.
struct SampledRoute {
  std::optional<std::vector<Point>> route;  ///< nullopt: no route within the budget
  bool time_capped = false;                 ///< stopped by the wall-clock cap, not the iterations
};

/// A sampling-based transit planner over F (OMPL), for one problem.
class SamplingTransit {
 public:
  virtual ~SamplingTransit() = default;
  /// A free polyline a, ..., b (every segment checked with router.isFree), or none.
  virtual SampledRoute route(Point a, Point b) = 0;
};

/// OMPL's planner `name` (a sampling entry of transitPlanners()) over the free region `router`
/// checks, sampling within `bounds` (the wall's bounding box). Query k of this object is seeded
/// from (seed, k), so a plan's routes repeat exactly.
std::unique_ptr<SamplingTransit> makeSamplingTransit(const TransitSpec& spec, const TransitRouter& router,
                                                     const Box& bounds, std::uint64_t seed);

/// Opens OMPL's plug-in (libcoverbench_ompl.so, coverbench/plugin.hpp) now, as the first sampling
/// query would: what will plan with a sampling planner calls it before any work, so a missing
/// plug-in is an InputError naming the file, and the worker processes forked after it share it.
void loadSamplingTransits();

}  // namespace coverbench
