#pragma once
/// `spanning-tree`: spanning-tree coverage on a grid of tool-sized cells (seed 004), with the
/// traversal variants `return`, `stop` and `short-branches-first`, and Spiral-STC (Gabriely and
/// Rimon 2001) as the variant `spiral-stc`. See README.md beside this file.

#include "coverbench/planner.hpp"

namespace coverbench::spanning_tree {

PlannerInfo info();

}  // namespace coverbench::spanning_tree
