// The planner of docs/ADDING_A_PLANNER.md compiles against the real interface, is the code the
// guide shows, and passes what every registered planner must: the conformance checks of the
// report card and the suite (coverbench/conformance.hpp) on every conformance wall at both tools.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../../docs/examples/perimeter_planner.cpp"
#include "coverbench/conformance.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

std::string slurp(const std::string& relative) {
  std::ifstream in(test::sourcePath(relative), std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The body of the first ```cpp block after the line `heading` of a Markdown text ("" if none).
std::string codeBlockAfter(const std::string& text, const std::string& heading) {
  const std::size_t h = text.find("\n" + heading + "\n");
  if (h == std::string::npos) return "";
  const std::size_t open = text.find("\n```cpp\n", h);
  if (open == std::string::npos) return "";
  const std::size_t begin = open + 8;
  const std::size_t close = text.find("\n```\n", begin - 1);
  return close == std::string::npos ? "" : text.substr(begin, close + 1 - begin);
}

TEST(ExamplePlanner, ProducesValidLoops) {
  const PlannerInfo info = perimeter::info();
  const Wall wall = loadWallFile(test::sourcePath("datasets/canonical/living_room_north.json"));
  Problem problem;
  problem.wall = &wall;
  problem.params = resolveParams(info, {{"inset", "0.05"}});
  const PlanResult r = runPlanner(info, problem, Budget());
  ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
  EXPECT_TRUE(test::isValidPath(wall, problem.tool, r.path));
  EXPECT_GT(r.path.waypoints.size(), 10u);
}

// The guide's code is the compiled example's, byte for byte: the whole file, in the block under
// "## A complete example"; its registry lines are the registry's, the example's added.
TEST(ExamplePlanner, TheGuideShowsTheCompiledExample) {
  const std::string guide = slurp("docs/ADDING_A_PLANNER.md");
  const std::string example = slurp("docs/examples/perimeter_planner.cpp");
  ASSERT_FALSE(example.empty());
  EXPECT_EQ(codeBlockAfter(guide, "## A complete example"), example);
  const std::string registry_block = codeBlockAfter(guide, "Then in `algorithms/registry.cpp`:");
  ASSERT_FALSE(registry_block.empty());
  const std::string registry = slurp("algorithms/registry.cpp");
  std::istringstream lines(registry_block);
  int checked = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("perimeter") != std::string::npos || line.find("...") != std::string::npos || line.empty()) continue;
    EXPECT_NE(registry.find(line), std::string::npos) << "the guide's line '" << line << "' is not in algorithms/registry.cpp";
    ++checked;
  }
  EXPECT_GE(checked, 4);
  EXPECT_NE(registry_block.find("#include \"perimeter/perimeter.hpp\""), std::string::npos);
  EXPECT_NE(registry_block.find("perimeter::info(),"), std::string::npos);
}

// A planner written from the guide passes the report card and the suite's conformance checks: on
// every conformance wall at both tools, the outcome the wall calls for (ok, partial with its
// reason where F is split, no_reachable_area where it is empty), a path both judges find valid,
// the same path twice, and the pieces of F reported as the definition counts them.
TEST(ExamplePlanner, PassesTheConformanceChecksOnEveryWall) {
  const PlannerInfo info = perimeter::info();
  const Params params = resolveParams(info, {});
  int partial = 0, none = 0;
  forEachConformanceProblem(info, test::conformanceWallFiles(), params, [&](const std::string&, Problem& problem) {
    const Wall& wall = *problem.wall;
    const ToolParams& tool = problem.tool;
    const JudgedPlan judged = planAndJudge(info, problem, Budget(std::chrono::seconds(60)));
    const std::string where = wall.name + " at s = " + std::to_string(tool.tool_width);
    const ExpectedOutcome expected = expectedOutcome(wall, tool);
    const ConformanceCheck check = checkConformance(expected, judged, info.min_coverage_reachable, true);
    EXPECT_TRUE(check.passed()) << where << ": " << check.cause;
    const PlanResult& r = judged.result;
    partial += r.status == PlanStatus::Partial;
    none += r.status == PlanStatus::NoReachableArea;
    if (!r.hasPath()) return;
    EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << where;
    EXPECT_EQ(r.free_components, expected.free_components) << where;
    EXPECT_EQ(r.unreachable_parts, 0u) << where << ": " << r.reason;
    const PlanResult again = runPlanner(info, problem, Budget(std::chrono::seconds(60)));
    ASSERT_EQ(again.path.waypoints.size(), r.path.waypoints.size()) << where;
    for (std::size_t i = 0; i < r.path.waypoints.size(); ++i)
      ASSERT_TRUE(again.path.waypoints[i] == r.path.waypoints[i]) << where << " waypoint " << i;
  });
  EXPECT_EQ(partial, 4);  // narrow_gap_disconnected at s = 0.1, overlapping_cluster at 0.05, rotated_polygons at both
  EXPECT_EQ(none, 1);     // exactly_tool_height at s = 0.1
}

}  // namespace
}  // namespace coverbench
