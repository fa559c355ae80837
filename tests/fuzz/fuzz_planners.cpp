// Every planner on walls made from the fuzzer's bytes: a rectangular or star-shaped boundary
// with up to eight rectangles, circles and star-shaped polygons, a tool and a planner. The wall
// checker decides which walls are walls; on those, a planner must return a path the exact
// validator passes, or a failure status with a reason. Grids stay under about 20,000 cells so
// that one input takes milliseconds, not minutes.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace coverbench;

/// A star-shaped ring (angles increasing, so always simple) around `c`, counter-clockwise.
Ring starRing(FuzzedDataProvider& in, Point c, double max_radius) {
  const int n = in.ConsumeIntegralInRange<int>(3, 9);
  Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * (i + in.ConsumeFloatingPointInRange<double>(0.0, 0.9)) / n;
    const double r = max_radius * in.ConsumeFloatingPointInRange<double>(0.2, 1.0);
    ring.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return ring;
}

Wall makeWall(FuzzedDataProvider& in, double& width, double& height) {
  Wall wall;
  wall.name = "fuzz";
  width = in.ConsumeFloatingPointInRange<double>(0.3, 20.0);
  height = in.ConsumeFloatingPointInRange<double>(0.3, 20.0);
  if (in.ConsumeBool()) {
    wall.boundary = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  } else {
    Ring star = starRing(in, {width / 2, height / 2}, std::min(width, height) / 2);
    double minx = 1e300, miny = 1e300;
    for (const Point& p : star) minx = std::min(minx, p.x), miny = std::min(miny, p.y);
    for (Point& p : star) p = {p.x - minx, p.y - miny};  // origin at the lower-left corner
    wall.boundary = star;
  }
  const int obstacles = in.ConsumeIntegralInRange<int>(0, 8);
  for (int i = 0; i < obstacles; ++i) {
    Obstacle o;
    const Point c{in.ConsumeFloatingPointInRange<double>(0.0, width), in.ConsumeFloatingPointInRange<double>(0.0, height)};
    const double size = in.ConsumeFloatingPointInRange<double>(0.01, std::min(width, height) / 2);
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
      case 0: {
        const double w = size, h = size * in.ConsumeFloatingPointInRange<double>(0.1, 3.0);
        o.type = ObstacleType::Rect;
        o.polygon = {{c.x, c.y}, {c.x + w, c.y}, {c.x + w, c.y + h}, {c.x, c.y + h}};
        break;
      }
      case 1:
        o.type = ObstacleType::Circle;
        o.center = c;
        o.radius = size / 2;
        break;
      default:
        o.type = ObstacleType::Polygon;
        o.polygon = starRing(in, c, size);
    }
    wall.obstacles.push_back(std::move(o));
  }
  return wall;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  double width = 0, height = 0;
  const Wall wall = makeWall(in, width, height);
  try {
    validateWall(wall, "fuzz");
  } catch (const InputError&) {
    return 0;  // not a wall: the parser would have refused it
  }
  const auto& planners = registeredPlanners();
  const PlannerInfo& info = planners[in.ConsumeIntegralInRange<std::size_t>(0, planners.size() - 1)];
  ToolParams tool;
  const double min_width = std::sqrt(width * height / 20000.0);
  tool.tool_width = std::max(min_width, in.ConsumeFloatingPointInRange<double>(0.02, 1.0));
  tool.clearance = in.ConsumeFloatingPointInRange<double>(0.0, 0.1);
  Problem problem;
  problem.wall = &wall;
  problem.tool = tool;
  problem.params = resolveParams(info, {});
  problem.seed = in.ConsumeIntegral<std::uint64_t>();
  const PlanResult result = runPlanner(info, problem, Budget(std::chrono::seconds(20)));
  if (!result.hasPath()) {
    if (result.reason.empty()) fuzz::broken(info.name + ": a failure status without a reason");
    if (result.reason.rfind("planner threw", 0) == 0) fuzz::broken(info.name + ": " + result.reason);
    if (!result.path.waypoints.empty()) fuzz::broken(info.name + ": a failure status with a path");
    return 0;
  }
  if (result.path.waypoints.empty()) fuzz::broken(info.name + ": status " + toString(result.status) + " with an empty path");
  if (result.path.tool_on.size() + 1 != result.path.waypoints.size()) fuzz::broken(info.name + ": tool_on is not one per segment");
  const Validity v = checkValidity(wall, tool, result.path);
  if (!v.valid)
    fuzz::broken(info.name + ": an invalid path (" + std::to_string(v.violations) + " violating segments, min clearance " +
                 std::to_string(v.min_clearance) + ", min boundary gap " + std::to_string(v.min_boundary_gap) + ")");
  if (result.status == PlanStatus::Ok && result.leftPartsOut()) fuzz::broken(info.name + ": ok, yet it says it left parts out");
  return 0;
}
