#include "boustrophedon.hpp"

#include "decomposition/decomposition_planner.hpp"

namespace coverbench::boustrophedon {

PlannerInfo info() {
  return decomposition::plannerInfo(
      decomposition::Kind::Boustrophedon,
      {.name = "boustrophedon", .version = "14", .code_folders = {"boustrophedon", "decomposition"},
       .summary = "Boustrophedon cellular decomposition of the free region (cells split only at critical points), "
                  "cells ordered by a TSP tour and covered by back-and-forth passes",
       .reference = "Choset, Coverage of known spaces: the boustrophedon cellular decomposition, Autonomous Robots 9, 2000"});
}

}  // namespace coverbench::boustrophedon
