// Transits go around obstacles, never through them, and are as short as the graph allows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coverbench/datasets.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"
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

/// The route from a to b on wall w for the tool (r 0.05, c 0.02), checked valid; empty when there is
/// none (a failure is recorded).
std::vector<Point> validRoute(const Wall& w, Point a, Point b) {
  const ToolParams tool{0.1, 0.02};
  Workspace ws(w, tool);
  const auto route = ws.router().route(a, b);
  EXPECT_TRUE(route.has_value());
  if (!route) return {};
  Path p;
  for (const Point& q : *route) p.moveTo(q, false);
  EXPECT_TRUE(test::isValidPath(w, tool, p));
  return *route;
}

TEST(Transit, OfEqualRoutesTakesTheOneWithFewestPoints) {
  // Two windows of equal height: the route over them passes the nodes above their four top
  // corners, all on the line y = 1.3 + R (R = 0.07 plus the nodes' 5e-6), at x = 1, 2, 3 and 4.
  // Going through the middle two is exactly as long (steps of 1 m), so the search meets exact
  // ties; the straight move from the first to the last is free, and a route must take it rather
  // than stopping on the way.
  const std::vector<Point> route = validRoute(rectWall(6, 2.5, {rect(1, 0.1, 1, 1.2), rect(3, 0.1, 1, 1.2)}), {0.5, 0.8}, {4.5, 0.8});
  ASSERT_FALSE(route.empty());
  std::size_t on_top = 0;
  for (const Point& q : route) on_top += std::fabs(q.y - (1.3 + 0.07)) < 1e-4;
  EXPECT_EQ(on_top, 2u) << "the route stops on the line over the windows at " << on_top << " points";
  for (std::size_t k = 1; k + 1 < route.size(); ++k) {
    const Point u = route[k] - route[k - 1], v = route[k + 1] - route[k];
    EXPECT_FALSE(std::fabs(cross(u, v)) <= 1e-12 && dot(u, v) > 0.0) << "vertex " << k << " lies on the straight way on";
  }
}

TEST(Transit, AroundABarrierSixTimesLongerThanTheStraightLine) {
  // A barrier from the left edge to x = 4 between two points 1 m apart: the route goes round its end,
  // over six times the straight distance (the search's growing bounds must reach it).
  const Point a{1.0, 1.0}, b{1.0, 2.0};
  const std::vector<Point> route = validRoute(rectWall(5, 3, {rect(0, 1.4, 4, 0.2)}), a, b);
  ASSERT_FALSE(route.empty());
  // At least the way round the barrier's two end corners (4, 1.4) and (4, 1.6); at most that plus
  // the half turn round the end at R = 0.07, whose nodes circumscribe it by a square's half (4 R,
  // not pi R), and 2 cm of slack.
  const double round_end = distance(a, {4, 1.4}) + 0.2 + distance({4, 1.6}, b);
  EXPECT_GE(polylineLength(route), round_end);
  EXPECT_LE(polylineLength(route), round_end + 4 * 0.07 + 0.02);
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

// --- Transits inside a connected free region, at every scale (issue 31) ---------------------------
//
// A public benchmark's 100 m field with 12 building holes, at s = 3 m and c = 0: a pocket in one
// corner opens to the rest only through a passage 0.07 m wider than the tool, far from anything the
// corner nodes see, and no F vertex lies within the near-end window of points in the pocket. The
// router gave up there; trapezoidal left 50 parts of the covered component out.

/// Points of F's largest component, drawn uniformly from its box.
std::vector<Point> pointsIn(Workspace& ws, std::size_t count, std::uint64_t seed) {
  const std::vector<PolygonWithHoles> comps = componentsByArea(ws.free());
  std::vector<Point> pts;
  if (comps.empty()) return pts;
  const Box b = boundingBox(comps.front().outer);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(b.min_x, b.max_x), y(b.min_y, b.max_y);
  for (int tries = 0; pts.size() < count && tries < 100000; ++tries) {
    const Point p{x(rng), y(rng)};
    if (pointInPolygon(comps.front(), p) && ws.router().isFree(p, p)) pts.push_back(p);
  }
  return pts;
}

Wall scaled(const Wall& w, double k) {
  Wall out = w;
  out.name += "-scaled";
  for (Point& p : out.boundary) p = p * k;
  for (Obstacle& o : out.obstacles)
    for (Point& p : o.polygon) p = p * k;
  return out;
}

TEST(TransitsAtFieldScale, EveryPairInTheCoveredComponentIsJoinedByAFreeRoute) {
  const Wall field = loadWallFile(test::sourcePath("tests/data/field-12-holes.json"));
  for (const auto& [wall, tool] : {std::pair<Wall, ToolParams>{field, {3.0, 0.0}}, {scaled(field, 1.0 / 30.0), {0.1, 0.0}}}) {
    Workspace ws(wall, tool);
    const std::vector<Point> pts = pointsIn(ws, 200, 7);
    ASSERT_EQ(pts.size(), 200u);
    // By hand: a point in the pocket above the passage at (98.46, 80.2) and one across the field.
    std::vector<std::pair<Point, Point>> pairs{{Point{98.227, 91.958} * (tool.tool_width / 3.0), Point{24.401, 39.968} * (tool.tool_width / 3.0)}};
    for (std::size_t i = 0; i + 1 < pts.size(); i += 2) pairs.emplace_back(pts[i], pts[i + 1]);
    for (const auto& [a, b] : pairs) {
      const auto route = ws.router().route(a, b);
      ASSERT_TRUE(route.has_value()) << wall.name << ": no route from (" << a.x << ", " << a.y << ") to (" << b.x << ", " << b.y << ")";
      for (std::size_t k = 0; k + 1 < route->size(); ++k) EXPECT_TRUE(ws.router().isFree((*route)[k], (*route)[k + 1]));
    }
  }
}

TEST(TransitsAtFieldScale, EveryPlannerLeavesNoPartOfTheCoveredComponentOut) {
  const Wall field = loadWallFile(test::sourcePath("tests/data/field-12-holes.json"));
  for (const auto& [wall, tool] : {std::pair<Wall, ToolParams>{field, {3.0, 0.0}}, {scaled(field, 1.0 / 30.0), {0.1, 0.0}}}) {
    for (const std::string& name : test::plannerNames()) {
      const PlannerInfo& info = findPlanner(name);
      Problem problem;
      problem.wall = &wall;
      problem.tool = tool;
      // spanning-tree, a grid method, reaches 0.984 without its corner spurs (its declared 0.98);
      // with them, 0.9987.
      problem.params = resolveParams(info, name == "spanning-tree" ? std::vector<std::pair<std::string, std::string>>{{"corner_spurs", "true"}}
                                                                   : std::vector<std::pair<std::string, std::string>>{});
      const PlanResult r = runPlanner(info, problem, Budget());
      ASSERT_TRUE(r.hasPath()) << name << " on " << wall.name << ": " << r.reason;
      EXPECT_EQ(r.unreachable_parts, 0u) << name << " on " << wall.name << ": " << r.reason;
      EXPECT_EQ(r.free_components, 2u) << name;  // a corner closed off by a gap narrower than the tool
      const PathMetrics m = computeMetrics(wall, tool, r.path);
      EXPECT_TRUE(m.validity.valid) << name << " on " << wall.name;
      EXPECT_GE(m.coverage.coverage_reachable, 0.99) << name << " on " << wall.name;
    }
  }
}

// Random fields like the benchmark's (100 m, 8 to 14 rotated building footprints, s = 3 m, c = 0)
// and generated walls of every family at tool widths from 5 cm to 5 m: every pair of points in F's
// largest component is joined by a free route.
TEST(TransitsAtFieldScale, PropertyEveryPairInAComponentIsJoinedOnFieldsAndFamilies) {
  std::mt19937_64 rng(2031);
  auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  std::vector<std::pair<Wall, ToolParams>> cases;
  for (int f = 0; f < 40; ++f) {
    Wall w;
    w.name = "field-" + std::to_string(f);
    w.boundary = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    const int n = 8 + static_cast<int>(rng() % 7);
    for (int k = 0; k < n; ++k) {
      const Point c{u(8, 92), u(8, 92)};
      const double a = u(0, M_PI), hw = u(3, 9), hh = u(3, 9);
      const Point e1{std::cos(a) * hw, std::sin(a) * hw}, e2{-std::sin(a) * hh, std::cos(a) * hh};
      Obstacle o;
      o.type = ObstacleType::Polygon;
      o.polygon = {c - e1 - e2, c + e1 - e2, c + e1 + e2, c - e1 + e2};
      w.obstacles.push_back(o);
    }
    cases.emplace_back(w, ToolParams{3.0, 0.0});
  }
  for (const char* family : {"residential", "facade", "industrial", "random", "narrow", "open"})
    for (double s : {0.05, 0.3, 1.0, 2.0, 5.0}) cases.emplace_back(generateWall(family, 11, 0), ToolParams{s, s / 10.0});
  std::size_t routed = 0;
  for (const auto& [wall, tool] : cases) {
    const Box b = boundingBox(wall.boundary);
    if (b.width() * b.height() / (tool.tool_width * tool.tool_width) > kMaxGridCells) continue;
    Workspace ws(wall, tool);
    const std::vector<Point> pts = pointsIn(ws, 40, routed + 1);
    for (std::size_t i = 0; i + 1 < pts.size(); i += 2) {
      const auto route = ws.router().route(pts[i], pts[i + 1]);
      EXPECT_TRUE(route.has_value()) << wall.name << " at s = " << tool.tool_width << ": no route from (" << pts[i].x << ", "
                                     << pts[i].y << ") to (" << pts[i + 1].x << ", " << pts[i + 1].y << ")";
      ++routed;
    }
  }
  EXPECT_GE(routed, 1000u);
}

// Over generated walls of every family and tool widths from 5 cm to 5 m, no planner leaves a part
// of the component it covers out for want of a transit.
TEST(TransitsAtFieldScale, PropertyNoPlannerLeavesAPartOfItsComponentOutAtAnyToolWidth) {
  std::size_t plans = 0;
  for (const char* family : {"residential", "facade", "gable", "stairwell", "industrial", "random", "narrow", "open"}) {
    const Wall wall = generateWall(family, 11, 0);
    for (double s : {0.05, 0.3, 1.0, 2.0, 5.0}) {
      const ToolParams tool{s, s / 10.0};
      const Box b = boundingBox(wall.boundary);
      if (b.width() * b.height() / (s * s) > kMaxGridCells) continue;
      for (const std::string& name : test::plannerNames()) {
        const PlannerInfo& info = findPlanner(name);
        Problem problem;
        problem.wall = &wall;
        problem.tool = tool;
        problem.params = resolveParams(info, {});
        const PlanResult r = runPlanner(info, problem, Budget());
        EXPECT_EQ(r.unreachable_parts, 0u) << name << " on " << wall.name << " at s = " << s << ": " << r.reason;
        ++plans;
      }
    }
  }
  EXPECT_GE(plans, 200u);
}

}  // namespace
}  // namespace coverbench
