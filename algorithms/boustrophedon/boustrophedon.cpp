#include "boustrophedon.hpp"

#include "decomposition/decomposition_planner.hpp"

namespace coverbench::boustrophedon {

PlannerInfo info() {
  PlannerInfo info = decomposition::plannerInfo(decomposition::Kind::Boustrophedon);
  info.name = "boustrophedon";
  info.version = std::string("12");  // not = "12": GCC 12 warns falsely (-Wrestrict) on that assignment here
  info.code_folders = {"boustrophedon", "decomposition"};
  info.summary = "Boustrophedon cellular decomposition of the free region (cells split only at critical points), "
                 "cells ordered by a TSP tour and covered by back-and-forth passes";
  info.reference = "Choset, Coverage of known spaces: the boustrophedon cellular decomposition, Autonomous Robots 9, 2000";
  return info;
}

}  // namespace coverbench::boustrophedon
