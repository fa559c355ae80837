#include "coverbench/path.hpp"

namespace coverbench {

void Path::moveTo(Point p, bool tool) {
  if (!waypoints.empty() && waypoints.back() == p) return;
  if (!waypoints.empty()) tool_on.push_back(tool);
  waypoints.push_back(p);
}

}  // namespace coverbench
