#pragma once
/// `zigzag`: boustrophedon rows over the free region, with boundary-following passes.
///
/// Reference: the lawnmower / boustrophedon pattern as surveyed by Galceran and Carreras,
/// "A survey on coverage path planning for robotics", RAS 61(12), 2013; seeds 000 and 001, with
/// their mistakes fixed (rows over the exact free region, evenly spaced, transits routed around
/// obstacles). See README.md beside this file.

#include "coverbench/planner.hpp"

namespace coverbench::zigzag {

PlannerInfo info();

}  // namespace coverbench::zigzag
