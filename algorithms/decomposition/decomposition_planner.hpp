#pragma once
/// The planner shared by `trapezoidal` and `boustrophedon`: decompose the free region into
/// cells, order the cells, cover each with back-and-forth passes, route between them.
/// See README.md beside this file.

#include "cell_decomposition.hpp"
#include "coverbench/planner.hpp"

namespace coverbench::decomposition {

/// The PlannerInfo of the planner of `kind`: `info` (the name, version, code folders, summary
/// and reference each planner's folder sets) with the parameters, promise and maker they share.
PlannerInfo plannerInfo(Kind kind, PlannerInfo info);

}  // namespace coverbench::decomposition
