// What a forward-only car could paint at best (metrics/include/coverbench/car_ceiling.hpp):
// hand-computed rectangles, a strip too narrow to turn in, a dead-end pocket, and the bound held
// against the plans a car actually drives.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/car_ceiling.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

const ToolParams kTool{0.1, 0.02};  // r = 0.05

CarCeiling ceilingOf(const Wall& wall, double turn_radius) {
  CarCeilingOptions o;
  o.turn_radius = turn_radius;
  return forwardCarCeiling(wall, kTool, o);
}

// An obstacle-free W x H rectangle: a tool that turns on the spot misses r^2 (1 - pi/4) in each
// corner; a forward-only car, whose centre turns at R at best, misses (R + r)^2 (1 - pi/4). The
// lattice may let the car a little closer into a corner (it errs high, as a ceiling should), by
// at most 0.01.
TEST(CarCeiling, ARectangleLosesItsFourCornersToTheTurnRadius) {
  struct Case {
    double w, h, radius;
  };
  for (const Case c : {Case{3, 2, 0.3}, Case{3, 2, 0.5}, Case{6, 4, 0.3}, Case{6, 4, 0.5}}) {
    const double r = kTool.tool_width / 2.0, corner = 1.0 - M_PI / 4.0;
    const double expected = (c.w * c.h - 4.0 * (c.radius + r) * (c.radius + r) * corner) / (c.w * c.h - 4.0 * r * r * corner);
    const CarCeiling got = ceilingOf(test::rectWall(c.w, c.h), c.radius);
    EXPECT_GE(got.interior, expected - 0.002) << c.w << " x " << c.h << ", R = " << c.radius;
    EXPECT_LE(got.interior, expected + 0.01) << c.w << " x " << c.h << ", R = " << c.radius;
    EXPECT_NEAR(got.reachable_area, c.w * c.h, 0.03 * c.w * c.h);
    EXPECT_GE(got.with_ends, got.interior);
  }
}

// A 3 m strip whose F is 0.52 m high cannot hold a U-turn of radius 0.3 m (2R = 0.6 m): no pose is
// viable, and whatever a car paints there it paints on one way through, weaving at most. That is
// at least one straight band (0.1 m x 3 m of the strip's 1.79 m^2 reach: 0.17), and far from all
// of it. At 0.8 m high (F 0.7 m) it turns at both ends, and only the corners are lost.
TEST(CarCeiling, AStripTooNarrowToTurnInHasNoViablePose) {
  const CarCeiling narrow = ceilingOf(test::rectWall(3.0, 0.62), 0.3);
  EXPECT_EQ(narrow.viable, 0u);
  EXPECT_EQ(narrow.interior, 0.0);
  EXPECT_GT(narrow.states, 0u);
  EXPECT_GT(narrow.with_ends, 0.17);
  EXPECT_LT(narrow.with_ends, 0.75);
  const CarCeiling wide = ceilingOf(test::rectWall(3.0, 0.8), 0.3);
  EXPECT_GT(wide.viable, 0u);
  EXPECT_GT(wide.interior, 0.9);
}

// A 3 m x 2 m room with a 1 m x 0.5 m pocket off its right side: the pocket's F is 0.4 m wide, so
// a car that drives in never comes out. The pocket is a dead end: left out of `interior`, and
// `with_ends` adds what a path's head (driving out of it) and tail (driving into it) can paint
// there. Each is one pass: at least a straight band of the tool's width down the pocket's dead
// part (about 0.7 m deep beyond where a car can still turn out: 2 x 0.1 x 0.7 = 0.14 m^2), and at
// most what its longest chain of poses paints, which weaves across the 0.4 m: well under the
// 0.46 m^2 of the whole pocket's paint (what `with_ends` credited when it took a dead end whole).
TEST(CarCeiling, ADeadEndPocketCountsOnlyAsItsHeadAndTail) {
  Wall wall;
  wall.name = "pocket";
  wall.boundary = {{0, 0}, {3, 0}, {3, 0.8}, {4, 0.8}, {4, 1.3}, {3, 1.3}, {3, 2}, {0, 2}};
  const CarCeiling c = ceilingOf(wall, 0.3);
  const double extra = c.with_ends_area - c.interior_area;
  EXPECT_GT(extra, 0.14);
  EXPECT_LT(extra, 0.40);
  // The room alone, as in the rectangle case, over the room and the pocket; more by what a car
  // paints dipping into the pocket's mouth and turning out, and by the lattice's error.
  const double room = 6.0 - 4.0 * 0.35 * 0.35 * (1.0 - M_PI / 4.0);
  EXPECT_GE(c.interior, room / 6.5 - 0.002);
  EXPECT_LE(c.interior, room / 6.5 + 0.02);
}

// Two rooms, 3 m x 2 m and 2 m x 2 m, joined by a slit 6 cm high that no tool of 10 cm passes: F
// falls into two pieces and a path stays in one. The estimate is the larger room's: its area less
// its four corners, (6 - 4 (R + r)^2 (1 - pi/4)) = 5.895 m^2, over what a tool reaches in both
// rooms (about 10 m^2), 0.59; counting both rooms would give 0.98.
TEST(CarCeiling, APathStaysInOnePieceOfF) {
  Wall wall;
  wall.name = "two_rooms";
  wall.boundary = {{0, 0}, {3, 0}, {3, 0.9}, {4, 0.9}, {4, 0}, {6, 0}, {6, 2}, {4, 2}, {4, 0.96}, {3, 0.96}, {3, 2}, {0, 2}};
  const CarCeiling c = ceilingOf(wall, 0.3);
  EXPECT_EQ(c.pieces, 2u);
  // (To within the lattice's error, as for a rectangle: 0.005 of R.)
  const double room = 6.0 - 4.0 * 0.35 * 0.35 * (1.0 - M_PI / 4.0);
  EXPECT_NEAR(c.reachable_area, 10.0, 0.3);
  EXPECT_NEAR(c.interior, room / c.reachable_area, 0.005);
  EXPECT_LT(c.with_ends, 0.62);
  EXPECT_GE(c.with_ends, c.interior);
  // What a tool paints at best in the larger room, turning on the spot or reversing: about 6 of 10.
  EXPECT_NEAR(c.largest_piece_area, 6.0, 0.2);
  EXPECT_NEAR(c.largest_piece, c.largest_piece_area / c.reachable_area, 1e-12);
}

// A 3 m x 2 m room and, behind a corridor 0.3 m long and 0.16 m high, a room of 0.72 m x 0.72 m
// (F 0.62 m across) where a car of R = 0.3 m can drive circles but never join one from the
// corridor, nor leave one for it. Its circles' poses are viable, but in components of their own:
// a path's viable poses lie in one component, so the estimate is the large room's alone, its area
// less its four corners over R of both rooms: 5.895 / 6.49 m^2 = 0.908 (counting the small room's
// circles too gave about 0.93). Every reachable point is in one piece of F: `largest_piece` 1.
TEST(CarCeiling, APathsViablePosesLieInOneComponent) {
  Wall wall;
  wall.name = "room_behind_a_corridor";
  wall.boundary = {{0, 0}, {3, 0}, {3, 0.92}, {3.3, 0.92}, {3.3, 0.64}, {4.02, 0.64}, {4.02, 1.36}, {3.3, 1.36}, {3.3, 1.08}, {3, 1.08}, {3, 2}, {0, 2}};
  const CarCeiling c = ceilingOf(wall, 0.3);
  EXPECT_EQ(c.pieces, 1u);
  EXPECT_GT(c.components, 1u);
  const double room = 6.0 - 4.0 * 0.35 * 0.35 * (1.0 - M_PI / 4.0);
  EXPECT_NEAR(c.interior, room / c.reachable_area, 0.005);
  EXPECT_GE(c.with_ends, c.interior);
  EXPECT_NEAR(c.largest_piece, 1.0, 1e-12);
  EXPECT_NEAR(c.largest_piece_area, c.reachable_area, 1e-9);
}

TEST(CarCeiling, SameWallSameNumbers) {
  const Wall wall = generateWall("residential", 3, 1);
  const CarCeiling a = ceilingOf(wall, 0.3), b = ceilingOf(wall, 0.3);
  EXPECT_EQ(a.viable, b.viable);
  EXPECT_EQ(a.interior_area, b.interior_area);
  EXPECT_EQ(a.with_ends_area, b.with_ends_area);
}

// The ceiling is an upper bound: no plan a forward-only car drives, ours or the smoothed
// baseline, covers more of R than `with_ends` says it could (the lattice's raster counts area
// to within about 0.01 of the metrics engine's).
TEST(CarCeiling, NoDrivenPlanCoversMoreThanTheCeiling) {
  const PlannerInfo& info = findPlanner("zigzag");
  VehicleModel car;
  car.kind = VehicleModel::Kind::Car;
  car.turn_radius = 0.3;
  for (const std::string family : {"open", "residential", "narrow", "stairwell"})
    for (std::size_t i = 0; i < 2; ++i) {
      const Wall wall = generateWall(family, 3, i);
      const CarCeiling ceiling = ceilingOf(wall, 0.3);
      for (const std::string car_plan : {"headland", "smoothed"}) {
        Problem problem;
        problem.wall = &wall;
        problem.tool = kTool;
        problem.params = resolveParams(info, {{"car_plan", car_plan}});
        problem.vehicle = car;
        const PlanResult plan = runPlanner(info, problem, Budget());
        const PathMetrics m = computeMetrics(wall, kTool, plan.path, car);
        ASSERT_TRUE(m.validity.valid) << wall.name << " " << car_plan;
        EXPECT_LE(m.coverage.coverage_reachable, ceiling.with_ends + 0.01) << wall.name << " " << car_plan;
      }
    }
}

}  // namespace
}  // namespace coverbench
