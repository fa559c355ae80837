// Exact validity against hand-computed clearances; arcs in closed form against hand-computed
// distances and against fine chords.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "coverbench/clearance.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/rng.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::circle;
using test::rect;
using test::rectWall;

Path line(std::vector<Point> points, bool tool = true) {
  Path p;
  for (const Point& q : points) p.moveTo(q, tool);
  return p;
}

const ToolParams kTool{0.2, 0.05};  // r = 0.1, c = 0.05

TEST(Validity, PassTouchingTheBoundaryExactlyIsValid) {
  const Wall w = rectWall(4, 2);
  const Validity v = checkValidity(w, kTool, line({{0.1, 0.1}, {3.9, 0.1}, {3.9, 1.9}}));
  EXPECT_TRUE(v.valid);
  EXPECT_EQ(v.violations, 0u);
  EXPECT_NEAR(v.min_boundary_gap, 0.0, 1e-15);
  EXPECT_TRUE(std::isinf(v.min_clearance));  // no obstacles
}

TEST(Validity, DiskPokingOutOfTheWallIsOutsideBoundary) {
  const Wall w = rectWall(4, 2);
  const Validity v = checkValidity(w, kTool, line({{0.05, 1.0}, {2.0, 1.0}, {2.0, 1.5}}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.violations, 1u);
  EXPECT_EQ(v.outside_boundary, 1u);
  EXPECT_NEAR(v.min_boundary_gap, -0.05, 1e-12);
}

TEST(Validity, ClearanceFromTheToolEdgeNotItsCentre) {
  const Wall w = rectWall(4, 2, {rect(1, 0.5, 1, 1)});
  // Centre 0.2 below the obstacle: gap 0.2 - r = 0.1 >= c.
  Validity v = checkValidity(w, kTool, line({{0.5, 0.3}, {3.5, 0.3}}));
  EXPECT_TRUE(v.valid);
  EXPECT_NEAR(v.min_clearance, 0.1, 1e-12);
  // Centre 0.16 below: gap 0.06 >= 0.05, valid.
  v = checkValidity(w, kTool, line({{0.5, 0.34}, {3.5, 0.34}}));
  EXPECT_TRUE(v.valid);
  EXPECT_NEAR(v.min_clearance, 0.06, 1e-12);
  // Centre 0.14 below: gap 0.04 < c although the centre is outside the obstacle.
  v = checkValidity(w, kTool, line({{0.5, 0.36}, {3.5, 0.36}}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.too_close, 1u);
  EXPECT_EQ(v.outside_boundary, 0u);
  EXPECT_NEAR(v.min_clearance, 0.04, 1e-12);
}

TEST(Validity, SegmentThroughObstacleCountsOnceAndClearanceIsMinusR) {
  const Wall w = rectWall(4, 2, {rect(1, 0.5, 1, 1)});
  const Validity v = checkValidity(w, kTool, line({{0.3, 0.3}, {0.3, 1.0}, {3.5, 1.0}, {3.5, 1.7}}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.violations, 1u);
  EXPECT_NEAR(v.min_clearance, -0.1, 1e-12);
}

TEST(Validity, CornerClipBetweenFarEndpointsIsCaught) {
  // Both ends far outside; the segment clips the obstacle's corner over 2.8 cm (sampling at 5 cm
  // could step over it).
  const Wall w = rectWall(5, 5, {rect(1, 1, 1, 1)});
  const Validity v = checkValidity(w, ToolParams{0.02, 0.0}, line({{0.2, 3.78}, {3.78, 0.2}}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.too_close, 1u);
}

TEST(Validity, TransitsAreCheckedToo) {
  const Wall w = rectWall(4, 2, {rect(1, 0.5, 1, 1)});
  const Validity v = checkValidity(w, kTool, line({{0.3, 1.0}, {3.5, 1.0}}, false));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.violations, 1u);
}

TEST(Validity, CircleClearance) {
  const Wall w = rectWall(4, 3, {circle(2, 1.5, 0.3)});
  // Passing 0.5 from the centre: gap 0.5 - 0.3 - 0.1 = 0.1.
  const Validity v = checkValidity(w, kTool, line({{0.5, 1.0}, {3.5, 1.0}}));
  EXPECT_TRUE(v.valid);
  EXPECT_NEAR(v.min_clearance, 0.1, 1e-12);
  // A diagonal passing the centre at distance 0.44 (gap 0.04 < c): invalid.
  const double d = 0.44;
  const Point n{-std::sqrt(0.5), std::sqrt(0.5)};
  const Point a = Point{2, 1.5} + n * d + Point{-1, -1}, b = Point{2, 1.5} + n * d + Point{1, 1};
  const Validity u = checkValidity(w, kTool, line({a, b}));
  EXPECT_FALSE(u.valid);
  EXPECT_NEAR(u.min_clearance, 0.04, 1e-12);
}

TEST(Validity, SinglePointIsChecked) {
  const Wall w = rectWall(4, 2, {rect(1, 0.5, 1, 1)});
  EXPECT_TRUE(checkValidity(w, kTool, line({{0.5, 0.3}})).valid);
  EXPECT_FALSE(checkValidity(w, kTool, line({{1.5, 1.0}})).valid);
}

TEST(Validity, SegmentCrossingAReflexCornerOfAnLShapeLeavesTheWall) {
  Wall w = rectWall(1, 1);
  w.boundary = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  // From the bottom arm to the left arm in a straight line cuts across the outside corner.
  const Validity v = checkValidity(w, kTool, line({{3.5, 0.5}, {0.5, 3.5}}));
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.outside_boundary, 1u);
}

TEST(Lengths, SplitByToolState) {
  Path p;
  p.moveTo({0, 0}, true);
  p.moveTo({3, 0}, true);
  p.moveTo({3, 4}, false);
  const Lengths l = pathLengths(p);
  EXPECT_DOUBLE_EQ(l.cover, 3.0);
  EXPECT_DOUBLE_EQ(l.transit, 4.0);
  EXPECT_DOUBLE_EQ(l.total, 7.0);
}

TEST(ArcClearance, DistancesOfAQuarterCircleByHand) {
  // The quarter circle of radius 1 about the origin from (1, 0) to (0, 1), on [-5, 5]^2.
  Wall wall;
  wall.boundary = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  const double quarter = std::tan(M_PI / 8.0);
  auto with = [&](Obstacle o) {
    Wall w = wall;
    w.obstacles.push_back(std::move(o));
    return w;
  };
  auto square = [](double x, double y, double half) {
    Obstacle o;
    o.type = ObstacleType::Polygon;
    o.polygon = {{x - half, y - half}, {x + half, y - half}, {x + half, y + half}, {x - half, y + half}};
    return o;
  };
  {
    const ClearanceField field(wall);
    const SegmentClearance c = field.measureArc({1, 0}, {0, 1}, quarter);
    EXPECT_TRUE(c.inside);
    EXPECT_NEAR(c.boundary_distance, 4.0, 1e-12);  // x = 5 from the arc's x = 1 (and y = 5 from y = 1)
    EXPECT_TRUE(std::isinf(c.obstacle_distance));
    // The same ends the other way round (bulge -tan(pi / 8)): the arc through (0.29, 0.29) about
    // (1, 1), still 4 from x = 5 at its end (1, 0).
    EXPECT_NEAR(field.measureArc({1, 0}, {0, 1}, -quarter).boundary_distance, 4.0, 1e-12);
  }
  {
    // A circle of radius 0.5 at (3, 3): radially, sqrt(18) - 1 - 0.5.
    const Wall w = with(test::circle(3, 3, 0.5));
    EXPECT_NEAR(ClearanceField(w).measureArc({1, 0}, {0, 1}, quarter).obstacle_distance, std::sqrt(18.0) - 1.5, 1e-12);
  }
  {
    // A square of half side 0.2 at the centre: its corner (0.2, 0.2) is 1 - 0.2 sqrt(2) inside.
    const Wall w = with(square(0, 0, 0.2));
    EXPECT_NEAR(ClearanceField(w).measureArc({1, 0}, {0, 1}, quarter).obstacle_distance, 1.0 - 0.2 * std::sqrt(2.0), 1e-12);
  }
  {
    // A square at (-1.5, 0), beside the circle but outside the arc's sweep: the arc's end (0, 1)
    // is nearest, to its corner (-1.4, 0.1): sqrt(1.4^2 + 0.9^2), not the radial 0.4.
    const Wall w = with(square(-1.5, 0, 0.1));
    EXPECT_NEAR(ClearanceField(w).measureArc({1, 0}, {0, 1}, quarter).obstacle_distance, std::hypot(1.4, 0.9), 1e-12);
  }
  {
    // A thin rectangle across the arc: they meet.
    const Wall w = with(test::rect(0.6, 0.6, 0.02, 0.5));
    EXPECT_EQ(ClearanceField(w).measureArc({1, 0}, {0, 1}, quarter).obstacle_distance, 0.0);
    EXPECT_FALSE(ClearanceField(w).arcFree({1, 0}, {0, 1}, quarter, 0.01, 0.0, 0.0));
  }
  {
    // The wall's edge across the arc: outside.
    Wall w;
    w.boundary = {{-5, -5}, {0.8, -5}, {0.8, 5}, {-5, 5}};
    const SegmentClearance d = ClearanceField(w).measureArc({1, 0}, {0, 1}, quarter);
    EXPECT_EQ(d.boundary_distance, 0.0);
    EXPECT_FALSE(d.inside);
  }
}

TEST(ArcClearance, AgreesWithFineChordsOnRandomArcsAndWalls) {
  // measureArc against the least of measure() over chords of 1e-9 m sagitta (within that of the
  // arc): the same distances to 1e-8 m on 400 arcs over 20 generated walls, every other one
  // sweeping up to 272 degrees (bulge up to 2.5: the sweep test's branch for more than half a turn).
  Rng rng(11);
  int compared = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Wall wall = test::randomWall(seed);
    const ClearanceField field(wall);
    const Box box = boundingBox(wall.boundary);
    for (int k = 0; k < 20; ++k) {
      const Point a{box.min_x + rng.uniform(0.0, 1.0) * box.width(), box.min_y + rng.uniform(0.0, 1.0) * box.height()};
      const Point b{box.min_x + rng.uniform(0.0, 1.0) * box.width(), box.min_y + rng.uniform(0.0, 1.0) * box.height()};
      const double bulge = (rng.uniform(0.0, 1.0) * 2.0 - 1.0) * (k % 2 == 0 ? 0.99 : 2.5);
      if (std::fabs(bulge) < 0.01 || distance(a, b) < 1e-3) continue;
      Path arc;
      arc.moveTo(a, true);
      arc.arcTo(b, bulge, true);
      const Path chords = chordalPath(arc, 1e-9);
      double boundary = INFINITY, obstacle = INFINITY;
      for (std::size_t i = 0; i + 1 < chords.waypoints.size(); ++i) {
        const SegmentClearance c = field.measure(chords.waypoints[i], chords.waypoints[i + 1]);
        boundary = std::fmin(boundary, c.boundary_distance);
        obstacle = std::fmin(obstacle, c.obstacle_distance);
      }
      const SegmentClearance c = field.measureArc(a, b, bulge);
      EXPECT_NEAR(c.boundary_distance, boundary, 1e-8) << "seed " << seed << " arc " << k;
      if (std::isfinite(obstacle)) { EXPECT_NEAR(c.obstacle_distance, obstacle, 1e-8) << "seed " << seed << " arc " << k; }
      ++compared;
    }
  }
  EXPECT_GT(compared, 300);
}


// Acceptance 3 of issue 61: an invalid path's message names its first violating segments (index,
// points), what each breaks (the obstacle by its label, obstacles[i] without one, or the wall's
// edge) and the gap reached. Every expectation below is worked out by hand from the coordinates.
TEST(Validity, AnInvalidPathNamesItsFirstViolatingSegmentsAndWhatTheyHit) {
  Obstacle socket = rect(1.0, 1.4, 0.4, 0.4);  // far from the path
  socket.label = "socket";
  Obstacle window = rect(2.0, 0.6, 0.5, 0.4);  // x in [2, 2.5], y in [0.6, 1]
  window.label = "window";
  const Wall w = rectWall(4, 2, {socket, window, circle(3.23, 1.5, 0.1)});  // the circle has no label
  // r = 0.1, c = 0.05.
  const Path path = line({{0.5, 0.3},     // 0: y = 0.3, 0.2 from the floor: fine
                          {1.5, 0.3},     // 1: up x = 1.5, 0.5 left of the window: fine
                          {1.5, 0.8},     // 2: along y = 0.8 through the window: gap 0 - r = -0.1
                          {3.0, 0.8},     // 3: up x = 3 to y = 1.5: 0.23 - 0.1 from the circle, gap 0.03
                          {3.0, 1.5},     // 4: along y = 1.5 through the circle (gap -0.1), to x = 3.95:
                          {3.95, 1.5},    //    0.05 from the right edge, gap -0.05
                          {3.95, 0.3},    // 5: down the right edge: gap -0.05, obstacles far
                          {2.2, 0.3},     // 6: back from the edge (gap -0.05 at its start)
                          {2.2, 0.75}});  // 7: up into the window: the sixth, only counted
  const Validity v = checkValidity(w, kTool, path);
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.violations, 6u);
  EXPECT_EQ(v.violating, (std::vector<std::size_t>{2, 3, 4, 5, 6, 7}));
  ASSERT_EQ(v.described.size(), kDescribedViolations);
  const Violation& first = v.described[0];
  EXPECT_EQ(first.segment, 2u);
  EXPECT_EQ(first.from.x, 1.5);
  EXPECT_EQ(first.from.y, 0.8);
  EXPECT_EQ(first.to.x, 3.0);
  EXPECT_EQ(first.to.y, 0.8);
  EXPECT_TRUE(first.too_close);
  EXPECT_FALSE(first.outside_boundary);
  EXPECT_EQ(first.obstacle, 1);
  EXPECT_EQ(first.obstacle_label, "window");
  EXPECT_NEAR(first.clearance, -0.1, 1e-12);
  EXPECT_EQ(v.described[1].obstacle, 2);
  EXPECT_EQ(v.described[1].obstacle_label, "");
  EXPECT_NEAR(v.described[1].clearance, 0.03, 1e-12);
  EXPECT_TRUE(v.described[2].outside_boundary && v.described[2].too_close);
  EXPECT_NEAR(v.described[2].boundary_gap, -0.05, 1e-12);
  EXPECT_EQ(v.described[3].obstacle, -1);  // 0.62 m from the circle: no obstacle named
  EXPECT_EQ(v.described[4].segment, 6u);
  EXPECT_EQ(describeViolations(v, kTool.clearance),
            "6 segments violate the wall or the clearance: "
            "segment 2 (1.5, 0.8)->(3, 0.8) enters obstacle \"window\" (clearance -0.1 m < 0.05 m); "
            "segment 3 (3, 0.8)->(3, 1.5) comes too close to obstacles[2] (clearance 0.03 m < 0.05 m); "
            "segment 4 (3, 1.5)->(3.95, 1.5) leaves the wall's edge (gap -0.05 m < 0 m) and enters obstacles[2] "
            "(clearance -0.1 m < 0.05 m); "
            "segment 5 (3.95, 1.5)->(3.95, 0.3) leaves the wall's edge (gap -0.05 m < 0 m); "
            "segment 6 (3.95, 0.3)->(2.2, 0.3) leaves the wall's edge (gap -0.05 m < 0 m); 1 more");
  EXPECT_EQ(describeViolations(checkValidity(w, kTool, line({{0.5, 0.3}, {1.5, 0.3}})), kTool.clearance), "");
  // As bindings get them.
  const nlohmann::json j = nlohmann::json::parse(violationsJson(v));
  ASSERT_EQ(j.size(), 5u);
  EXPECT_EQ(j[0]["segment"], 2);
  EXPECT_EQ(j[0]["from"], nlohmann::json::parse("[1.5, 0.8]"));
  EXPECT_EQ(j[0]["obstacle"], 1);
  EXPECT_EQ(j[0]["obstacle_label"], "window");
  EXPECT_TRUE(j[0]["too_close"].get<bool>());
  EXPECT_TRUE(j[3]["obstacle"].is_null());
  EXPECT_TRUE(j[3]["clearance"].is_null());
}

// A gap short of the clearance by less than six digits show is printed with the digits that
// tell them apart; a gantry's lifted move is named as one.
TEST(Validity, AViolationsNumbersAreToldApartFromTheLimit) {
  const Wall w = rectWall(4, 2, {rect(2.0, 0.0, 0.5, 0.5)});
  // Centre at y = 0.65 - 1e-7: 0.15 - 1e-7 from the obstacle's top (y = 0.5), gap 0.05 - 1e-7.
  const Validity v = checkValidity(w, kTool, line({{1.0, 0.65 - 1e-7}, {3.0, 0.65 - 1e-7}}));
  ASSERT_FALSE(v.valid);
  EXPECT_EQ(describeViolations(v, kTool.clearance),
            "1 segments violate the wall or the clearance: segment 0 (1, 0.65)->(3, 0.65) comes too close to "
            "obstacles[0] (clearance 0.0499999 m < 0.05 m)");
  VehicleModel gantry;
  gantry.kind = VehicleModel::Kind::Gantry;
  Path lifted = line({{0.5, 1.0}, {1.0, 1.0}});
  lifted.moveTo({5.0, 1.0}, false);
  const Validity g = checkValidity(w, kTool, lifted, gantry);
  ASSERT_FALSE(g.valid);
  EXPECT_EQ(describeViolations(g, kTool.clearance),
            "1 segments violate the wall or the clearance: segment 1 (1, 1)->(5, 1) leaves the wall's bounding box "
            "(a lifted move)");
}

}  // namespace
}  // namespace coverbench
