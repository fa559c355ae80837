#pragma once
/// `spiral`: concentric passes offset inward from the boundary of the free region.
///
/// Reference: contour-parallel ("spiral") coverage, e.g. Held, "On the Computational Geometry of
/// Pocket Machining", LNCS 500, 1991; seeds 000 and 001, with their mistakes fixed (exact round
/// offsets of F instead of point sampling, rings linked without crossing obstacles, the leftover
/// centre covered). See README.md beside this file.

#include "coverbench/planner.hpp"

namespace coverbench::spiral {

PlannerInfo info();

}  // namespace coverbench::spiral
