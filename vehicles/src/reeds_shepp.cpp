// car.hpp's OMPL curves, answered by the plug-in libcoverbench_ompl.so (ompl_curves_plugin.hpp),
// opened by the first curve a process asks for.
#include "coverbench/car.hpp"
#include "coverbench/plugin.hpp"
#include "ompl_curves_plugin.hpp"

namespace coverbench {
namespace {

const vehicle_detail::OmplCurvesApi& ompl() {
  static const PluginSpec spec{"OMPL", "a car that may reverse cannot be planned for", "libcoverbench_ompl.so",
                               "COVERBENCH_OMPL_PLUGIN", COVERBENCH_OMPL_PLUGIN_PATH, vehicle_detail::kOmplCurvesEntry,
                               vehicle_detail::kOmplCurvesAbi};
  static const auto* api = static_cast<const vehicle_detail::OmplCurvesApi*>(openPlugin(spec, nullptr));
  return *api;
}

}  // namespace

std::vector<CurvePrimitive> reedsSheppPrimitives(Pose from, Pose to, double radius) {
  return ompl().reeds_shepp_primitives(from, to, radius);
}
double reedsSheppLength(Pose from, Pose to, double radius) { return ompl().reeds_shepp_length(from, to, radius); }
double omplDubinsLength(Pose from, Pose to, double radius) { return ompl().dubins_length(from, to, radius); }

}  // namespace coverbench
