// The sampling transit planners' host side: each query is answered by OMPL in the plug-in
// libcoverbench_ompl.so (ompl_plugin.hpp), opened by the first query of the process.
#include <memory>
#include <stdexcept>

#include "coverbench/plugin.hpp"
#include "coverbench/transit_planners.hpp"
#include "coverbench/transit_router.hpp"
#include "ompl_plugin.hpp"

namespace coverbench {
namespace {

/// SplitMix64's finaliser: a query's seed from the plan's seed and the query's number.
std::uint64_t mixSeed(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

const transit_detail::OmplTransitApi& ompl() {
  static const PluginSpec spec{"OMPL", "the sampling transit planners cannot run", "libcoverbench_ompl.so",
                               "COVERBENCH_OMPL_PLUGIN", COVERBENCH_OMPL_PLUGIN_PATH, transit_detail::kOmplTransitEntry,
                               transit_detail::kOmplTransitAbi};
  static const auto* api = static_cast<const transit_detail::OmplTransitApi*>(openPlugin(spec, nullptr));
  return *api;
}

bool isFree(const void* router, Point a, Point b) { return static_cast<const TransitRouter*>(router)->isFree(a, b); }

class OmplTransit final : public SamplingTransit {
 public:
  OmplTransit(const TransitSpec& spec, const TransitRouter& router, const Box& bounds, std::uint64_t seed)
      : spec_(spec), router_(&router), bounds_(bounds), seed_(seed) {}

  SampledRoute route(Point a, Point b) override {
    const std::uint64_t query_seed = mixSeed(seed_ ^ mixSeed(++queries_));
    return ompl().route(spec_, &isFree, router_, bounds_, query_seed, a, b);
  }

 private:
  TransitSpec spec_;
  const TransitRouter* router_;
  Box bounds_;
  std::uint64_t seed_;
  std::uint64_t queries_ = 0;
};

}  // namespace

std::unique_ptr<SamplingTransit> makeSamplingTransit(const TransitSpec& spec, const TransitRouter& router,
                                                     const Box& bounds, std::uint64_t seed) {
  const TransitPlannerInfo* info = findTransitPlanner(spec.planner);
  if (!info || !info->sampling) throw std::invalid_argument("no sampling transit planner named " + spec.planner);
  return std::make_unique<OmplTransit>(spec, router, bounds, seed);
}

void loadSamplingTransits() { ompl(); }

}  // namespace coverbench
