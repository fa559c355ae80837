// Boundary loops and the rows inside them (issue: planners at the quality frontier): the swept
// region and the headland regions against hand-computed areas, and the sweep planners' rows on
// obstacle-free walls against the closed forms of what a round tool must paint twice.
#include <gtest/gtest.h>

#include <cmath>

#include "coverbench/headland.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

Ring square(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

TEST(SweepAlong, ARectangleGrowsByTheSegmentAndAHoleShrinks) {
  // [0, 1]^2 moved 0.25 up and down: [0, 1] x [-0.25, 1.25], area 1.5.
  const Region unit{{square(0, 0, 1, 1), {}}};
  EXPECT_NEAR(area(sweepAlong(unit, {0.0, 0.25})), 1.5, 1e-9);
  // With a hole [0.4, 0.6]^2 moved 0.05 up and down: the outside grows to 1 x 1.1, the hole
  // shrinks to 0.2 x 0.1: 1.1 - 0.02 = 1.08.
  Ring hole = square(0.4, 0.4, 0.6, 0.6);
  std::reverse(hole.begin(), hole.end());
  const Region holed{{square(0, 0, 1, 1), {hole}}};
  EXPECT_NEAR(area(sweepAlong(holed, {0.0, 0.05})), 1.08, 1e-9);
  // Moved 0.15 sideways, more than half the hole's width: the hole closes; 1.3 x 1.
  EXPECT_NEAR(area(sweepAlong(holed, {0.15, 0.0})), 1.3, 1e-9);
}

TEST(SweepAlong, ATriangleSweptAlongOneSideAddsAParallelogram) {
  // The right triangle (0,0), (2,0), (0,1) moved 0.5 either way along x: a convex region plus a
  // segment of length 1 gains the segment's length times its height across it: 1 + 1 * 1 = 2.
  const Region tri{{{{0, 0}, {2, 0}, {0, 1}}, {}}};
  EXPECT_NEAR(area(sweepAlong(tri, {0.5, 0.0})), 2.0, 1e-9);
}

TEST(Headland, RegionsOfARectangleLieWhereTheyShould) {
  // F of a 5 m x 5 m wall at s = 0.1: [0.05, 4.95]^2, drawn m = kFreeSpaceMargin inside. One
  // loop on F's edge; rows one spacing inside across ([0.15, 4.85]^2), ends half a spacing inside
  // along them, swept half a spacing across, then cut back to F drawn the arc tolerance t
  // deeper: [0.1, 4.9] x [0.05 + t, 4.95 - t], all m farther in.
  const Wall wall = test::rectWall(5.0, 5.0);
  Workspace ws(wall, {0.1, 0.02});
  const Region& f = ws.free();
  HeadlandOptions o;
  o.spacing = 0.1;
  o.radius = 0.05;
  o.arc_tolerance = 1e-4;
  o.end_inset = 0.5;
  o.with_unpainted = true;
  const Headland h = headland(ws, f, o);
  const double m = kFreeSpaceMargin, t = o.arc_tolerance;
  ASSERT_EQ(h.loops.size(), 1u);
  EXPECT_NEAR(area(h.inner), std::pow(4.7 - 2 * m, 2), 1e-5);
  EXPECT_NEAR(area(h.ends), (4.8 - 2 * m) * (4.9 - 2 * (m + t)), 1e-5);
  EXPECT_NEAR(area(h.unpainted), std::pow(4.8 - 2 * m, 2), 1e-5);
  const Box inner = boundingBox(h.inner), ends = boundingBox(h.ends);
  EXPECT_NEAR(inner.min_y, 0.15 + m, 2e-6);
  EXPECT_NEAR(ends.min_x, 0.10 + m, 2e-6);
  EXPECT_NEAR(ends.min_y, 0.05 + m + t, 2e-6);
  // Rows along y instead: the ends region is swept along x.
  o.along_x = false;
  EXPECT_NEAR(area(headland(ws, f, o).ends), (4.9 - 2 * (m + t)) * (4.8 - 2 * m), 1e-5);
  // Two loops: everything one spacing deeper.
  o.loops = 2;
  EXPECT_EQ(headland(ws, f, o).loops.size(), 2u);
  EXPECT_NEAR(area(headland(ws, f, o).inner), std::pow(4.5 - 2 * m, 2), 1e-5);
  // No loop: rows from edge to edge of F.
  o.loops = 0;
  EXPECT_NEAR(area(headland(ws, f, o).ends), area(f), 1e-12);
}

TEST(Headland, RowsEndWhereTheLoopPaintsOnAnOpenWall) {
  // The closed form for an open rectangle W x H (F = (W - s) x (H - s)): rows run H_F / s - 1
  // deep, each ending in the loop's band at both ends. Each row end paints, beyond the band's
  // edge, half a tool width along the side, so the overlap is about s / W_F of the swept area;
  // the turns and corners add a little. The length is |R| / s within the loop's extra perimeter.
  // (At row_end_inset 0.5, where the closed form holds; the default 0.6 trades a little of it.)
  const ToolParams tool{0.1, 0.02};
  const Wall wall = test::rectWall(10.0, 10.0);
  for (const char* planner : {"zigzag", "boustrophedon", "trapezoidal"}) {
    const PlanResult r = test::planWith(planner, wall, tool, {{"row_end_inset", "0.5"}});
    ASSERT_EQ(r.status, PlanStatus::Ok) << planner << ": " << r.reason;
    EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << planner;
    const PathMetrics m = computeMetrics(wall, tool, r.path);
    // All is painted but the four convex corners' pieces between the loop and the first and last
    // rows, (1 - pi/4) (s/2)^2 each, of |R| = 100 - (4 - pi) (s/2)^2.
    const double corner = (1.0 - M_PI / 4.0) * 0.0025, reachable = 100.0 - (4.0 - M_PI) * 0.0025;
    EXPECT_NEAR(m.coverage.coverage_reachable, 1.0 - 4.0 * corner / reachable, 2e-6) << planner;
    EXPECT_NEAR(m.passes.overlap, 0.1 / 9.9, 0.001) << planner;
    EXPECT_LE(m.length_ratio, 1.012) << planner;
    EXPECT_GE(m.length_ratio, 1.0) << planner;
  }
}

TEST(Headland, ARowEndInsetTradesOverlapForScallops) {
  // Ending rows farther from the loop paints less twice and leaves scallops between the round
  // ends of rows no turn joins: overlap down, coverage down, monotonically.
  const ToolParams tool{0.1, 0.02};
  const Wall wall = test::rectWall(5.0, 5.0);
  double last_overlap = INFINITY, last_coverage = INFINITY;
  for (const char* inset : {"0.5", "0.6", "0.7", "1"}) {
    const PlanResult r = test::planWith("zigzag", wall, tool, {{"row_end_inset", inset}});
    ASSERT_EQ(r.status, PlanStatus::Ok) << inset;
    EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << inset;
    const PathMetrics m = computeMetrics(wall, tool, r.path);
    EXPECT_LT(m.passes.overlap, last_overlap) << inset;
    EXPECT_LT(m.coverage.coverage_reachable, last_coverage + 1e-12) << inset;
    last_overlap = m.passes.overlap, last_coverage = m.coverage.coverage_reachable;
  }
  EXPECT_LT(last_coverage, 0.999);  // 1.0: the scallops of zigzag with the rows in `inner`
}

TEST(Headland, BelowHalfASpacingRowsRunIntoTheLoopsBandAndAtZeroToItsLine) {
  // An open 5 m x 5 m wall, s = 0.1 m: the loop runs on F's edge, the square of the path's
  // extreme waypoints [e, 5 - e]. A row (a painted straight segment off the loop's lines) ends
  // row_end_inset spacings (0.1 m) inside the loop: at e + 0.1 i and 5 - e - 0.1 i along its
  // direction, and at 0 on the loop's line within the planner's offset tolerance (zigzag 1 mm,
  // the decomposition planners 2 mm). Farther in paints less twice.
  const ToolParams tool{0.1, 0.02};
  const Wall wall = test::rectWall(5.0, 5.0);
  for (const auto& [planner, tolerance] : {std::pair{"zigzag", 1e-3}, {"boustrophedon", 2e-3}, {"trapezoidal", 2e-3}}) {
    double last_overlap = INFINITY;
    for (const char* inset : {"0", "0.25", "0.5"}) {
      const PlanResult r = test::planWith(planner, wall, tool, {{"row_end_inset", inset}});
      ASSERT_EQ(r.status, PlanStatus::Ok) << planner << " " << inset << ": " << r.reason;
      EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << planner << " " << inset;
      double e = INFINITY;
      for (const Point& p : r.path.waypoints) e = std::fmin(e, std::fmin(p.x, p.y));
      EXPECT_NEAR(e, 0.05, 1e-4) << planner;  // F's edge: r from the wall's, and a hair more
      const auto onLoop = [&](double v) { return std::fabs(v - e) < 1e-9 || std::fabs(v - (5.0 - e)) < 1e-9; };
      // Rows along x (their ends' x) and along y (their ends' y): [lowest, highest, how many].
      double ends[2][3] = {{INFINITY, -INFINITY, 0}, {INFINITY, -INFINITY, 0}};
      for (std::size_t i = 0; i < r.path.segments(); ++i) {
        const Point a = r.path.waypoints[i], b = r.path.waypoints[i + 1];
        if (!r.path.tool_on[i] || r.path.bulgeOf(i) != 0.0) continue;
        for (int axis = 0; axis < 2; ++axis) {
          const double across = axis == 0 ? a.y : a.x, along_a = axis == 0 ? a.x : a.y, along_b = axis == 0 ? b.x : b.y;
          if (std::fabs(across - (axis == 0 ? b.y : b.x)) > 1e-9 || onLoop(across)) continue;
          ends[axis][0] = std::fmin(ends[axis][0], std::fmin(along_a, along_b));
          ends[axis][1] = std::fmax(ends[axis][1], std::fmax(along_a, along_b));
          ends[axis][2] += 1;
        }
      }
      const double* rows = ends[0][2] > ends[1][2] ? ends[0] : ends[1];
      EXPECT_GE(rows[2], 40.0) << planner << " " << inset;
      const double end = std::fmax(0.1 * std::stod(inset), tolerance);
      EXPECT_NEAR(rows[0], e + end, 1e-6) << planner << " " << inset;
      EXPECT_NEAR(rows[1], 5.0 - e - end, 1e-6) << planner << " " << inset;
      const double overlap = computeMetrics(wall, tool, r.path).passes.overlap;
      EXPECT_LT(overlap, last_overlap) << planner << " " << inset;
      last_overlap = overlap;
    }
  }
}

TEST(Headland, RowsToTheLoopsLineLeaveMoreOfASprayedCoatNearItsMean) {
  // A 2 m x 1.5 m wall with a 0.6 m x 0.5 m window, a beta fan (2.5) on a gun whose flow follows
  // the speed, rows spaced for it (coat_ripple 0.02). Rows run to the loop's line paint their ends
  // into the loop's band: more paint there (a higher mean), and more of R within 10 % of the mean
  // than rows ending half a spacing inside (zigzag 0.739 against 0.725, the decomposition planners
  // 0.754 against 0.655), for a higher CV (the band where both paint is thicker). The same
  // coverage: the loop paints what the row ends reach either way.
  ToolParams tool{0.1, 0.02};
  tool.profile.kind = FluxProfile::Kind::Beta;
  tool.profile.beta = 2.5;
  tool.profile.flow = FluxProfile::Flow::Speed;
  const Wall wall = test::rectWall(2.0, 1.5, {test::rect(0.7, 0.5, 0.6, 0.5)});
  for (const char* planner : {"zigzag", "boustrophedon", "trapezoidal"}) {
    const PlanResult line = test::planWith(planner, wall, tool, {{"coat_ripple", "0.02"}, {"row_end_inset", "0"}});
    const PlanResult half = test::planWith(planner, wall, tool, {{"coat_ripple", "0.02"}, {"row_end_inset", "0.5"}});
    ASSERT_EQ(line.status, PlanStatus::Ok) << planner << ": " << line.reason;
    ASSERT_EQ(half.status, PlanStatus::Ok) << planner << ": " << half.reason;
    const PathMetrics a = computeMetrics(wall, tool, line.path), b = computeMetrics(wall, tool, half.path);
    ASSERT_TRUE(a.deposition && b.deposition) << planner;
    EXPECT_TRUE(a.validity.valid) << planner;
    EXPECT_GT(a.deposition->even_share, b.deposition->even_share + 0.01) << planner;
    EXPECT_GT(a.deposition->mean_um, b.deposition->mean_um) << planner;
    EXPECT_GT(a.deposition->cv, b.deposition->cv) << planner;
    EXPECT_NEAR(a.coverage.coverage_reachable, b.coverage.coverage_reachable, 1e-6) << planner;
  }
}

TEST(Headland, RowsUnderAWindowBetweenTwoRowsStillPaintItsBand) {
  // A window whose bottom lies between two rows: the row just below reaches under it (its strip
  // does), so the band under the window is painted without a pass of its own. Windows at several
  // heights, so every offset against the rows occurs.
  const ToolParams tool{0.1, 0.02};
  for (int k = 0; k < 10; ++k) {
    const double y = 1.0 + 0.0137 * k;
    const Wall wall = test::rectWall(6.0, 4.0, {test::rect(2.0, y, 1.2, 1.4)});
    for (const char* planner : {"zigzag", "boustrophedon"})
      for (const char* angle : {"0", "90"}) {
        // At row_end_inset 0.5 nothing but the corners is left; at the default 0.6 the scallops
        // between row ends take a few parts in ten thousand.
        const PlanResult r = test::planWith(planner, wall, tool, {{"sweep_angle", angle}, {"row_end_inset", "0.5"}});
        ASSERT_EQ(r.status, PlanStatus::Ok) << planner << " " << y;
        EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << planner << " " << y;
        EXPECT_GE(coverage(wall, tool, r.path).coverage_reachable, 0.9999) << planner << " " << angle << " " << y;
        const PlanResult d = test::planWith(planner, wall, tool, {{"sweep_angle", angle}});
        ASSERT_EQ(d.status, PlanStatus::Ok) << planner << " " << y;
        EXPECT_TRUE(test::isValidPath(wall, tool, d.path)) << planner << " " << y;
        EXPECT_GE(coverage(wall, tool, d.path).coverage_reachable, 0.999) << planner << " " << angle << " " << y;
      }
  }
}

TEST(Headland, ACorridorTooThinForTheDeeperInsetStillGetsRows) {
  // A window 0.24 m from the wall's right edge: F there is a vertical corridor 0.10 m wide,
  // painted by the two loops along it but for a strip between them that only rows crossing it
  // reach. At row_end_inset 0.6 the rows' region has no room in it; the thin part of F half a
  // spacing deep keeps rows there (without that fallback: coverage 0.9966 zigzag, 0.9963
  // boustrophedon; with it 0.9998, as at 0.5).
  const ToolParams tool{0.1, 0.02};
  const Wall wall = test::rectWall(4.0, 3.0, {test::rect(1.0, 0.8, 2.76, 1.4)});
  for (const char* planner : {"zigzag", "boustrophedon", "trapezoidal"}) {
    const PlanResult deep = test::planWith(planner, wall, tool, {{"row_end_inset", "0.6"}});
    const PlanResult half = test::planWith(planner, wall, tool, {{"row_end_inset", "0.5"}});
    ASSERT_EQ(deep.status, PlanStatus::Ok) << planner << ": " << deep.reason;
    ASSERT_EQ(half.status, PlanStatus::Ok) << planner << ": " << half.reason;
    EXPECT_TRUE(test::isValidPath(wall, tool, deep.path)) << planner;
    const double c_deep = coverage(wall, tool, deep.path).coverage_reachable;
    EXPECT_GE(c_deep, 0.9995) << planner;
    EXPECT_GE(c_deep, coverage(wall, tool, half.path).coverage_reachable - 2e-4) << planner;
  }
}

TEST(Headland, FillLeftoversPaintsWhatRowsAndLoopsMissed) {
  // A slot 0.34 m wide and 0.2 m deep between two blocks on the floor: F in it is 0.2 m wide,
  // too thin for rows one spacing inside the loop and reaching less than 1.5 spacings beyond
  // them, so the middle of the slot is left between its two loop sides. With fill_leftovers it
  // gets a pass of its own, and coverage grows.
  const ToolParams tool{0.1, 0.02};
  const Wall wall = test::rectWall(4.0, 3.0, {test::rect(0.0, 0.0, 1.9, 0.2), test::rect(2.24, 0.0, 1.76, 0.2)});
  for (const char* planner : {"zigzag", "boustrophedon", "trapezoidal"}) {
    const PlanResult plain = test::planWith(planner, wall, tool);
    const PlanResult filled = test::planWith(planner, wall, tool, {{"fill_leftovers", "true"}});
    ASSERT_TRUE(filled.hasPath()) << planner << ": " << filled.reason;
    EXPECT_TRUE(test::isValidPath(wall, tool, filled.path)) << planner;
    EXPECT_EQ(plain.stats.count("leftover_passes"), 0u) << planner;
    EXPECT_GE(filled.stats.at("leftover_passes"), 1.0) << planner;
    const double before = coverage(wall, tool, plain.path).coverage_reachable;
    const double after = coverage(wall, tool, filled.path).coverage_reachable;
    EXPECT_GT(after, before + 2e-4) << planner;
    EXPECT_GE(after, 0.9999) << planner;
  }
}

}  // namespace
}  // namespace coverbench
