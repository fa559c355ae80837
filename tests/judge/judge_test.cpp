// The exact judge (judge/): hand-computed areas, adversarial paths on the limits, and property
// tests of the fast metrics engine against it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coverbench/datasets.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using judge::Interval;
using test::circle;
using test::rect;
using test::rectWall;

Path pathOf(std::vector<Point> points, bool tool = true) {
  Path p;
  p.waypoints = std::move(points);
  p.tool_on.assign(p.waypoints.size() > 0 ? p.waypoints.size() - 1 : 0, tool);
  return p;
}

const double kPi = std::acos(-1.0);
// Areas of the regular n-gons inscribed in and circumscribed about a circle of radius rho.
double inscribed(double rho, int n) { return n / 2.0 * rho * rho * std::sin(2 * kPi / n); }
double circumscribed(double rho, int n) { return n * rho * rho * std::tan(kPi / n); }

// ---- depot legs (path.hpp: depot legs) ------------------------------------------------------

// Both judges' verdicts, which must agree: valid, the depot legs each accepted and their length.
struct Verdicts {
  bool valid;
  std::size_t legs;
  double length;
};
Verdicts judged(const Wall& wall, const ToolParams& tool, const Path& path) {
  SCOPED_TRACE(wall.name + " from (" + std::to_string(path.waypoints[0].x) + ", " + std::to_string(path.waypoints[0].y) + ")");
  const Validity fast = checkValidity(wall, tool, path);
  const judge::ExactValidity exact = judge::judgeValidity(wall, tool, path);
  EXPECT_EQ(fast.valid, exact.valid);
  EXPECT_EQ(fast.violations, exact.violations);
  EXPECT_EQ(fast.depot_legs, exact.depot_legs);
  EXPECT_NEAR(fast.depot_length, exact.depot_length, 1e-12);
  return {exact.valid, exact.depot_legs, exact.depot_length};
}
Path toolPath(std::vector<Point> points, std::vector<bool> on) {
  Path p = pathOf(std::move(points));
  p.tool_on = std::move(on);
  return p;
}

// On a 2 m x 1 m wall (s = 0.1 m, c = 0.02 m: F is 0.05 m inside its edge and 0.07 m clear of
// obstacles) a start on the left edge at (0, 0.5) lies 0.05 m outside F.
TEST(DepotLegs, BothJudgesAcceptTheToolOffMovesFromAStartOutsideFAndNothingMore) {
  const ToolParams tool{0.1, 0.02};
  Wall wall = rectWall(2, 1);
  wall.start = Point{0.0, 0.5};
  wall.end = Point{2.0, 0.5};
  // From the start into F, paint, and out to the end: two legs of 0.06 m.
  const Path both = toolPath({{0.0, 0.5}, {0.06, 0.5}, {1.94, 0.5}, {2.0, 0.5}}, {false, true, false});
  Verdicts v = judged(wall, tool, both);
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.legs, 2u);
  EXPECT_NEAR(v.length, 0.12, 1e-12);
  // The fast engine's gaps leave the legs out: the tool then keeps 0.01 m from the edge.
  EXPECT_NEAR(checkValidity(wall, tool, both).min_boundary_gap, 0.01, 1e-12);
  // The leg painting: checked as any segment, and its disk leaves the wall.
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.06, 0.5}, {1.0, 0.5}}, {true, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // A leg of any length: 0.3 m to (0.3, 0.5), and 0.06 m from the end to (1.94, 0.5).
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.3, 0.5}, {1.94, 0.5}, {2.0, 0.5}}, {false, true, false}));
  EXPECT_TRUE(v.valid);
  EXPECT_NEAR(v.length, 0.36, 1e-12);
  // A path that does not begin at the start, or a wall without one: no leg.
  v = judged(wall, tool, toolPath({{0.0, 0.4}, {0.06, 0.4}, {1.0, 0.4}}, {false, true}));
  EXPECT_FALSE(v.valid);
  Wall no_start = wall;
  no_start.start.reset();
  v = judged(no_start, tool, toolPath({{0.0, 0.5}, {0.06, 0.5}, {1.0, 0.5}}, {false, true}));
  EXPECT_FALSE(v.valid);
  // A start inside F gets no leg: its first segment out of F is invalid.
  Wall inside = wall;
  inside.start = Point{0.5, 0.5};
  v = judged(inside, tool, toolPath({{0.5, 0.5}, {0.03, 0.5}, {0.5, 0.5}}, {false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // Tool-off moves that never reach a waypoint in F are no leg: all outside F, all invalid.
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.02, 0.5}, {0.02, 0.02}, {1.0, 0.02}}, {false, false, false}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // A leg that paints on its way to F (its second segment): no leg; the first three segments
  // (out of F) fail.
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.02, 0.5}, {0.02, 0.2}, {0.3, 0.2}, {1.0, 0.2}}, {false, true, false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  EXPECT_EQ(checkValidity(wall, tool, toolPath({{0.0, 0.5}, {0.02, 0.5}, {0.02, 0.2}, {0.3, 0.2}, {1.0, 0.2}},
                                                {false, true, false, true})).violations, 3u);
}

// A start at the corner (0, 0), reached along the bottom edge from a dock at (1, 0): the leg runs
// on the wall's edge to the corner, then 0.06 sqrt(2) m into F at (0.06, 0.06).
TEST(DepotLegs, ALegAlongTheEdgeToACornerIsAcceptedOneLeavingTheWallIsNot) {
  const ToolParams tool{0.1, 0.02};
  Wall wall = rectWall(2, 1);
  wall.start = Point{1.0, 0.0};
  Verdicts v = judged(wall, tool, toolPath({{1.0, 0.0}, {0.0, 0.0}, {0.06, 0.06}, {1.9, 0.06}}, {false, false, true}));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.legs, 1u);
  EXPECT_NEAR(v.length, 1.0 + 0.06 * std::sqrt(2.0), 1e-12);
  // The same dock, a leg 1 cm below the wall's edge: both of its first segments fail.
  v = judged(wall, tool, toolPath({{1.0, 0.0}, {0.5, -0.01}, {0.06, 0.06}, {1.9, 0.06}}, {false, false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // A U-shaped wall (a notch 1 m wide from y = 0.5 to the top at y = 2): from the tip of the
  // left arm at (1, 2) straight to the tip of the right arm at (2, 2), across the notch (out of
  // the wall, though both ends are on its edge and it crosses no edge), then down into F.
  Wall u;
  u.name = "u";
  u.boundary = {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 0.5}, {1, 0.5}, {1, 2}, {0, 2}};
  u.start = Point{1.0, 2.0};
  v = judged(u, tool, toolPath({{1.0, 2.0}, {2.0, 2.0}, {2.5, 1.5}, {2.5, 0.5}}, {false, false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // Down the arm's inner edge to its foot (1, 0.5), then into F at (1.5, 0.3): accepted.
  v = judged(u, tool, toolPath({{1.0, 2.0}, {1.0, 0.5}, {1.5, 0.3}, {2.5, 0.3}}, {false, false, true}));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.legs, 1u);
  EXPECT_NEAR(v.length, 1.5 + std::hypot(0.5, 0.2), 1e-12);
}

// A window from x = 0.02 to 0.3, y = 0.3 to 0.7, 2 cm from the left edge: a dock at (0, 0.5)
// sits in the slot between them. Its leg runs down the slot to (0.01, 0.29), below the window's
// corner, then to (0.1, 0.2) in F (0.1 m from the window and the edges).
TEST(DepotLegs, ALegRoutedAroundAnObstacleIsAcceptedOneThroughItIsNot) {
  const ToolParams tool{0.1, 0.02};
  Wall wall = rectWall(2, 1, {rect(0.02, 0.3, 0.28, 0.4)});
  wall.start = Point{0.0, 0.5};
  Verdicts v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.01, 0.29}, {0.1, 0.2}, {1.5, 0.2}}, {false, false, true}));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.legs, 1u);
  EXPECT_NEAR(v.length, std::hypot(0.01, 0.21) + std::hypot(0.09, 0.09), 1e-12);
  // Straight through the window to (0.4, 0.5): no leg, and the move fails.
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.4, 0.5}, {1.5, 0.5}}, {false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // Along the window's bottom edge on the way: no leg (not even touching it).
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {0.01, 0.3}, {0.1, 0.3}, {0.1, 0.2}, {1.5, 0.2}}, {false, false, false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // A lying plan: the same good leg, with one segment out of the wall hidden in it.
  v = judged(wall, tool, toolPath({{0.0, 0.5}, {-0.01, 0.29}, {0.1, 0.2}, {1.5, 0.2}}, {false, false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
  // A round obstacle of radius 0.1 m at (0.5, 0.5): a dock at (0, 0.5) straight to (0.3, 0.5),
  // 0.1 m from it, is a leg; straight on to (0.7, 0.5) crosses it.
  Wall round = rectWall(2, 1, {circle(0.5, 0.5, 0.1)});
  round.start = Point{0.0, 0.5};
  v = judged(round, tool, toolPath({{0.0, 0.5}, {0.3, 0.5}, {0.3, 0.2}}, {false, true}));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.legs, 1u);
  v = judged(round, tool, toolPath({{0.0, 0.5}, {0.7, 0.5}, {1.5, 0.5}}, {false, true}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.legs, 0u);
}

// ---- hand-computed areas -------------------------------------------------------------------

TEST(ExactJudge, OneStrokeOnASquareHasItsClosedFormAreas) {
  // 1 m square, s = 0.2 (r = 0.1), one horizontal stroke 0.4 m long.
  const Wall wall = rectWall(1, 1);
  ToolParams tool;
  tool.tool_width = 0.2;
  const Path path = pathOf({{0.3, 0.5}, {0.7, 0.5}});
  const int n = 128;
  const judge::ExactCoverage c = judge::judgeCoverage(wall, tool, path, {n});
  const double r = 0.1;
  const double swept = 0.4 * 2 * r + kPi * r * r;                // rectangle + disk
  const double reachable = 1.0 - 4 * r * r * (1 - kPi / 4);      // the square minus four corner cusps
  EXPECT_TRUE(c.swept_area.contains(swept));
  EXPECT_TRUE(c.reachable_area.contains(reachable));
  EXPECT_TRUE(c.coverage_reachable.contains(swept / reachable));
  EXPECT_TRUE(c.coverage_wall.contains(swept));
  // The bounds are the polygons' own areas: the stroke's straight sides are exact (the polygons
  // have vertices, resp. tangent edges, at 90 degrees), only the round ends differ.
  EXPECT_NEAR(c.swept_area.lower, 0.4 * 2 * r + inscribed(r, n), 1e-10);
  EXPECT_NEAR(c.swept_area.upper, 0.4 * 2 * r + circumscribed(r, n), 1e-10);
  EXPECT_NEAR(c.reachable_area.lower, 1.0 - 4 * r * r + inscribed(r, n), 1e-10);
  EXPECT_NEAR(c.reachable_area.upper, 1.0 - 4 * r * r + circumscribed(r, n), 1e-10);
  // No arc in P: exact up to the rounding to double.
  EXPECT_EQ(c.paintable_area.lower, 1.0);
  EXPECT_EQ(c.paintable_area.upper, 1.0);
}

TEST(ExactJudge, IntervalsShrinkAsTheSquareOfTheArcVertices) {
  const Wall wall = rectWall(1, 1);
  ToolParams tool;
  tool.tool_width = 0.2;
  const Path path = pathOf({{0.3, 0.5}, {0.7, 0.5}});
  const double w32 = judge::judgeCoverage(wall, tool, path, {32}).swept_area.width();
  const double w128 = judge::judgeCoverage(wall, tool, path, {128}).swept_area.width();
  EXPECT_GT(w128, 0.0);
  EXPECT_NEAR(w32 / w128, 16.0, 0.2);
}

TEST(ExactJudge, ObstaclesComeOffThePaintableArea) {
  ToolParams tool;
  const int n = 64;
  {  // a rectangle: exact
    const judge::ExactCoverage c = judge::judgeCoverage(rectWall(2, 1, {rect(0.5, 0.25, 0.5, 0.5)}), tool, Path{}, {n});
    EXPECT_EQ(c.paintable_area.lower, 2.0 - 0.25);
    EXPECT_EQ(c.paintable_area.upper, 2.0 - 0.25);
    EXPECT_EQ(c.swept_area.upper, 0.0);
    EXPECT_EQ(c.coverage_wall.lower, 0.0);
  }
  {  // a round socket of radius 0.1: between the wall minus the two polygons
    const judge::ExactCoverage c = judge::judgeCoverage(rectWall(2, 1, {circle(1, 0.5, 0.1)}), tool, Path{}, {n});
    EXPECT_TRUE(c.paintable_area.contains(2.0 - kPi * 0.01));
    EXPECT_NEAR(c.paintable_area.lower, 2.0 - circumscribed(0.1, n), 1e-10);
    EXPECT_NEAR(c.paintable_area.upper, 2.0 - inscribed(0.1, n), 1e-10);
  }
}

TEST(ExactJudge, ReachableAreaOfAWallWithAWindowFollowsTheDefinition) {
  // 3 x 2 wall, 1 x 0.5 window at (1, 0.75); s = 0.2, c = 0.05. F is the wall eroded by 0.1 minus
  // the window grown by 0.15 (round corners); R is F grown by 0.1.
  const Wall wall = rectWall(3, 2, {rect(1, 0.75, 1, 0.5)});
  ToolParams tool;
  tool.tool_width = 0.2;
  tool.clearance = 0.05;
  const judge::ExactCoverage c = judge::judgeCoverage(wall, tool, Path{}, {256});
  // R is the wall minus its four corner cusps, minus F's hole (the window grown by r + c) shrunk
  // back by r: the window grown by c, with corners of radius c.
  const double r = 0.1;
  const double window_grown_by_c = 1 * 0.5 + 2 * (1 + 0.5) * 0.05 + kPi * 0.05 * 0.05;
  const double expected = 6.0 - 4 * r * r * (1 - kPi / 4) - window_grown_by_c;
  EXPECT_TRUE(c.reachable_area.contains(expected)) << c.reachable_area.lower << " " << c.reachable_area.upper;
  EXPECT_LT(c.reachable_area.width(), 2e-5);
}

// ---- validity on the limits (dyadic numbers: every distance below is exact) ----------------

struct LimitCase : testing::Test {
  // 2 x 2 wall, window [1, 1.5] x [1, 1.5]; s = 0.5 (r = 0.25), c = 0.0625: r + c = 0.3125.
  Wall wall = rectWall(2, 2, {rect(1, 1, 0.5, 0.5)});
  ToolParams tool{0.5, 0.0625};
  judge::ExactValidity exact(const Path& p) const { return judge::judgeValidity(wall, tool, p); }
  Validity fast(const Path& p) const { return checkValidity(wall, tool, p); }
};

TEST_F(LimitCase, AlongAnObstacleEdgeExactlyAtTheClearance) {
  const Path on = pathOf({{0.25, 0.6875}, {1.75, 0.6875}});  // 0.3125 below the window
  EXPECT_TRUE(exact(on).valid);
  EXPECT_TRUE(fast(on).valid);
  const Path graze = pathOf({{0.25, std::nextafter(0.6875, 1.0)}, {1.75, 0.6875}});  // 1e-16 m too close
  EXPECT_FALSE(exact(graze).valid);
  EXPECT_EQ(exact(graze).too_close, 1u);
  // The fast engine forgives shortfalls up to 1e-9 m (docs/metrics.md): it calls this valid.
  EXPECT_TRUE(fast(graze).valid);
  const Path nano = pathOf({{0.25, 0.6875 + 2e-9}, {1.75, 0.6875 + 2e-9}});  // 2 nm too close
  EXPECT_FALSE(exact(nano).valid);
  EXPECT_FALSE(fast(nano).valid);
}

TEST_F(LimitCase, TouchingAnObstacleCornerExactlyAtTheClearance) {
  // (0.8125, 0.75) is 0.3125 from the corner (1, 1) along a 3-4-5 direction.
  const Path on = pathOf({{0.25, 0.75}, {0.8125, 0.75}});
  EXPECT_TRUE(exact(on).valid);
  const Path in = pathOf({{0.25, 0.75}, {std::nextafter(0.8125, 1.0), 0.75}});
  EXPECT_FALSE(exact(in).valid);
  EXPECT_EQ(exact(in).violating, std::vector<std::size_t>{0});
}

TEST_F(LimitCase, AlongTheWallEdgeExactlyAtTheToolRadius) {
  const Path on = pathOf({{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.25}});
  EXPECT_TRUE(exact(on).valid);
  const Path out = pathOf({{0.25, 0.25}, {0.75, std::nextafter(0.25, 0.0)}, {0.25, 0.25}});
  const judge::ExactValidity v = exact(out);
  EXPECT_EQ(v.outside_boundary, 2u);
  EXPECT_EQ(v.too_close, 0u);
  EXPECT_EQ(v.violating, (std::vector<std::size_t>{0, 1}));
}

TEST_F(LimitCase, ThroughAOneNanometreGapBetweenTwoObstacles) {
  wall.obstacles = {rect(0.5, 1, 0.5, 0.5), rect(1 + 1e-9, 1, 0.5, 0.5)};
  const Path through = pathOf({{1 + 5e-10, 0.25}, {1 + 5e-10, 1.75}});
  EXPECT_EQ(exact(through).too_close, 1u);
  EXPECT_FALSE(fast(through).valid);
}

TEST_F(LimitCase, AcrossAWindowAndInsideOne) {
  EXPECT_EQ(exact(pathOf({{0.25, 1.25}, {1.75, 1.25}})).too_close, 1u);  // crosses it
  wall.obstacles = {rect(0.4, 0.4, 1.2, 1.2)};
  // Deep inside the window: every edge is more than r + c away, so only the inside test sees it.
  const Path inside = pathOf({{0.9, 1.0}, {1.1, 1.0}});
  EXPECT_EQ(exact(inside).too_close, 1u);
  EXPECT_FALSE(fast(inside).valid);
}

TEST_F(LimitCase, RoundObstacleAtExactlyItsLimit) {
  wall.obstacles = {circle(1, 1, 0.25)};  // limit: 0.25 + 0.3125 = 0.5625 from the centre
  EXPECT_TRUE(exact(pathOf({{0.4375, 0.25}, {0.4375, 1.75}})).valid);
  EXPECT_FALSE(exact(pathOf({{std::nextafter(0.4375, 1.0), 0.25}, {0.4375, 1.75}})).valid);
  EXPECT_TRUE(exact(pathOf({{0.4375, 1.0}})).valid);  // one waypoint: a point
  EXPECT_FALSE(exact(pathOf({{0.45, 1.0}})).valid);
}

TEST_F(LimitCase, OutsideTheWallAltogether) {
  const judge::ExactValidity v = exact(pathOf({{3, 3}, {4, 4}}));
  EXPECT_EQ(v.outside_boundary, 1u);
  EXPECT_FALSE(v.valid);
}

// ---- properties: the fast engine against the exact judge -----------------------------------

// Random segments on random walls: the two judges agree on every segment whose gaps are not
// within 1e-8 m of a limit (where the fast engine's 1e-9 m tolerance and rounding may decide).
TEST(ExactJudgeProperty, FastValidityAgreesAwayFromTheLimits) {
  std::mt19937 rng(7);
  int compared = 0, invalid = 0;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    const Wall wall = test::randomWall(seed);
    ToolParams tool;
    tool.tool_width = 0.1 + 0.05 * (seed % 4);
    Box box;
    for (Point p : wall.boundary) box.add(p);
    std::uniform_real_distribution<double> x(box.min_x - 0.1, box.max_x + 0.1), y(box.min_y - 0.1, box.max_y + 0.1);
    for (int k = 0; k < 60; ++k) {
      const Path p = k % 10 == 0 ? pathOf({{x(rng), y(rng)}}) : pathOf({{x(rng), y(rng)}, {x(rng), y(rng)}});
      const Validity f = checkValidity(wall, tool, p);
      const bool near_boundary = std::fabs(f.min_boundary_gap) < 1e-8;
      const bool near_obstacle = std::isfinite(f.min_clearance) && std::fabs(f.min_clearance - tool.clearance) < 1e-8;
      if (near_boundary || near_obstacle) continue;
      const judge::ExactValidity e = judge::judgeValidity(wall, tool, p);
      ASSERT_EQ(e.outside_boundary, f.outside_boundary) << wall.name << " path " << k;
      ASSERT_EQ(e.too_close, f.too_close) << wall.name << " path " << k;
      ++compared;
      invalid += !e.valid;
    }
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(invalid, 500);          // the sample exercises both verdicts
  EXPECT_LT(invalid, compared - 300);
}

// Every planner on a hundred generated walls of every family but the 50 m stress walls: the exact
// judge's verdict and violation counts equal the fast engine's (all planners' paths are valid).
TEST(ExactJudgeProperty, PlannedPathsValidityAgreesOnAHundredWalls) {
  int judged = 0;
  for (const char* family : {"residential", "facade", "gable", "stairwell", "industrial", "random", "narrow", "open"}) {
    for (const Wall& wall : test::sampled(generateWalls(family, 21, family == std::string("facade") ? 4 : 14))) {
      for (const PlannerInfo& info : registeredPlanners()) {
        ToolParams tool;
        tool.tool_width = 0.15;
        const PlanResult result = test::planWith(info.name, wall, tool);
        if (result.path.waypoints.empty()) continue;
        const Validity fast = checkValidity(wall, tool, result.path);
        const judge::ExactValidity exact = judge::judgeValidity(wall, tool, result.path);
        ASSERT_EQ(exact.valid, fast.valid) << family << " " << wall.name << " " << info.name;
        ASSERT_EQ(exact.violations, fast.violations) << family << " " << wall.name << " " << info.name;
        ++judged;
      }
    }
  }
  EXPECT_GT(judged, 500 / static_cast<int>(test::sampleStride()));
}

// Planned paths on generated walls of every family: both judges find them valid, and the fast
// engine's coverage and areas lie within its stated error bounds of the certified intervals.
TEST(ExactJudgeProperty, FastCoverageWithinItsStatedBoundsOnPlannedPaths) {
  std::size_t judged = 0;
  const std::vector<std::string> families = test::sampled(std::vector<std::string>{"residential", "gable", "stairwell", "random", "open"});
  for (const std::string& family : families) {
    const std::vector<Wall> walls = generateWalls(family, 11, 1);
    for (const Wall& wall : walls) {
      for (const char* planner : {"zigzag", "spiral", "spanning-tree"}) {
        ToolParams tool;
        tool.tool_width = 0.2;
        const PlanResult result = test::planWith(planner, wall, tool);
        if (result.path.waypoints.empty()) {
          ADD_FAILURE() << family << " " << wall.name << " " << planner << ": no path, " << result.reason;
          continue;
        }
        const PathMetrics fast = computeMetrics(wall, tool, result.path);
        const judge::Judgement exact = judge::judgePath(wall, tool, result.path, {}, {32});
        const std::string where = family + " " + wall.name + " " + planner;
        EXPECT_EQ(exact.validity.valid, fast.validity.valid) << where;
        EXPECT_EQ(exact.validity.violations, fast.validity.violations) << where;
        const judge::ExactCoverage& c = exact.coverage;
        const double bound = fastErrorBound(tool.tool_width);
        EXPECT_LE(c.coverage_reachable.distanceTo(fast.coverage.coverage_reachable), bound) << where;
        EXPECT_LE(c.coverage_wall.distanceTo(fast.coverage.coverage_wall), bound) << where;
        EXPECT_LE(c.reachable_area.distanceTo(fast.coverage.reachable_area),
                  bound * c.reachable_area.upper) << where;
        EXPECT_LE(c.paintable_area.distanceTo(fast.coverage.paintable_area),
                  bound * c.paintable_area.upper) << where;
        EXPECT_LE(c.swept_area.distanceTo(fast.coverage.swept_area),
                  bound * c.swept_area.upper) << where;
        ++judged;
      }
    }
  }
  EXPECT_EQ(judged, 3 * families.size());  // every planner plans every one of these walls
}

// The fast engine's closed forms for |R| and |P| (regionAreas) against the certified intervals on
// generated walls: inside them where a closed form covers the whole area, and within the stated
// bound where the rest of the wall is polygons.
TEST(ExactJudgeProperty, RegionAreasClosedFormsInsideTheCertifiedIntervals) {
  ToolParams tool;
  tool.tool_width = 0.2;
  int whole_reachable = 0, whole_paintable = 0, obstacles = 0;
  for (const char* family : {"residential", "gable", "stairwell"}) {
    for (const Wall& wall : generateWalls(family, 3, 2)) {
      const RegionAreas fast = regionAreas(wall, tool);
      const judge::ExactCoverage exact = judge::judgeCoverage(wall, tool, Path{}, {128});
      const std::string where = std::string(family) + " " + wall.name;
      const bool paintable_closed = fast.obstacles_in_closed_form == wall.obstacles.size();
      const double slack = 1e-12 * exact.reachable_area.upper;  // rounding
      if (fast.wall_in_closed_form) {
        EXPECT_LE(exact.reachable_area.distanceTo(fast.reachable), slack) << where;
        ++whole_reachable;
      }
      if (paintable_closed) {
        EXPECT_LE(exact.paintable_area.distanceTo(fast.paintable), slack) << where;
        ++whole_paintable;
      }
      const double bound = fastErrorBound(tool.tool_width);
      EXPECT_LE(exact.reachable_area.distanceTo(fast.reachable), bound * exact.reachable_area.upper) << where;
      EXPECT_LE(exact.paintable_area.distanceTo(fast.paintable), bound * exact.paintable_area.upper) << where;
      obstacles += static_cast<int>(fast.obstacles_in_closed_form);
    }
  }
  // These walls exercise both closed forms (counts from the generators' seed 3).
  EXPECT_GE(whole_reachable, 2);
  EXPECT_GE(whole_paintable, 4);
  EXPECT_GE(obstacles, 8);
}

}  // namespace
}  // namespace coverbench
