// The row planners for a line or rectangle tool (docs/metrics.md#tool-shapes). First zigzag on a
// gantry: the line's own rows from edge to edge, joined by lifted moves, not its circumscribed
// disk's. Valid in both engines (the lifted moves lower the line at its row's heading, inside the
// wall's box), covering what the disk's rows leave at the edges and beside obstacles, and saying
// nothing of a disk. Then a holonomic robot, which turns the shape on the wall, and boustrophedon
// and trapezoidal, which paint zigzag's rows cell by cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

ToolParams line(double width, double clearance = 0.02) { return shape(ToolShape::Line, width, 0.0, clearance); }

VehicleModel gantry() {
  VehicleModel v;
  v.kind = VehicleModel::Kind::Gantry;
  return v;
}

/// `planner`'s plan for `tool` under `vehicle`, judged as a run is (planAndJudge).
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

JudgedPlan zigzag(const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle,
                  const std::vector<std::pair<std::string, std::string>>& settings = {}) {
  return plan("zigzag", wall, tool, vehicle, settings);
}

/// The tool-on segments of a path, in order.
std::vector<std::pair<Point, Point>> painted(const Path& path) {
  std::vector<std::pair<Point, Point>> out;
  for (std::size_t i = 0; i < path.segments(); ++i)
    if (path.tool_on[i]) out.push_back({path.waypoints[i], path.waypoints[i + 1]});
  return out;
}

// A bare 2 x 1 m wall, s = 0.2 m, no loops: five rows at y = 0.1 .. 0.9, each from edge to edge
// (2 um margins), the rest lifted; all of R covered but the margins' slivers.
TEST(LineRows, OnABareWallTheRowsRunFromEdgeToEdge) {
  const Wall wall = test::rectWall(2.0, 1.0);
  const JudgedPlan j = zigzag(wall, line(0.2), gantry(), {{"boundary_passes", "0"}});
  ASSERT_EQ(j.verdict, RunStatus::Ok) << j.reason;
  EXPECT_TRUE(j.result.planned_for_shape);
  EXPECT_EQ(j.reason.find("circumscribed"), std::string::npos) << j.reason;
  EXPECT_EQ(j.result.stats.at("rows"), 5.0);
  EXPECT_TRUE(test::isValidPath(wall, line(0.2), j.result.path, gantry()));
  std::vector<double> heights;
  for (std::size_t i = 0; i < j.result.path.segments(); ++i) {
    const Point a = j.result.path.waypoints[i], b = j.result.path.waypoints[i + 1];
    if (!j.result.path.tool_on[i]) continue;
    EXPECT_EQ(a.y, b.y);  // rows along the x axis
    EXPECT_NEAR(std::min(a.x, b.x), 0.0, 3e-6);
    EXPECT_NEAR(std::max(a.x, b.x), 2.0, 3e-6);
    heights.push_back(a.y);
  }
  std::sort(heights.begin(), heights.end());
  ASSERT_EQ(heights.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(heights[k], 0.1 + 0.2 * static_cast<double>(k), 4e-6);
  EXPECT_GT(j.metrics.coverage.coverage_reachable, 0.99998);
  EXPECT_LT(j.metrics.passes.overlap, 1e-4);  // rows 0.19999 m apart: 1 um strips twice
  // On a holonomic robot the line turns on the wall at each row end, so its rows end where its
  // disk fits (h from the ends) and the wall's corners are left: less than on a gantry.
  const JudgedPlan turning = zigzag(wall, line(0.2), VehicleModel{});
  ASSERT_EQ(turning.verdict, RunStatus::Ok) << turning.reason;
  EXPECT_TRUE(turning.result.planned_for_shape);
  EXPECT_EQ(turning.reason.find("circumscribed"), std::string::npos) << turning.reason;
  EXPECT_TRUE(test::isValidPath(wall, line(0.2), turning.result.path, VehicleModel{}));
  EXPECT_LT(turning.metrics.coverage.coverage_reachable, j.metrics.coverage.coverage_reachable);
  EXPECT_GT(turning.metrics.coverage.coverage_reachable, 0.99);  // the corners: (4 - pi) h^2 of 2 m^2
}

// A window and a round socket: the rows stop c from each, and rows of their own take the bands
// the regular rows leave above and below them. Both engines find it valid; it covers more of R
// than the disk's rows with a fifth of their paint twice. The rows leave under 1 % of R (the
// window's round corners), so no loops are run first (loops_first 0).
TEST(LineRows, RowsOfTheirOwnCoverTheBandsBesideObstacles) {
  const Wall wall = test::rectWall(2.0, 1.0, {test::rect(0.8, 0.3, 0.3, 0.3), test::circle(1.6, 0.5, 0.1)});
  const JudgedPlan rows = zigzag(wall, line(0.2), gantry());
  ASSERT_EQ(rows.verdict, RunStatus::Ok) << rows.reason;
  EXPECT_TRUE(test::isValidPath(wall, line(0.2), rows.result.path, gantry()));
  EXPECT_GT(rows.result.stats.at("leftover_rows"), 0.0);
  EXPECT_EQ(rows.result.stats.at("loops_first"), 0.0);
  EXPECT_LT(rows.result.stats.at("rows_left_share"), 0.01);
  const JudgedPlan holonomic = zigzag(wall, line(0.2), VehicleModel{});
  EXPECT_LT(holonomic.metrics.coverage.coverage_reachable, rows.metrics.coverage.coverage_reachable);
  EXPECT_LT(rows.metrics.passes.overlap, holonomic.metrics.passes.overlap / 4.0);
  // At a sweep angle the rows turn with it, and stay valid.
  const JudgedPlan turned = zigzag(wall, line(0.2), gantry(), {{"sweep_angle", "30"}});
  ASSERT_EQ(turned.verdict, RunStatus::Ok) << turned.reason;
  EXPECT_TRUE(test::isValidPath(wall, line(0.2), turned.result.path, gantry()));
}

// A rectangle on a gantry is planned for itself too: its rows end d / 2 from the edges and cover
// the bare wall whole, where its circumscribed disk's rows leave a quarter of a square pad's R.
TEST(LineRows, ARectangleOnAGantryIsPlannedForItself) {
  const Wall wall = test::rectWall(2.0, 1.0);
  ToolParams pad = line(0.2);
  pad.shape = ToolShape::Rectangle;
  pad.depth = 0.2;
  const JudgedPlan j = zigzag(wall, pad, gantry());
  ASSERT_EQ(j.verdict, RunStatus::Ok) << j.reason;
  EXPECT_TRUE(j.result.planned_for_shape);
  EXPECT_EQ(j.reason.find("circumscribed"), std::string::npos) << j.reason;
  EXPECT_TRUE(test::isValidPath(wall, pad, j.result.path, gantry()));
  EXPECT_GT(j.metrics.coverage.coverage_reachable, 0.99998);
  EXPECT_LT(j.metrics.passes.overlap, 1e-4);
  for (std::size_t i = 0; i < j.result.path.segments(); ++i)
    if (j.result.path.tool_on[i]) {
      EXPECT_NEAR(std::min(j.result.path.waypoints[i].x, j.result.path.waypoints[i + 1].x), 0.1, 3e-6);
      EXPECT_NEAR(std::max(j.result.path.waypoints[i].x, j.result.path.waypoints[i + 1].x), 1.9, 3e-6);
    }
}

// A square pad on a holonomic robot turns on the wall at each row end: a 90 deg turn sweeps the
// whole disk of radius R = 0.1 sqrt(2) m, so every row ends where that disk fits (R from the
// edges), and rows 0.1 m from the top and bottom edges cannot end anywhere. Loops along R's edge
// paint the band from R - h to R + h; the rows, 0.2 m apart, paint the rest: only a strip R - h =
// 0.041 m wide along the edges is left (the corners' turns paint a little of it). Planned for the
// pad itself, not its 0.283 m disk, whose rows would lie 0.283 m apart.
TEST(LineRows, ARectangleOnAHolonomicRobotTurnsWhereItsDiskFits) {
  const Wall wall = test::rectWall(2.0, 1.0);
  ToolParams pad = line(0.2);
  pad.shape = ToolShape::Rectangle;
  pad.depth = 0.2;
  const double r = 0.1 * std::sqrt(2.0);
  const JudgedPlan j = zigzag(wall, pad, VehicleModel{});
  ASSERT_TRUE(j.result.hasPath()) << j.reason;
  EXPECT_TRUE(j.result.planned_for_shape);
  EXPECT_EQ(j.reason.find("circumscribed"), std::string::npos) << j.reason;
  EXPECT_TRUE(test::isValidPath(wall, pad, j.result.path, VehicleModel{}));
  EXPECT_EQ(j.result.stats.at("loops_first"), 1.0);
  for (Point p : j.result.path.waypoints) {  // every turn where the disk of radius R fits
    EXPECT_GE(std::min(p.x, 2.0 - p.x), r) << p.x << ", " << p.y;
    EXPECT_GE(std::min(p.y, 1.0 - p.y), r) << p.x << ", " << p.y;
  }
  // Left: at most the strip R - h along the edges, 2 (2 + 1) (R - h) = 0.249 m^2 of 2 m^2.
  const double strip = 2.0 * 3.0 * (r - 0.1) / 2.0;
  EXPECT_GT(j.metrics.coverage.coverage_reachable, 1.0 - strip - 1e-3);
  EXPECT_LT(j.metrics.coverage.coverage_reachable, 1.0 - strip / 2.0);
  // The strip is over 5 % of R: the run is partial and says why.
  EXPECT_EQ(j.result.status, PlanStatus::Partial);
  EXPECT_NE(j.reason.find("where it cannot turn at a row end"), std::string::npos) << j.reason;
}

// Random walls (polygons, overlapping obstacles touching the edge), widths 0.1 to 0.25 m, with and
// without clearance: every path is valid in both engines and covers nearly all of R.
TEST(LineRowsProperty, ValidInBothEnginesOnRandomWalls) {
  std::vector<double> coverage;
  int loops = 0;  // walls whose slanted or round edges the rows leave more than 1 % of R along
  for (unsigned seed = 1; seed <= 16; ++seed) {
    const Wall wall = test::randomWall(seed);
    const ToolParams tool = line(0.1 + 0.05 * (seed % 4), seed % 3 == 0 ? 0.0 : 0.02);
    const JudgedPlan j = zigzag(wall, tool, gantry(), {{"sweep_angle", std::to_string(15 * (seed % 5))}});
    if (j.result.status == PlanStatus::NoReachableArea) continue;
    ASSERT_TRUE(j.result.hasPath()) << wall.name << ": " << j.reason;
    EXPECT_TRUE(j.result.planned_for_shape);
    EXPECT_TRUE(test::isValidPath(wall, tool, j.result.path, gantry())) << wall.name;
    coverage.push_back(j.metrics.coverage.coverage_reachable);
    loops += j.result.stats.at("loops_first") > 0.0;
    // On a holonomic robot (rows ending where the line can turn): valid in both engines too. (Its
    // coverage is not bounded by the gantry's: its short joins between rows paint on the wall.)
    const JudgedPlan turning = zigzag(wall, tool, VehicleModel{}, {{"sweep_angle", std::to_string(15 * (seed % 5))}});
    if (turning.result.hasPath())
      EXPECT_TRUE(test::isValidPath(wall, tool, turning.result.path, VehicleModel{})) << wall.name;
  }
  ASSERT_GE(coverage.size(), 12u);
  EXPECT_GE(loops, 4);
  std::sort(coverage.begin(), coverage.end());
  EXPECT_GT(coverage[coverage.size() / 2], 0.99);
}

// boustrophedon and trapezoidal (shape_cells.hpp): the shape's own rows, zigzag's, painted cell
// by cell of the region where the shape may stand.

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
// each row end, valid too.
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
    }
    ASSERT_GE(coverage.size(), 9u);
  }
}

}  // namespace
}  // namespace coverbench
