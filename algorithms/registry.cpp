// The explicit list of planners. Adding a planner: one folder under algorithms/ and one line here.
#include "coverbench/registry.hpp"

#include "adaptive_resolution/adaptive_resolution.hpp"
#include "boustrophedon/boustrophedon.hpp"
#include "spanning_tree/spanning_tree.hpp"
#include "spiral/spiral.hpp"
#include "trapezoidal/trapezoidal.hpp"
#include "zigzag/zigzag.hpp"

namespace coverbench {

const std::vector<PlannerInfo>& registeredPlanners() {
  static const std::vector<PlannerInfo> planners = {
      zigzag::info(),
      spiral::info(),
      spanning_tree::info(),
      adaptive_resolution::info(),
      trapezoidal::info(),
      boustrophedon::info(),
  };
  return planners;
}

}  // namespace coverbench
