#pragma once
/// `trapezoidal`: vertical trapezoidal decomposition of the free region (seed 002; Choset et al.,
/// Principles of Robot Motion, sec. 6.1), cells ordered and covered by back-and-forth passes.
/// See algorithms/decomposition/README.md.

#include "coverbench/planner.hpp"

namespace coverbench::trapezoidal {

PlannerInfo info();

}  // namespace coverbench::trapezoidal
