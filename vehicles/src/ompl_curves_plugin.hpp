#pragma once
// OMPL is loaded only when a car's Reeds-Shepp curve is first asked for (coverbench/plugin.hpp):
// ompl_curves.cpp is built into the plug-in libcoverbench_ompl.so (with the sampling transits,
// transits/src/ompl_transit.cpp), which reeds_shepp.cpp opens. The plug-in links OMPL and nothing
// of ours.

#include <vector>

#include "coverbench/car.hpp"

namespace coverbench::vehicle_detail {

/// What the plug-in offers the car: car.hpp's OMPL functions.
struct OmplCurvesApi {
  int abi;  ///< kOmplCurvesAbi of the plug-in's build
  std::vector<CurvePrimitive> (*reeds_shepp_primitives)(Pose from, Pose to, double radius);
  double (*reeds_shepp_length)(Pose from, Pose to, double radius);
  double (*dubins_length)(Pose from, Pose to, double radius);
};

/// Changes whenever OmplCurvesApi or the types it passes change.
inline constexpr int kOmplCurvesAbi = 1;

/// The entry: const void* coverbench_ompl_curves_plugin(const void* host) (host: none) returns an
/// OmplCurvesApi.
inline constexpr const char* kOmplCurvesEntry = "coverbench_ompl_curves_plugin";

}  // namespace coverbench::vehicle_detail
