// Exact validity against hand-computed clearances.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/metrics.hpp"
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

}  // namespace
}  // namespace coverbench
