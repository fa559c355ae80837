#pragma once
/// `adaptive-resolution`: a quadtree over the free region whose leaves shrink where obstacles and
/// edges cut in; rows across open leaves, single cells near obstacles, a loop along every edge,
/// and optional waypoint density that adapts to the distance from obstacles (seed 000's idea).
/// See README.md beside this file.

#include "coverbench/planner.hpp"

namespace coverbench::adaptive_resolution {

PlannerInfo info();

}  // namespace coverbench::adaptive_resolution
