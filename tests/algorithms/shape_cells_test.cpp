// boustrophedon and trapezoidal for a line or rectangle tool on a gantry (shape_cells.hpp): the
// shape's own rows, zigzag's, painted cell by cell of the region where the shape may stand.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "coverbench/judge.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

ToolParams shape(ToolShape kind, double width, double depth = 0.0, double clearance = 0.02) {
  ToolParams tool{width, clearance};
  tool.shape = kind;
  tool.depth = depth;
  return tool;
}

VehicleModel gantry() {
  VehicleModel v;
  v.kind = VehicleModel::Kind::Gantry;
  return v;
}

JudgedPlan plan(const std::string& planner, const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle,
                const std::vector<std::pair<std::string, std::string>>& settings = {}) {
  const PlannerInfo& info = findPlanner(planner);
  ProblemInputs inputs;
  inputs.wall = &wall;
  inputs.tool = tool;
  inputs.vehicle = vehicle;
  inputs.params = resolveParams(info, settings);
  return planAndJudge(info, buildProblem(info, std::move(inputs), "test"), Budget());
}

/// The tool-on segments of a path, in order.
std::vector<std::pair<Point, Point>> painted(const Path& path) {
  std::vector<std::pair<Point, Point>> out;
  for (std::size_t i = 0; i < path.segments(); ++i)
    if (path.tool_on[i]) out.push_back({path.waypoints[i], path.waypoints[i + 1]});
  return out;
}

// A 2 x 1 m wall with a 0.4 x 0.4 m window in its middle, rows along x, s = 0.2 m, no loops:
// the region where the line may stand is cut into four cells (below, left of, right of and above
// the window), and each planner paints every row beside the window on one side before it paints
// any on the other. Both paint zigzag's rows (the same area covered, in another order), lifted
// between them, valid in both engines, and say nothing of a disk.
TEST(ShapeCells, TheRowsBesideAWindowArePaintedOneSideAtATime) {
  const Wall wall = test::rectWall(2.0, 1.0, {test::rect(0.8, 0.3, 0.4, 0.4)});
  const ToolParams tool = shape(ToolShape::Line, 0.2);
  const JudgedPlan rows = plan("zigzag", wall, tool, gantry(), {{"boundary_passes", "0"}});
  ASSERT_EQ(rows.verdict, RunStatus::Ok) << rows.reason;
  for (const std::string name : {"boustrophedon", "trapezoidal"}) {
    SCOPED_TRACE(name);
    const JudgedPlan j = plan(name, wall, tool, gantry(), {{"boundary_loop", "false"}});
    ASSERT_EQ(j.verdict, RunStatus::Ok) << j.reason;
    EXPECT_TRUE(j.result.planned_for_shape);
    EXPECT_EQ(j.reason.find("circumscribed"), std::string::npos) << j.reason;
    EXPECT_TRUE(test::isValidPath(wall, tool, j.result.path, gantry()));
    // boustrophedon: split only where the window begins and ends; trapezoidal at every corner too.
    if (name == "boustrophedon") EXPECT_EQ(j.result.stats.at("cells"), 4.0);
    EXPECT_GE(j.result.stats.at("cells"), 4.0);
    EXPECT_EQ(j.result.stats.at("pieces_outside_cells"), 0.0);
    EXPECT_EQ(j.result.stats.at("intervals"), rows.result.stats.at("intervals"));
    EXPECT_NEAR(j.metrics.coverage.coverage_reachable, rows.metrics.coverage.coverage_reachable, 1e-9);
    EXPECT_NEAR(j.metrics.passes.overlap, rows.metrics.passes.overlap, 1e-9);
    // Beside the window: pieces ending at its left side (x = 0.8 - c) and starting at its right.
    std::vector<int> side;  // -1 left, +1 right, 0 elsewhere, per painted segment
    for (const auto& [a, b] : painted(j.result.path)) {
      const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
      side.push_back(std::fabs(hi - 0.78) < 1e-4 ? -1 : std::fabs(lo - 1.22) < 1e-4 ? 1 : 0);
    }
    ASSERT_GE(std::count(side.begin(), side.end(), -1), 2);
    ASSERT_GE(std::count(side.begin(), side.end(), 1), 2);
    for (int s : {-1, 1}) {
      const auto first = std::find(side.begin(), side.end(), s) - side.begin();
      const auto last = side.rend() - std::find(side.rbegin(), side.rend(), s) - 1;
      for (auto k = first; k <= last; ++k) EXPECT_EQ(side[static_cast<std::size_t>(k)], s) << "segment " << k;
    }
  }
}

// A rectangle: its rows end d / 2 from the edges, as zigzag's do, and cover the bare wall whole.
TEST(ShapeCells, ARectangleIsPlannedForItself) {
  const Wall wall = test::rectWall(2.0, 1.0);
  const ToolParams pad = shape(ToolShape::Rectangle, 0.2, 0.2);
  for (const std::string name : {"boustrophedon", "trapezoidal"}) {
    SCOPED_TRACE(name);
    const JudgedPlan j = plan(name, wall, pad, gantry());
    ASSERT_EQ(j.verdict, RunStatus::Ok) << j.reason;
    EXPECT_TRUE(j.result.planned_for_shape);
    EXPECT_TRUE(test::isValidPath(wall, pad, j.result.path, gantry()));
    EXPECT_GT(j.metrics.coverage.coverage_reachable, 0.99998);
    for (const auto& [a, b] : painted(j.result.path)) {
      EXPECT_NEAR(std::min(a.x, b.x), 0.1, 3e-6);
      EXPECT_NEAR(std::max(a.x, b.x), 1.9, 3e-6);
    }
    // On a holonomic robot it turns on the wall at each row end, as zigzag's rows do there.
    const JudgedPlan turning = plan(name, wall, pad, VehicleModel{});
    const JudgedPlan rows = plan("zigzag", wall, pad, VehicleModel{});
    ASSERT_TRUE(turning.result.hasPath()) << turning.reason;
    EXPECT_TRUE(turning.result.planned_for_shape);
    EXPECT_TRUE(test::isValidPath(wall, pad, turning.result.path, VehicleModel{}));
    EXPECT_LT(turning.metrics.coverage.coverage_reachable, j.metrics.coverage.coverage_reachable);
    EXPECT_NEAR(turning.metrics.coverage.coverage_reachable, rows.metrics.coverage.coverage_reachable, 2e-3);
  }
}

// Random walls (polygons, overlapping obstacles touching the edge), lines and rectangles, several
// sweep angles, with and without clearance: every path valid in both engines, every piece in a
// cell, the coverage of zigzag's rows of the shape; on a holonomic robot, which turns the shape at
// each row end, valid too and never above the gantry's.
TEST(ShapeCellsProperty, ValidInBothEnginesOnRandomWalls) {
  for (const std::string name : {"boustrophedon", "trapezoidal"}) {
    SCOPED_TRACE(name);
    std::vector<double> coverage;
    for (unsigned seed = 1; seed <= 12; ++seed) {
      const Wall wall = test::randomWall(seed);
      const double width = 0.1 + 0.05 * (seed % 4), clearance = seed % 3 == 0 ? 0.0 : 0.02;
      const ToolParams tool = seed % 2 == 0 ? shape(ToolShape::Rectangle, width, 0.5 * width, clearance)
                                            : shape(ToolShape::Line, width, 0.0, clearance);
      const std::vector<std::pair<std::string, std::string>> angle{{"sweep_angle", std::to_string(15 * (seed % 5))}};
      const JudgedPlan j = plan(name, wall, tool, gantry(), angle);
      if (j.result.status == PlanStatus::NoReachableArea) continue;
      ASSERT_TRUE(j.result.hasPath()) << wall.name << ": " << j.reason;
      EXPECT_TRUE(j.result.planned_for_shape);
      EXPECT_EQ(j.result.stats.at("pieces_outside_cells"), 0.0) << wall.name;
      EXPECT_TRUE(test::isValidPath(wall, tool, j.result.path, gantry())) << wall.name;
      coverage.push_back(j.metrics.coverage.coverage_reachable);
      // zigzag's rows and loops (the loops' chords aside): what they paint, in another order.
      const JudgedPlan rows = plan("zigzag", wall, tool, gantry(), angle);
      EXPECT_NEAR(coverage.back(), rows.metrics.coverage.coverage_reachable, 2e-3) << wall.name;
      EXPECT_EQ(j.result.stats.at("loops_first"), rows.result.stats.at("loops_first")) << wall.name;
      // On a holonomic robot (rows ending where the shape can turn): valid in both engines too.
      const JudgedPlan turning = plan(name, wall, tool, VehicleModel{}, angle);
      if (turning.result.hasPath())
        EXPECT_TRUE(test::isValidPath(wall, tool, turning.result.path, VehicleModel{})) << wall.name;
      EXPECT_GT(coverage.back(), turning.metrics.coverage.coverage_reachable - 1e-3) << wall.name;
    }
    ASSERT_GE(coverage.size(), 9u);
  }
}

}  // namespace
}  // namespace coverbench
