#pragma once
// OMPL is loaded only when a sampling transit planner runs (coverbench/plugin.hpp):
// ompl_transit.cpp is built into the plug-in libcoverbench_ompl.so (with the car's curves,
// vehicles/src/ompl_curves.cpp), which sampling_transit.cpp opens on the first sampling query. The
// plug-in links OMPL and nothing of ours: a query carries the host's free test.

#include <cstdint>

#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/transit_planners.hpp"

namespace coverbench::transit_detail {

/// Whether the straight move a-b is free (a == b: whether the tool may stand at a): the host's
/// TransitRouter::isFree on `router`.
using FreeTest = bool (*)(const void* router, Point a, Point b);

/// What the plug-in offers the transits.
struct OmplTransitApi {
  int abi;  ///< kOmplTransitAbi of the plug-in's build
  /// One query of spec.planner from a to b, sampling within `bounds`, every OMPL generator seeded
  /// from `query_seed`.
  SampledRoute (*route)(const TransitSpec& spec, FreeTest is_free, const void* router, const Box& bounds,
                        std::uint64_t query_seed, Point a, Point b);
};

/// Changes whenever OmplTransitApi or the types it passes change.
inline constexpr int kOmplTransitAbi = 1;

/// The entry: const void* coverbench_ompl_transit_plugin(const void* host) (host: none) returns
/// an OmplTransitApi.
inline constexpr const char* kOmplTransitEntry = "coverbench_ompl_transit_plugin";

}  // namespace coverbench::transit_detail
