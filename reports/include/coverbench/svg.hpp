#pragma once
/// SVG pictures of a wall and a path: wall, obstacles, free region, swept band, coverage layer
/// (uncovered reachable area, areas passed twice or more), path (tool on solid, transit dashed),
/// start and end. Scaled to a fixed picture size so a 20 m facade and a
/// 1 m strip are equally readable; a scale bar gives metres.

#include <string>

#include "coverbench/geometry.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

struct SvgContent {
  const Wall* wall = nullptr;
  ToolParams tool;
  const Region* free = nullptr;  ///< optional: the free centre region F
  const Path* path = nullptr;    ///< optional
  const Region* uncovered = nullptr;  ///< optional coverage layer: reachable but not swept
  const Region* overlap = nullptr;    ///< optional coverage layer: passed over twice or more
  std::string title;
};

std::string renderSvg(const SvgContent& content);

}  // namespace coverbench
