#include "trapezoidal.hpp"

#include "decomposition/decomposition_planner.hpp"

namespace coverbench::trapezoidal {

PlannerInfo info() {
  return decomposition::plannerInfo(
      decomposition::Kind::Trapezoidal,
      {.name = "trapezoidal", .version = "14", .code_folders = {"trapezoidal", "decomposition"},
       .summary = "Trapezoidal decomposition of the free region (a cell boundary through every corner), cells ordered "
                  "by a TSP tour and covered by back-and-forth passes",
       .reference = "Choset et al., Principles of Robot Motion, MIT Press 2005, sec. 6.1"});
}

}  // namespace coverbench::trapezoidal
