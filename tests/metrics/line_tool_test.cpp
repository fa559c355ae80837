// The line and rectangle tools (docs/metrics.md#tool-shapes) in both engines: a straight pass and
// a right-angle turn against hand-computed areas and verdicts, and random paths on random walls
// where the fast engine and the exact judge must agree.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coverbench/judge.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/metrics.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::rectWall;

const double kPi = std::acos(-1.0);

// The rectangle [x0, x1] x [y0, y1] as a labelled obstacle.
Obstacle rect(double x0, double y0, double x1, double y1, const std::string& label) {
  Obstacle o = test::rect(x0, y0, x1 - x0, y1 - y0);
  o.label = label;
  return o;
}

Path polyline(std::vector<Point> points) {
  Path p;
  p.waypoints = std::move(points);
  p.tool_on.assign(p.waypoints.size() - 1, true);
  return p;
}

ToolParams line(double width, double clearance = 0.02) {
  ToolParams tool;
  tool.tool_width = width;
  tool.clearance = clearance;
  tool.shape = ToolShape::Line;
  return tool;
}

// A rectangle `width` across the heading and `depth` along it.
ToolParams rectangle(double width, double depth, double clearance = 0.02) {
  ToolParams tool = line(width, clearance);
  tool.shape = ToolShape::Rectangle;
  tool.depth = depth;
  return tool;
}

// Both engines' verdicts on one path, which must agree; the fast engine's is returned.
Validity bothVerdicts(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle = {}) {
  const Validity fast = checkValidity(wall, tool, path, vehicle);
  const judge::ExactValidity exact = judge::judgeValidity(wall, tool, path, vehicle);
  EXPECT_EQ(fast.valid, exact.valid);
  EXPECT_EQ(fast.outside_boundary, exact.outside_boundary);
  EXPECT_EQ(fast.too_close, exact.too_close);
  return fast;
}

// The swept area by both engines against the hand value: the judge's certified interval holds it,
// and the fast engine (sectors as chords within 1 um, corners on Clipper's 1 um grid) is within 5e-6 m^2.
void expectSwept(const Wall& wall, const ToolParams& tool, const Path& path, double hand) {
  const PathMetrics fast = computeMetrics(wall, tool, path);
  EXPECT_NEAR(fast.coverage.swept_area, hand, 5e-6);
  EXPECT_NEAR(fast.passes.swept_area, hand, 5e-6);
  const judge::ExactCoverage exact = judge::judgeCoverage(wall, tool, path);
  EXPECT_TRUE(exact.swept_area.contains(hand)) << exact.swept_area.lower << " " << exact.swept_area.upper;
  EXPECT_LT(exact.swept_area.width(), 1e-4);
}

// A 2 x 1 m wall, a line 0.2 m long (h = 0.1 m), c = 0.02 m.
TEST(LineTool, AStraightPassSweepsItsRectangleInBothEngines) {
  const Wall wall = rectWall(2.0, 1.0);
  const Path pass = polyline({{0.5, 0.5}, {1.5, 0.5}});
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), pass).valid);
  expectSwept(wall, line(0.2), pass, 0.2 * 1.0);
  // R is the whole wall (no obstacles), so a tenth of it is covered.
  const PathMetrics m = computeMetrics(wall, line(0.2), pass);
  EXPECT_NEAR(m.coverage.reachable_area, 2.0, 1e-9);
  EXPECT_NEAR(m.coverage.coverage_reachable, 0.1, 1e-8);
  EXPECT_EQ(m.passes.overlap, 0.0);
  // A disk of the same width sweeps its round ends too.
  ToolParams disk = line(0.2);
  disk.shape = ToolShape::Disk;
  EXPECT_NEAR(computeMetrics(wall, disk, pass).coverage.swept_area, 0.2 + kPi * 0.01, 1e-9);
}

TEST(LineTool, APassRightUpToTheWallsEdgeIsValidForALineAndNotForADisk) {
  const Wall wall = rectWall(2.0, 1.0);
  const Path to_edge = polyline({{0.5, 0.5}, {2.0, 0.5}});
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), to_edge).valid);  // the line lies on the edge at the end
  expectSwept(wall, line(0.2), to_edge, 0.2 * 1.5);
  ToolParams disk = line(0.2);
  disk.shape = ToolShape::Disk;
  EXPECT_FALSE(checkValidity(wall, disk, to_edge).valid);
  // Along the bottom edge: the line's end runs on it (valid); 0.1 mm lower it leaves the wall.
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), polyline({{0.5, 0.1}, {1.5, 0.1}})).valid);
  const Validity low = bothVerdicts(wall, line(0.2), polyline({{0.5, 0.0999}, {1.5, 0.0999}}));
  EXPECT_EQ(low.outside_boundary, 1u);
  EXPECT_NE(describeViolations(low, 0.02).find("crosses the wall's edge"), std::string::npos) << describeViolations(low, 0.02);
}

// East 1 m, then north 0.5 m: the line turns a quarter circle about (1.5, 0.3). Of the two
// quarter disks it sweeps (radius 0.1), the one inside the corner lies in both rectangles, the
// one outside it is new: |S| = 0.2 + 0.1 - 0.1^2 + pi 0.1^2 / 4.
TEST(LineTool, ARightAngleTurnSweepsTwoQuarterDisksOneOfThemNew) {
  const Wall wall = rectWall(2.0, 1.0);
  const Path turn = polyline({{0.5, 0.3}, {1.5, 0.3}, {1.5, 0.8}});
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), turn).valid);
  const double quarter = kPi * 0.01 / 4.0;
  const double hand = 0.2 + 0.1 - 0.01 + quarter;
  expectSwept(wall, line(0.2), turn, hand);
  // Passes: the corner square [1.4, 1.5] x [0.3, 0.4] twice, the inner quarter disk in it three times.
  const Passes p = computeMetrics(wall, line(0.2), turn).passes;
  EXPECT_NEAR(p.overlap, 0.01 / hand, 2e-5);
  EXPECT_NEAR(p.histogram[1], (0.01 - quarter) / hand, 2e-5);
  EXPECT_NEAR(p.histogram[2], quarter / hand, 2e-5);
  EXPECT_EQ(p.histogram[3], 0.0);
}

// A 1 cm square 5 cm beyond both rectangles (farther than c) but 7.1 cm from the turn's centre:
// inside the outer quarter disk the turn sweeps. With the turn the path is invalid in both
// engines; a gantry that lifts the tool to turn it does not sweep it, and is valid.
TEST(LineTool, ATurnIntoAnObstacleIsInvalidWhereTheMovesAloneAreNot) {
  const Wall wall = rectWall(2.0, 1.0, {rect(1.55, 0.24, 1.56, 0.25, "socket")});
  const Path turn = polyline({{0.5, 0.3}, {1.5, 0.3}, {1.5, 0.8}});
  const Validity v = bothVerdicts(wall, line(0.2), turn);
  EXPECT_EQ(v.too_close, 1u);
  EXPECT_EQ(v.violating, std::vector<std::size_t>{1});  // the turn belongs to the move it starts
  EXPECT_NE(describeViolations(v, 0.02).find("overlaps obstacle \"socket\""), std::string::npos) << describeViolations(v, 0.02);
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), polyline({{0.5, 0.3}, {1.5, 0.3}})).valid);
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), polyline({{1.5, 0.3}, {1.5, 0.8}})).valid);
  Path lifted = turn;
  lifted.waypoints.insert(lifted.waypoints.begin() + 2, Point{1.5, 0.3});
  lifted.tool_on = {true, false, true};
  VehicleModel gantry;
  gantry.kind = VehicleModel::Kind::Gantry;
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), lifted, gantry).valid);
  // A holonomic tool drags the line round even with the tool off: still invalid.
  EXPECT_FALSE(bothVerdicts(wall, line(0.2), lifted).valid);
}

// A gantry lowers and lifts a line at the heading of the row it begins or ends: rows from edge
// to edge, joined by lifted moves along the edge, are valid in both engines (the line there lies
// on the edge, inside the wall's box), where the disk's lifted rule (the disk at both ends inside
// the box) would refuse them. A line lowered across the box's edge is refused.
TEST(LineTool, AGantryLowersTheLineAtItsRowsHeading) {
  const Wall wall = rectWall(2.0, 1.0);
  VehicleModel gantry;
  gantry.kind = VehicleModel::Kind::Gantry;
  Path rows = polyline({{0.0, 0.1}, {2.0, 0.1}, {2.0, 0.3}, {0.0, 0.3}});
  rows.tool_on = {true, false, true};
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), rows, gantry).valid);
  // Lowered at (1, 0.05) to paint north, it lies along y = 0.05 (inside); to paint east, across it.
  Path north = polyline({{0.5, 0.5}, {1.0, 0.05}, {1.0, 0.5}});
  north.tool_on = {false, true};
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), north, gantry).valid);
  Path east = polyline({{0.5, 0.5}, {1.0, 0.05}, {1.5, 0.05}});
  east.tool_on = {false, true};
  const Validity v = bothVerdicts(wall, line(0.2), east, gantry);
  EXPECT_EQ(v.violating, (std::vector<std::size_t>{0, 1}));  // the lifted move lowers it outside, the row leaves the wall
  // A rectangle's corners count: 0.1 deep, lowered at (1, 0.05) to paint north, it reaches y = 0.
  EXPECT_TRUE(bothVerdicts(wall, rectangle(0.2, 0.1), north, gantry).valid);
  Path low = polyline({{0.5, 0.5}, {1.0, 0.04}, {1.0, 0.5}});
  low.tool_on = {false, true};
  EXPECT_EQ(bothVerdicts(wall, rectangle(0.2, 0.1), low, gantry).violating, (std::vector<std::size_t>{0, 1}));
}

// Straight back is no turn for a line (it is the same line turned half a circle): an obstacle
// beside the end, inside the disk a turn would sweep, is not touched, and the pass is doubled.
TEST(LineTool, GoingStraightBackDoesNotTurnTheLine) {
  const Wall wall = rectWall(2.0, 1.0, {rect(1.55, 0.55, 1.6, 0.6, "socket")});
  const Path back = polyline({{0.5, 0.5}, {1.5, 0.5}, {0.5, 0.5}});
  EXPECT_TRUE(bothVerdicts(wall, line(0.2), back).valid);
  const PathMetrics m = computeMetrics(wall, line(0.2), back);
  EXPECT_NEAR(m.coverage.swept_area, 0.2, 1e-9);
  EXPECT_NEAR(m.passes.overlap, 1.0, 1e-9);
}

// The obstacle wholly inside the rectangle a pass sweeps, touching none of its edges.
TEST(LineTool, AnObstacleWhollyInsideTheSweptRectangleIsFound) {
  const Wall wall = rectWall(2.0, 1.0, {rect(1.0, 0.45, 1.01, 0.46, "nail")});
  const Validity v = bothVerdicts(wall, line(0.4, 0.0), polyline({{0.5, 0.5}, {1.5, 0.5}}));
  EXPECT_EQ(v.too_close, 1u);
}

// R for a line tool is the wall minus its obstacles grown by c: a window 0.4 x 0.4 with c = 0.02
// takes away (0.44 x 0.44 with its corners rounded by c).
TEST(LineTool, ItsReachableRegionIsTheWallMinusTheObstaclesGrownByTheClearance) {
  const Wall wall = rectWall(2.0, 1.0, {rect(0.8, 0.3, 1.2, 0.7, "window")});
  const double grown = 0.4 * 0.4 + 4 * 0.4 * 0.02 + kPi * 0.02 * 0.02;
  const PathMetrics m = computeMetrics(wall, line(0.2), polyline({{0.2, 0.15}, {1.8, 0.15}}));
  EXPECT_NEAR(m.coverage.reachable_area, 2.0 - grown, 2e-6);
  const judge::ExactCoverage exact = judge::judgeCoverage(wall, line(0.2), polyline({{0.2, 0.15}, {1.8, 0.15}}));
  EXPECT_TRUE(exact.reachable_area.contains(2.0 - grown));
}

// A rectangle 0.25 x 0.125 m (h = 2e: every number a dyadic fraction, so "touching" is exact in
// the judge). A pass sweeps its rectangle d longer than the move; ending d / 2 short of the edge
// it touches it (valid), ending on it it crosses it (invalid), where a line is valid.
TEST(RectangleTool, AStraightPassSweepsARectangleDLongerThanTheMove) {
  const Wall wall = rectWall(2.0, 1.0);
  const ToolParams tool = rectangle(0.25, 0.125);
  const Path pass = polyline({{0.9375, 0.5}, {1.9375, 0.5}});
  EXPECT_TRUE(bothVerdicts(wall, tool, pass).valid);
  expectSwept(wall, tool, pass, 0.25 * 1.125);
  // At a length whose e / L is no double the judge still reads the touch exactly (along an axis
  // its scales are exact rationals).
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{0.5, 0.5}, {1.9375, 0.5}})).valid);
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{0.5, 0.875}, {1.5, 0.875}})).valid);  // the side on the top edge
  const Path to_edge = polyline({{0.9375, 0.5}, {2.0, 0.5}});
  const Validity v = bothVerdicts(wall, tool, to_edge);
  EXPECT_EQ(v.outside_boundary, 1u);
  EXPECT_NE(describeViolations(v, 0.02).find("crosses the wall's edge"), std::string::npos) << describeViolations(v, 0.02);
  EXPECT_TRUE(bothVerdicts(wall, line(0.25), to_edge).valid);
  // Along the bottom edge its long side runs on it (valid); 1 mm lower it leaves the wall.
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{0.5, 0.125}, {1.5, 0.125}})).valid);
  EXPECT_EQ(bothVerdicts(wall, tool, polyline({{0.5, 0.124}, {1.5, 0.124}})).outside_boundary, 1u);
}

// East L1 = 1 m, then north L2 = 0.5 m about p = (1.5, 0.3), h = 0.1, e = 0.05, R = hypot(h, e).
// The moves sweep A (L1 + 2e by 2h) and B (2h by L2 + 2e), overlapping in (h + e)^2 at p. The
// turn's four corner sectors (radius R, a quarter turn each) add, relative to p: the circular
// segments beyond y = -h and beyond x = h (each R^2 a - h e, a = atan(e / h)), and the part of
// [e, h] x [-h, -e] within R (the sector between (e, -h) and (h, -e), R^2 (pi / 2 - 2a) / 2,
// less the quadrilateral p, (e, -h), (e, -e), (h, -e) of area e (h - e)).
TEST(RectangleTool, ARightAngleTurnSweepsFourCornerSectors) {
  const Wall wall = rectWall(2.0, 1.0);
  const ToolParams tool = rectangle(0.2, 0.1);
  const Path turn = polyline({{0.5, 0.3}, {1.5, 0.3}, {1.5, 0.8}});
  EXPECT_TRUE(bothVerdicts(wall, tool, turn).valid);
  const double h = 0.1, e = 0.05, r2 = h * h + e * e, a = std::atan(e / h);
  const double moves = 2 * h * (1.0 + 2 * e) + 2 * h * (0.5 + 2 * e) - (h + e) * (h + e);
  const double corners = 2 * (r2 * a - h * e) + r2 * (kPi / 2 - 2 * a) / 2 - e * (h - e);
  expectSwept(wall, tool, turn, moves + corners);
  EXPECT_NEAR(moves + corners, 0.3206131, 1e-7);  // the same, in numbers
  // Straight back is no turn for a rectangle either (it is the same turned half a circle).
  const Path back = polyline({{0.5, 0.5}, {1.5, 0.5}, {0.5, 0.5}});
  expectSwept(wall, tool, back, 2 * h * (1.0 + 2 * e));
}

// A 5 mm square 2.5 cm beyond both moves' rectangles (farther than c = 2 cm) but 10.6 cm from
// the turn's centre, within the corners' reach R = 11.18 cm: the turn makes the path invalid in
// both engines, each move alone is valid, and a gantry that turns the tool lifted is valid.
TEST(RectangleTool, ATurnsCornerSectorIntoAnObstacleIsInvalid) {
  const Wall wall = rectWall(2.0, 1.0, {rect(1.575, 0.22, 1.58, 0.225, "socket")});
  const ToolParams tool = rectangle(0.2, 0.1);
  const Path turn = polyline({{0.5, 0.3}, {1.5, 0.3}, {1.5, 0.8}});
  const Validity v = bothVerdicts(wall, tool, turn);
  EXPECT_EQ(v.too_close, 1u);
  EXPECT_EQ(v.violating, std::vector<std::size_t>{1});
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{0.5, 0.3}, {1.5, 0.3}})).valid);
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{1.5, 0.3}, {1.5, 0.8}})).valid);
  Path lifted = turn;
  lifted.waypoints.insert(lifted.waypoints.begin() + 2, Point{1.5, 0.3});
  lifted.tool_on = {true, false, true};
  VehicleModel gantry;
  gantry.kind = VehicleModel::Kind::Gantry;
  EXPECT_TRUE(bothVerdicts(wall, tool, lifted, gantry).valid);
}

// A path that never moves has no heading: the rectangle must fit in every one, the disk of
// radius R = hypot(h, e) = 0.1118 m, as the disk tool's must fit its own.
TEST(RectangleTool, APathThatNeverMovesMustFitItsCircumscribedDisk) {
  const Wall wall = rectWall(2.0, 1.0);
  const ToolParams tool = rectangle(0.2, 0.1);
  EXPECT_FALSE(bothVerdicts(wall, tool, polyline({{0.5, 0.105}, {0.5, 0.105}})).valid);
  EXPECT_TRUE(bothVerdicts(wall, tool, polyline({{0.5, 0.115}, {0.5, 0.115}})).valid);
}

// A rectangle's depth is checked where every tool is, and only a rectangle has one.
TEST(RectangleTool, ItsDepthIsCheckedAndBelongsToARectangleOnly) {
  ToolParams tool = rectangle(0.2, 0.0);
  try {
    validateTool(tool, "here");
    ADD_FAILURE() << "a rectangle without a depth was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "here: tool_depth: is missing: a rectangle tool's depth along the heading, m");
  }
  tool.depth = -0.1;
  try {
    validateTool(tool, "here");
    ADD_FAILURE() << "a negative depth was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "here: tool_depth: a rectangle's depth must be in [0.001, 10] m, got -0.1");
  }
  tool = line(0.2);
  tool.depth = 0.1;
  EXPECT_THROW(validateTool(tool, "here"), InputError);
  EXPECT_NEAR(rectangle(0.2, 0.1).reachRadius(), std::sqrt(0.0125), 1e-15);
  EXPECT_EQ(circumscribedDisk(rectangle(0.3, 0.4)).tool_width, 0.5);
  EXPECT_EQ(toolLabel(rectangle(0.23, 0.05)), "rectangle s=0.23 m, d=0.05 m, c=0.02 m");
}

// Random polylines on random walls: both engines' verdicts agree, and on the valid ones the fast
// engine's swept area and coverage lie within 1e-5 (relative) of the judge's intervals.
TEST(LineToolProperty, BothEnginesAgreeOnRandomPathsOnRandomWalls) {
  std::mt19937 rng(11);
  int compared = 0, invalid = 0, areas = 0;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    const Wall wall = test::randomWall(seed);
    // Every other wall a rectangle, its depth from a tenth to the whole of its width.
    const double width = 0.1 + 0.05 * (seed % 4), clearance = seed % 3 == 0 ? 0.0 : 0.02;
    const ToolParams tool = seed % 2 == 0 ? rectangle(width, width * (0.1 + 0.3 * (seed % 4)), clearance) : line(width, clearance);
    Box box;
    for (Point p : wall.boundary) box.add(p);
    std::uniform_real_distribution<double> x(box.min_x, box.max_x), y(box.min_y, box.max_y);
    for (int k = 0; k < 12; ++k) {
      std::vector<Point> points;
      for (int j = 0; j < 2 + k % 4; ++j) points.push_back({x(rng), y(rng)});
      // Some short moves, so that many paths fit.
      for (std::size_t j = 1; j < points.size(); ++j) points[j] = points[j - 1] + (points[j] - points[j - 1]) * 0.15;
      const Path path = polyline(points);
      const Validity f = checkValidity(wall, tool, path);
      const judge::ExactValidity e = judge::judgeValidity(wall, tool, path);
      ASSERT_EQ(e.outside_boundary, f.outside_boundary) << wall.name << " path " << k;
      ASSERT_EQ(e.too_close, f.too_close) << wall.name << " path " << k;
      ++compared;
      invalid += !e.valid;
      if (!e.valid || k % 3 != 0) continue;
      const PathMetrics m = computeMetrics(wall, tool, path);
      const judge::ExactCoverage c = judge::judgeCoverage(wall, tool, path, {32});
      EXPECT_LE(c.swept_area.distanceTo(m.coverage.swept_area), 1e-5 * c.swept_area.upper) << wall.name << " path " << k;
      EXPECT_LE(c.coverage_reachable.distanceTo(m.coverage.coverage_reachable), 1e-4) << wall.name << " path " << k;
      ++areas;
    }
  }
  EXPECT_EQ(compared, 24 * 12);
  EXPECT_GT(invalid, 40);  // the sample exercises both verdicts
  EXPECT_LT(invalid, compared - 40);
  EXPECT_GT(areas, 10);
}

}  // namespace
}  // namespace coverbench
