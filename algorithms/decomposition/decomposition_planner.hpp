#pragma once
/// The planner shared by `trapezoidal` and `boustrophedon`: decompose the free region into
/// cells, order the cells, cover each with back-and-forth passes, route between them.
/// See README.md beside this file.

#include "cell_decomposition.hpp"
#include "coverbench/planner.hpp"

namespace coverbench::decomposition {

/// Everything but name, summary and reference, which each planner's folder sets.
PlannerInfo plannerInfo(Kind kind);

}  // namespace coverbench::decomposition
