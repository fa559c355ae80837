// The plan-file reader on any bytes (written to a scratch .json file): a path, or InputError
// naming the file. A path it accepts is within the scoring limits, so the validator and the
// metrics engine must score it against a fixed wall without failing.
#include <cstdint>
#include <string>

#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace coverbench;
  static const Wall wall = parseWallJson(
      R"({"name": "fuzz", "width": 4, "height": 3,
          "obstacles": [{"type": "rect", "x": 1, "y": 1, "width": 1, "height": 0.5},
                        {"type": "circle", "x": 3, "y": 2, "radius": 0.3}]})",
      "fuzz-wall");
  const std::string path = fuzz::scratchFile(data, size, ".json");
  LoadedPlan plan;
  try {
    plan = loadPlanFile(path);
  } catch (const InputError& e) {
    if (e.source().empty() || e.problem().empty()) fuzz::broken(std::string("InputError without source or problem: ") + e.what());
    return 0;
  }
  if (!plan.path.waypoints.empty() && plan.path.tool_on.size() + 1 != plan.path.waypoints.size())
    fuzz::broken("tool_on is not one per segment");
  if (plan.path.waypoints.size() > 2000) return 0;  // scoring large accepted paths is slow, not new
  ToolParams tool;
  tool.tool_width = 0.2;
  tool.clearance = 0.02;
  const Validity v = checkValidity(wall, tool, plan.path);
  if (v.valid != (v.violations == 0)) fuzz::broken("validity disagrees with its violation count");
  return 0;
}
