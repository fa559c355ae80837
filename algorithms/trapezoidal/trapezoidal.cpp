#include "trapezoidal.hpp"

#include "decomposition/decomposition_planner.hpp"

namespace coverbench::trapezoidal {

PlannerInfo info() {
  PlannerInfo info = decomposition::plannerInfo(decomposition::Kind::Trapezoidal);
  info.name = "trapezoidal";
  info.version = std::string("12");  // not = "12": GCC 12 warns falsely (-Wrestrict) on that assignment here
  info.code_folders = {"trapezoidal", "decomposition"};
  info.summary = "Trapezoidal decomposition of the free region (a cell boundary through every corner), cells ordered "
                 "by a TSP tour and covered by back-and-forth passes";
  info.reference = "Choset et al., Principles of Robot Motion, MIT Press 2005, sec. 6.1";
  return info;
}

}  // namespace coverbench::trapezoidal
