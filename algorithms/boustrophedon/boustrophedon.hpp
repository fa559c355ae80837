#pragma once
/// `boustrophedon`: Choset's boustrophedon cellular decomposition of the free region (cells split
/// only where the sweep line's connectivity changes), cells ordered and covered by back-and-forth
/// passes. See algorithms/decomposition/README.md.

#include "coverbench/planner.hpp"

namespace coverbench::boustrophedon {

PlannerInfo info();

}  // namespace coverbench::boustrophedon
