// The planner of docs/ADDING_A_PLANNER.md compiles against the real interface and honours the
// planner contract.
#include <gtest/gtest.h>

#include "../docs/examples/perimeter_planner.cpp"
#include "coverbench/registry.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

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

}  // namespace
}  // namespace coverbench
