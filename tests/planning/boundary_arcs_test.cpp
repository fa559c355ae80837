// Arcs as arcs (planning/include/coverbench/boundary_arcs.hpp): chains of chords on one circle
// become that arc, hand-computed; corners, chains off the circle and arcs that are not free stay
// as they were; and every planner's path with arcs paints what its chords painted, within the
// fit's sagitta along the arcs, over many generated walls.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/boundary_arcs.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

constexpr ToolParams kTool{0.1, 0.02};

/// Points of the circle of `radius` about `centre` from angle t0 to t1 (radians) in `chords` equal
/// chords, both ends included.
std::vector<Point> circlePoints(Point centre, double radius, double t0, double t1, int chords) {
  std::vector<Point> out;
  for (int k = 0; k <= chords; ++k) {
    const double t = t0 + (t1 - t0) * k / chords;
    out.push_back(centre + Point{std::cos(t), std::sin(t)} * radius);
  }
  return out;
}

Path polyline(const std::vector<Point>& points, bool tool) {
  Path p;
  for (const Point& q : points) p.moveTo(q, p.waypoints.empty() ? false : tool);
  if (!p.waypoints.empty()) p.tool_on.assign(p.waypoints.size() - 1, tool);
  return p;
}

// A 2 m x 2 m wall with a 0.4 m square window in its middle: F keeps r + c = 0.07 m from it.
Wall windowWall() { return test::rectWall(2.0, 2.0, {test::rect(0.8, 0.8, 0.4, 0.4)}); }

TEST(BoundaryArcs, AQuarterCircleOfChordsBetweenTangentLinesBecomesOneArc) {
  // Up the window's right side 0.1 m from it, a quarter circle of radius 0.1 about its corner
  // (1.2, 1.2) in 16 chords (sagitta 0.1 (1 - cos(pi / 64)) = 1.2e-4 m), then left along its top.
  const Wall wall = windowWall();
  Workspace ws(wall, kTool);
  std::vector<Point> points{{1.3, 0.8}};
  for (const Point& p : circlePoints({1.2, 1.2}, 0.1, 0.0, M_PI / 2.0, 16)) points.push_back(p);
  points.push_back({0.8, 1.3});
  const Path chords = polyline(points, true);
  ASSERT_EQ(chords.waypoints.size(), 19u);
  ArcFit fit;
  const Path arcs = withBoundaryArcs(chords, ws, fit);
  EXPECT_EQ(fit.arcs, 1u);
  EXPECT_EQ(fit.chords, 16u);
  EXPECT_EQ(fit.refused, 0u);
  ASSERT_EQ(arcs.waypoints.size(), 4u);
  EXPECT_EQ(arcs.bulgeOf(0), 0.0);
  EXPECT_NEAR(arcs.bulgeOf(1), std::tan(M_PI / 8.0), 1e-12);  // a quarter circle, counter-clockwise
  EXPECT_EQ(arcs.bulgeOf(2), 0.0);
  const ArcGeometry g = arcGeometry(arcs.waypoints[1], arcs.waypoints[2], arcs.bulgeOf(1));
  EXPECT_NEAR(g.centre.x, 1.2, 1e-12);
  EXPECT_NEAR(g.centre.y, 1.2, 1e-12);
  EXPECT_NEAR(g.radius, 0.1, 1e-12);
  // Its length is the arc's, 0.1 pi / 2, not the chords' 16 * 2 * 0.1 sin(pi / 64).
  EXPECT_NEAR(pathLengths(arcs).total, 0.4 + 0.1 * M_PI / 2.0 + 0.4, 1e-12);
  EXPECT_NEAR(pathLengths(chords).total, 0.8 + 3.2 * std::sin(M_PI / 64.0), 1e-12);
  // Lines tangent to the arc at both ends: no turn at all where the chords made 17 of 5.6 degrees
  // (the two halves at the tangent points 2.8), the same total heading change.
  const Motion m = motion(arcs), c = motion(chords);
  EXPECT_EQ(m.turns, 0u);
  EXPECT_EQ(c.turns, 17u);
  EXPECT_NEAR(m.turning_angle, M_PI / 2.0, 1e-9);
  EXPECT_NEAR(c.turning_angle, M_PI / 2.0, 1e-9);
  EXPECT_TRUE(test::isValidPath(wall, kTool, arcs));
}

TEST(BoundaryArcs, CornersChainsOffTheCircleAndShortChainsStayAsTheyAre) {
  const Wall wall = windowWall();
  Workspace ws(wall, kTool);
  ArcFit fit;
  // A loop round the window: four 90-degree corners.
  const Path square = polyline({{0.6, 0.6}, {1.4, 0.6}, {1.4, 1.4}, {0.6, 1.4}, {0.6, 0.6}}, true);
  const Path same = withBoundaryArcs(square, ws, fit);
  EXPECT_EQ(same.waypoints, square.waypoints);
  EXPECT_FALSE(same.hasArcs());
  // Two chords of a circle are left as they are (an arc replaces at least three).
  const Path two = polyline(circlePoints({1.2, 1.2}, 0.1, 0.0, 0.1, 2), true);
  EXPECT_FALSE(withBoundaryArcs(two, ws, fit).hasArcs());
  // The quarter circle with its middle vertex moved 1e-4 m outward (twice kArcFitTolerance): no arc
  // passes through it, so it stays a waypoint.
  std::vector<Point> bent = circlePoints({1.2, 1.2}, 0.1, 0.0, M_PI / 2.0, 16);
  bent[8] = Point{1.2, 1.2} + (bent[8] - Point{1.2, 1.2}) * (0.1001 / 0.1);
  const Path out = withBoundaryArcs(polyline(bent, true), ws, fit);
  bool kept = false;
  for (const Point& p : out.waypoints) kept = kept || p == bent[8];
  EXPECT_TRUE(kept);
  EXPECT_GE(fit.arcs, 2u) << "the chords either side of the moved vertex are arcs of their own";
}

TEST(BoundaryArcs, AnArcNeverJoinsTwoToolStatesNorALiftedMove) {
  const Wall wall = windowWall();
  const std::vector<Point> quarter = circlePoints({1.2, 1.2}, 0.1, 0.0, M_PI / 2.0, 16);
  Path p = polyline(quarter, true);
  for (std::size_t k = 8; k < p.tool_on.size(); ++k) p.tool_on[k] = false;
  {
    Workspace ws(wall, kTool);
    ArcFit fit;
    const Path out = withBoundaryArcs(p, ws, fit);
    ASSERT_EQ(fit.arcs, 2u);
    ASSERT_EQ(out.waypoints.size(), 3u);
    EXPECT_EQ(out.waypoints[1], quarter[8]);
    EXPECT_TRUE(out.tool_on[0]);
    EXPECT_FALSE(out.tool_on[1]);
  }
  {
    // A gantry's tool-off moves are lifted (they may leave F): never fitted.
    VehicleModel gantry;
    gantry.kind = VehicleModel::Kind::Gantry;
    Workspace ws(wall, kTool, gantry);
    ArcFit fit;
    const Path out = withBoundaryArcs(p, ws, fit);
    EXPECT_EQ(fit.arcs, 1u);
    EXPECT_EQ(out.waypoints.size(), 2u + 8u);
  }
}

TEST(BoundaryArcs, AnArcThatIsNotFreeStaysChords) {
  // A quarter circle of radius 0.2 about the window's corner in 21 chords (each 4.3 degrees,
  // sagitta 0.2 (1 - cos(pi / 84)) = 1.4e-4 m). A spike points at the middle of chord 10 from
  // 0.2 + 0.07 - 7e-5 m: the chord keeps 0.07 + 7e-5 from its tip, the arc only 0.07 - 7e-5.
  const Point corner{1.2, 1.2};
  const double mid = (10.5 / 21.0) * (M_PI / 2.0);
  const Point u{std::cos(mid), std::sin(mid)}, side{-u.y, u.x};
  const Point tip = corner + u * (0.27 - 7e-5);
  Wall wall = windowWall();
  Obstacle spike;
  spike.type = ObstacleType::Polygon;
  spike.polygon = {tip, tip + u * 0.1 + side * 0.02, tip + u * 0.1 - side * 0.02};
  wall.obstacles.push_back(spike);
  Workspace ws(wall, kTool);
  const Path chords = polyline(circlePoints(corner, 0.2, 0.0, M_PI / 2.0, 21), true);
  ASSERT_TRUE(test::isValidPath(wall, kTool, chords));
  ArcFit fit;
  const Path out = withBoundaryArcs(chords, ws, fit);
  EXPECT_EQ(fit.refused, 1u);
  EXPECT_EQ(fit.arcs, 0u);
  EXPECT_EQ(out.waypoints, chords.waypoints);
  // The same chain without the spike is one arc.
  Workspace open(windowWall(), kTool);
  ArcFit free_fit;
  EXPECT_EQ(withBoundaryArcs(chords, open, free_fit).waypoints.size(), 2u);
}

// Every planner on generated walls: the path with arcs against the same plan left as chords
// (Problem::straight_segments_only). Both valid; no more waypoints; the painted part of F moves by
// at most the fit's sagitta across the tool's two edges along every arc; the length by at most
// what the arcs add to their chords. (The conformance suite has the exact judge check them.)
class PlannerArcs : public testing::TestWithParam<std::string> {};

TEST_P(PlannerArcs, PaintTheSameAsTheirChordsWithinTheFitsSagitta) {
  const PlannerInfo& info = findPlanner(GetParam());
  std::size_t arcs_seen = 0;
  for (unsigned seed = 1; seed <= 16; ++seed) {
    const Wall wall = test::randomWall(seed);
    Problem problem;
    problem.wall = &wall;
    problem.tool = kTool;
    problem.params = resolveParams(info, {});
    const PlanResult with = runPlanner(info, problem, Budget());
    problem.straight_segments_only = true;
    const PlanResult without = runPlanner(info, problem, Budget());
    ASSERT_EQ(with.status, without.status) << "seed " << seed;
    if (!with.hasPath()) continue;
    EXPECT_FALSE(without.path.hasArcs());
    EXPECT_TRUE(checkValidity(wall, kTool, with.path).valid) << "seed " << seed;  // the exact judge: conformance suite
    EXPECT_LE(with.path.waypoints.size(), without.path.waypoints.size()) << "seed " << seed;
    double arc_length = 0.0, arc_excess = 0.0;
    for (std::size_t i = 0; i < with.path.segments(); ++i)
      if (with.path.bulgeOf(i) != 0.0) {
        ++arcs_seen;
        arc_length += segmentLength(with.path, i);
        arc_excess += segmentLength(with.path, i) - distance(with.path.waypoints[i], with.path.waypoints[i + 1]);
      }
    EXPECT_EQ(with.stats.at("boundary_arcs") > 0.0, arc_length > 0.0);
    const PathMetrics a = computeMetrics(wall, kTool, with.path), b = computeMetrics(wall, kTool, without.path);
    const double painted_a = a.coverage.coverage_reachable * a.coverage.reachable_area;
    const double painted_b = b.coverage.coverage_reachable * b.coverage.reachable_area;
    EXPECT_LE(std::fabs(painted_a - painted_b), 2.0 * kArcFitSagitta * arc_length + 1e-9) << "seed " << seed;
    EXPECT_LE(a.lengths.total, b.lengths.total + arc_excess + 1e-9) << "seed " << seed;
    EXPECT_GE(a.lengths.total, b.lengths.total - 1e-9) << "seed " << seed;
  }
  EXPECT_GT(arcs_seen, 0u) << "no generated wall gave this planner an arc to fit";
}

INSTANTIATE_TEST_SUITE_P(EveryPlanner, PlannerArcs, testing::ValuesIn(test::plannerNames()), test::plannerTestName);

}  // namespace
}  // namespace coverbench
