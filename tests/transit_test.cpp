// Transits go around obstacles, never through them, and are as short as the graph allows.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/metrics.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::rect;
using test::rectWall;

TEST(Transit, StraightWhenFree) {
  const Wall w = rectWall(4, 2);
  Workspace ws(w, {0.1, 0.02});
  const auto route = ws.router().route({0.5, 0.5}, {3.5, 1.5});
  ASSERT_TRUE(route);
  EXPECT_EQ(route->size(), 2u);
}

TEST(Transit, GoesAroundAWindowWithTheShortestDetour) {
  // A 1 m wide window from y = 0.3 to 1.3 between the two points; going over it is shorter.
  const Wall w = rectWall(4, 2.5, {rect(1.5, 0.3, 1, 1.0)});
  const ToolParams tool{0.1, 0.02};
  Workspace ws(w, tool);
  const Point a{0.5, 1.0}, b{3.5, 1.0};
  EXPECT_FALSE(ws.router().isFree(a, b));
  const auto route = ws.router().route(a, b);
  ASSERT_TRUE(route);
  Path p;
  for (const Point& q : *route) p.moveTo(q, false);
  EXPECT_TRUE(test::isValidPath(w, tool, p));
  // Lower bound: the straight line. Upper bound: over the two top corners at distance
  // R = r + c = 0.07, plus slack for the polygonal nodes around each corner.
  const double R = 0.07;
  const double over_top = distance(a, {1.5 - R, 1.3 + R}) + (1.0 + 2 * R) + distance({2.5 + R, 1.3 + R}, b);
  EXPECT_LE(polylineLength(*route), over_top + 0.05);
  EXPECT_GT(polylineLength(*route), distance(a, b));
  for (const Point& q : *route) EXPECT_GE(q.y, 1.0);  // over, not under (the bottom is longer)
}

TEST(Transit, OutOfACuspOfTheFreeRegion) {
  // A window 0.118 m above the floor (the gap below is too low for the tool) and a second one
  // 0.181 m to its right leave a corridor. Right of the first window's lower corner, the floor's
  // offset line meets the corner's clearance arc in a cusp of F; the way out follows the arc,
  // where no corner node can be seen from the cusp (found in the generated `narrow` family).
  const Wall w = rectWall(3.0, 2.157, {rect(1.87, 0.118, 0.328, 2.039), rect(2.379, 0.0, 0.329, 0.809)});
  const ToolParams tool{0.1, 0.02};
  Workspace ws(w, tool);
  const Point cusp{2.2156, 0.0501}, corridor{2.29, 1.5};
  ASSERT_TRUE(ws.router().isFree(cusp, cusp)) << "the cusp point is in F";
  const auto route = ws.router().route(cusp, corridor);
  ASSERT_TRUE(route);
  Path p;
  for (const Point& q : *route) p.moveTo(q, false);
  EXPECT_TRUE(test::isValidPath(w, tool, p));
  EXPECT_LT(polylineLength(*route), distance(cusp, corridor) + 0.2);
}

TEST(Transit, UnreachableAcrossAClosedGap) {
  // The window leaves 0.1 m at the top: less than s + 2c = 0.14, so the two sides are separate.
  const Wall w = rectWall(3, 1.2, {rect(1.4, 0, 0.2, 1.1)});
  Workspace ws(w, {0.1, 0.02});
  EXPECT_FALSE(ws.router().route({0.5, 0.6}, {2.5, 0.6}).has_value());
}

TEST(Transit, ThroughANarrowPassageWhenItFits) {
  // 0.16 m at the top: wider than s + 2c = 0.14, so the tool passes above the window.
  const Wall w = rectWall(3, 1.2, {rect(1.4, 0, 0.2, 1.04)});
  const ToolParams tool{0.1, 0.02};
  Workspace ws(w, tool);
  const auto route = ws.router().route({0.5, 0.6}, {2.5, 0.6});
  ASSERT_TRUE(route.has_value());
  Path p;
  for (const Point& q : *route) p.moveTo(q, false);
  EXPECT_TRUE(test::isValidPath(w, tool, p));
}

// Spurs (corner_spurs): hand-computed tips on an L-shaped painted run, r = 0.1 m.
TEST(CornerSpurs, OutAndBackAtCornersAndRunEnds) {
  const Wall w = rectWall(4, 3);
  Workspace ws(w, ToolParams{0.2, 0.0});
  Path p;
  p.moveTo({0.5, 0.5}, false);
  p.moveTo({2.0, 0.5}, true);
  p.moveTo({2.0, 1.5}, true);
  p.moveTo({3.0, 2.5}, false);  // a tool-off move: no spur at its ends
  std::size_t spurs = 0;
  const Path q = withCornerSpurs(p, 0.1, ws.router(), spurs);
  EXPECT_EQ(spurs, 3u);
  // The run starts at (0.5, 0.5): r back; the 90-degree corner at (2, 0.5): r (sqrt 2 - 1) along
  // the outward bisector (1, -1) / sqrt 2, i.e. 0.1 (1 - 1 / sqrt 2) in x and y; the run ends at
  // (2, 1.5): r on.
  const double d = 0.1 * (1.0 - 1.0 / std::sqrt(2.0));
  const std::vector<Point> want = {{0.5, 0.5}, {0.4, 0.5}, {0.5, 0.5}, {2.0, 0.5}, {2.0 + d, 0.5 - d}, {2.0, 0.5},
                                   {2.0, 1.5}, {2.0, 1.6}, {2.0, 1.5}, {3.0, 2.5}};
  const std::vector<bool> tool = {true, true, true, true, true, true, true, true, false};
  ASSERT_EQ(q.waypoints.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(q.waypoints[i].x, want[i].x, 1e-12) << i;
    EXPECT_NEAR(q.waypoints[i].y, want[i].y, 1e-12) << i;
  }
  EXPECT_EQ(q.tool_on, tool);
}

TEST(CornerSpurs, ShortenedOrLeftOutWhereNotFree) {
  // The run ends 0.15 m from the wall's right edge: the disk may move 0.05 m on, not r = 0.1, and
  // planners keep kPlanningMargin spare, so the spur is r / 4 = 0.025 m (halved twice); at 0.1 m
  // from the edge there is no room at all and none is added (spurs stop at r / 8).
  const Wall w = rectWall(4, 3);
  Workspace ws(w, ToolParams{0.2, 0.0});
  for (const auto& [end_x, tip_x] : {std::pair<double, double>{3.85, 3.875}, {3.9, NAN}}) {
    Path p;
    p.moveTo({3.0, 1.0}, false);
    p.moveTo({end_x, 1.0}, true);
    std::size_t spurs = 0;
    const Path q = withCornerSpurs(p, 0.1, ws.router(), spurs);
    EXPECT_TRUE(test::isValidPath(w, ToolParams{0.2, 0.0}, q));
    if (std::isnan(tip_x)) {
      EXPECT_EQ(spurs, 1u) << "only the start's";
      EXPECT_EQ(q.waypoints.back().x, end_x);
    } else {
      EXPECT_EQ(spurs, 2u);
      ASSERT_GE(q.waypoints.size(), 2u);
      EXPECT_NEAR(q.waypoints[q.waypoints.size() - 2].x, tip_x, 1e-12);
    }
  }
}

}  // namespace
}  // namespace coverbench
