// The grid planners' promises (issue: grid planners): seed 004's ordering of traversal
// improvements, Spiral-STC visiting every free sub-cell exactly once, and adaptive-resolution
// winning back the coverage a fixed grid loses near obstacles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "coverbench/clearance.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/sweep_search.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::rect;
using test::rectWall;

PlanResult planWith(const Wall& wall, const ToolParams& tool, std::vector<std::pair<std::string, std::string>> settings,
                    const std::string& planner = "spanning-tree") {
  return test::planWith(planner, wall, tool, settings);
}

TEST(SpanningTree, ShortBranchesFirstNoLongerThanStopWhichIsShorterThanReturn) {
  // Seed 004: 43 -> 33 -> 28 points on its example. The same ordering on every wall of a test
  // set: random walls, the canonical walls, both tree kinds.
  std::vector<Wall> walls;
  for (unsigned seed = 1; seed <= 25; ++seed) walls.push_back(test::randomWall(seed));
  for (const std::string& f : test::conformanceWallFiles()) walls.push_back(loadWallFile(f));
  int compared = 0;
  for (const Wall& wall : walls)
    for (const char* tree : {"dfs", "mst"}) {
      const ToolParams tool{0.1, 0.02};
      // A waypoint per cell visit: the seed counts points.
      const PlanResult ret = planWith(wall, tool, {{"variant", "return"}, {"tree", tree}, {"waypoint_per_cell", "true"}, {"boundary_loop", "false"}});
      const PlanResult stop = planWith(wall, tool, {{"variant", "stop"}, {"tree", tree}, {"waypoint_per_cell", "true"}, {"boundary_loop", "false"}});
      const PlanResult sbf =
          planWith(wall, tool, {{"variant", "short-branches-first"}, {"tree", tree}, {"waypoint_per_cell", "true"},
                                 {"boundary_loop", "false"}});
      if (ret.status != PlanStatus::Ok) continue;
      ASSERT_EQ(stop.status, PlanStatus::Ok);
      ASSERT_EQ(sbf.status, PlanStatus::Ok);
      const double l_ret = pathLengths(ret.path).total, l_stop = pathLengths(stop.path).total,
                   l_sbf = pathLengths(sbf.path).total;
      EXPECT_LE(l_sbf, l_stop + 1e-9) << wall.name << " " << tree;
      if (ret.stats.at("tree_cells") > 1.0) {
        EXPECT_LT(l_stop, l_ret) << wall.name << " " << tree;
      }
      EXPECT_LE(sbf.path.waypoints.size(), stop.path.waypoints.size()) << wall.name;
      EXPECT_LT(stop.path.waypoints.size(), ret.path.waypoints.size()) << wall.name;
      // All three visit the same cells (only the walk differs), so coverage is the same.
      EXPECT_NEAR(coverage(wall, tool, ret.path).coverage_reachable, coverage(wall, tool, sbf.path).coverage_reachable, 1e-9);
      ++compared;
    }
  EXPECT_GE(compared, 60);
}

TEST(SpanningTree, SpiralStcVisitsEveryFreeSubCellExactlyOnce) {
  // Sub-cells s = 0.1 m with centres at 0.05 + 0.1 k (and two planning margins); windows cover
  // whole 2 x 2 mega-cells (their edges 0.1 m from the nearest free centres), so no mega-cell is
  // partially blocked. The walls are 1 cm more than a multiple of s: on one exactly a multiple,
  // the last column and row would lie on F's exact far edge, and are dropped (see the planner).
  const ToolParams tool{0.1, 0.0};
  const std::vector<Wall> walls = {
      rectWall(2.01, 1.21),
      rectWall(2.01, 1.21, {rect(0.85, 0.45, 0.3, 0.3)}),
      rectWall(3.21, 2.01, {rect(0.45, 0.45, 0.3, 0.7), rect(1.65, 0.05, 0.7, 0.3), rect(2.45, 1.25, 0.3, 0.3)}),
  };
  for (const Wall& wall : walls)
    for (const char* tree : {"dfs", "mst"}) {
      const PlanResult r = planWith(wall, tool, {{"variant", "spiral-stc"}, {"tree", tree}, {"waypoint_per_cell", "true"}, {"boundary_loop", "false"}});
      ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
      ASSERT_TRUE(test::isValidPath(wall, tool, r.path));
      EXPECT_EQ(r.stats.at("partially_blocked_sub_cells"), 0.0) << "the wall is built without them";
      std::set<std::pair<long, long>> visited;
      for (const Point& p : r.path.waypoints)
        EXPECT_TRUE(visited.insert({std::lround(p.x * 1000), std::lround(p.y * 1000)}).second)
            << "sub-cell (" << p.x << ", " << p.y << ") visited twice, tree " << tree;
      EXPECT_EQ(static_cast<double>(visited.size()), r.stats.at("free_cells"));
      EXPECT_EQ(static_cast<double>(visited.size()), 4.0 * r.stats.at("mega_cells"));
      for (bool on : r.path.tool_on) EXPECT_TRUE(on) << "one closed walk around the tree, no transits";
      for (std::size_t i = 1; i < r.path.waypoints.size(); ++i)  // every move is to a neighbouring sub-cell
        EXPECT_NEAR(distance(r.path.waypoints[i - 1], r.path.waypoints[i]), 0.1, 1e-3);
    }
}

TEST(SpanningTree, AWaypointOnlyWhereTheWalkTurnsIsTheSamePath) {
  // The default path keeps a waypoint only where the walk turns or the tool switches: the same
  // moves as a waypoint per cell, so the same length, coverage and overlap; its waypoints are a
  // subsequence of the per-cell ones.
  const ToolParams tool{0.1, 0.02};
  std::vector<Wall> walls = {loadWallFile(test::sourcePath("datasets/canonical/seed_10x10_5obs.json"))};
  for (unsigned seed = 1; seed <= 5; ++seed) walls.push_back(test::randomWall(seed));
  for (const Wall& wall : walls)
    for (const char* variant : {"return", "short-branches-first", "spiral-stc"}) {
      const PlanResult few = planWith(wall, tool, {{"variant", variant}});
      const PlanResult all = planWith(wall, tool, {{"variant", variant}, {"waypoint_per_cell", "true"}});
      ASSERT_EQ(few.status, all.status) << wall.name << " " << variant;
      if (!few.hasPath()) continue;
      EXPECT_LT(few.path.waypoints.size(), all.path.waypoints.size()) << wall.name << " " << variant;
      const PathMetrics a = computeMetrics(wall, tool, few.path), b = computeMetrics(wall, tool, all.path);
      EXPECT_NEAR(a.lengths.total, b.lengths.total, 1e-9 * b.lengths.total) << wall.name << " " << variant;
      EXPECT_NEAR(a.lengths.cover, b.lengths.cover, 1e-9 * b.lengths.total) << wall.name << " " << variant;
      EXPECT_NEAR(a.coverage.coverage_reachable, b.coverage.coverage_reachable, 1e-9) << wall.name << " " << variant;
      EXPECT_NEAR(a.passes.overlap, b.passes.overlap, 1e-9) << wall.name << " " << variant;
      std::size_t k = 0;
      for (const Point& p : few.path.waypoints) {
        while (k < all.path.waypoints.size() && !(all.path.waypoints[k] == p)) ++k;
        ASSERT_LT(k, all.path.waypoints.size()) << wall.name << " " << variant << ": waypoint not on the per-cell path";
      }
    }
}

TEST(SpanningTree, PartiallyBlockedMegaCellsAreStillCovered) {
  // A window that cuts through mega-cells: their free sub-cells are covered by ordinary trees.
  const ToolParams tool{0.1, 0.0};
  const Wall wall = rectWall(2.01, 1.21, {rect(0.75, 0.35, 0.3, 0.3)});
  const PlanResult stc = planWith(wall, tool, {{"variant", "spiral-stc"}, {"waypoint_per_cell", "true"}, {"boundary_loop", "false"}});
  const PlanResult plain = planWith(wall, tool, {{"variant", "stop"}, {"boundary_loop", "false"}});
  ASSERT_EQ(stc.status, PlanStatus::Ok);
  EXPECT_GT(stc.stats.at("partially_blocked_sub_cells"), 0.0);
  std::set<std::pair<long, long>> cells;
  for (const Point& p : stc.path.waypoints) cells.insert({std::lround(p.x * 1000), std::lround(p.y * 1000)});
  EXPECT_EQ(static_cast<double>(cells.size()), stc.stats.at("free_cells")) << "every free sub-cell is visited";
  EXPECT_GE(coverage(wall, tool, stc.path).coverage_reachable, coverage(wall, tool, plain.path).coverage_reachable - 1e-9);
}

TEST(SpanningTree, TheGridPitchIsExactlyTheToolWidth) {
  // Issue "planners at the quality frontier": version 2 fitted its pitch to the bounding box
  // (0.0999959 m instead of 0.1), so cells meant to sit on F's edge landed outside it.
  const ToolParams tool{0.05, 0.02};
  const Wall wall = loadWallFile(test::sourcePath("datasets/canonical/seed_10x10_5obs.json"));
  for (const char* variant : {"short-branches-first", "spiral-stc"})
    for (const char* loop : {"true", "false"}) {
      const PlanResult r = planWith(wall, tool, {{"variant", variant}, {"boundary_loop", loop}});
      ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
      EXPECT_EQ(r.stats.at("grid_spacing_x"), 0.05) << variant << " loop " << loop;
      EXPECT_EQ(r.stats.at("grid_spacing_y"), 0.05) << variant << " loop " << loop;
    }
}

TEST(SpanningTree, CentresOnFsExactEdgeAreMeasuredNotDropped) {
  // Without the loop the first column and row of centres lie 2 micrometres inside F's exact edge,
  // which is inside F's conservative polygon's 55-micrometre margin: only the exact measurement
  // keeps them. A 2.01 m x 1.21 m wall at s = 0.1, c = 0: F spans [0.05, 1.96] x [0.05, 1.16],
  // so centres at 0.05 + 0.1 k fit 20 columns and 12 rows: 240 cells, every one free.
  const ToolParams tool{0.1, 0.0};
  const PlanResult r = planWith(rectWall(2.01, 1.21), tool, {{"boundary_loop", "false"}, {"waypoint_per_cell", "true"}});
  ASSERT_EQ(r.status, PlanStatus::Ok) << r.reason;
  EXPECT_EQ(r.stats.at("free_cells"), 240.0);
  EXPECT_TRUE(test::isValidPath(rectWall(2.01, 1.21), tool, r.path));
  double min_x = INFINITY, min_y = INFINITY;
  for (const Point& p : r.path.waypoints) min_x = std::min(min_x, p.x), min_y = std::min(min_y, p.y);
  EXPECT_NEAR(min_x, 0.05, 1e-5);
  EXPECT_NEAR(min_y, 0.05, 1e-5);
}

TEST(SpanningTree, TheBoundaryLoopPaintsWhatTheCellsLeave) {
  // The L-shaped wall: version 2 lost a 0.1 m strip along both inner edges (coverage
  // 0.951). With the loop (the default) the cells start where its band ends; on every random
  // and conformance wall the loop never loses coverage, and the median is at least 0.98 (the
  // issue's target for every family but narrow).
  const ToolParams tool{0.1, 0.02};
  Wall l;
  l.name = "l-shape";
  l.boundary = {{0, 0}, {4, 0}, {4, 1}, {2, 1}, {2, 3}, {0, 3}};
  const PlanResult on_l = planWith(l, tool, {});
  ASSERT_EQ(on_l.status, PlanStatus::Ok) << on_l.reason;
  EXPECT_TRUE(test::isValidPath(l, tool, on_l.path));
  EXPECT_GE(coverage(l, tool, on_l.path).coverage_reachable, 0.99);

  std::vector<Wall> walls{l};
  for (unsigned seed = 1; seed <= 25; ++seed) walls.push_back(test::randomWall(seed));
  for (const std::string& f : test::conformanceWallFiles()) walls.push_back(loadWallFile(f));
  std::vector<double> with;
  for (const Wall& wall : walls)
    for (const char* variant : {"short-branches-first", "spiral-stc"}) {
      const PlanResult loop = planWith(wall, tool, {{"variant", variant}});
      const PlanResult grid = planWith(wall, tool, {{"variant", variant}, {"boundary_loop", "false"}});
      if (!loop.hasPath()) continue;
      ASSERT_TRUE(test::isValidPath(wall, tool, loop.path)) << wall.name << " " << variant;
      const double c_loop = coverage(wall, tool, loop.path).coverage_reachable;
      if (grid.hasPath()) {
        EXPECT_GE(c_loop, coverage(wall, tool, grid.path).coverage_reachable - 1e-9) << wall.name << " " << variant;
      }
      if (std::string(variant) == "short-branches-first") with.push_back(c_loop);
    }
  ASSERT_GE(with.size(), 30u);
  std::sort(with.begin(), with.end());
  EXPECT_GE(with[with.size() / 2], 0.98);
}

TEST(AdaptiveResolution, BeatsTheFixedGridOnCoverageWallOnEveryWall) {
  // Residential walls are where obstacles (doors, windows, sockets, switches) dominate.
  const ToolParams tool{0.1, 0.02};
  for (std::uint64_t i = 0; i < 30; ++i) {
    const Wall wall = generateWall("residential", 1, i);
    const PlanResult grid = planWith(wall, tool, {});
    const PlanResult adaptive = planWith(wall, tool, {}, "adaptive-resolution");
    ASSERT_TRUE(adaptive.hasPath()) << adaptive.reason;
    if (!grid.hasPath()) continue;
    EXPECT_GT(coverage(wall, tool, adaptive.path).coverage_wall, coverage(wall, tool, grid.path).coverage_wall) << wall.name;
  }
}

TEST(AdaptiveResolution, LeavesAreLargeInTheOpenAndFineNearObstacles) {
  const ToolParams tool{0.05, 0.02};
  const Wall open = rectWall(6.4, 6.4);
  const PlanResult r = planWith(open, tool, {}, "adaptive-resolution");
  ASSERT_EQ(r.status, PlanStatus::Ok);
  EXPECT_GE(r.stats.at("largest_leaf_cells"), 32.0) << "the open middle of an empty wall is a few big leaves";
  EXPECT_LT(r.stats.at("open_leaves") + r.stats.at("fine_leaves"), 1000.0) << "far fewer leaves than its 16384 cells";
  EXPECT_LE(r.stats.at("fine_leaves"), 4.0 * 128.0) << "single cells only along the edge (128 cells a side)";
  const Wall busy = rectWall(6.4, 6.4, {rect(1, 1, 1, 1), test::circle(4, 4, 0.5)});
  const PlanResult b = planWith(busy, tool, {}, "adaptive-resolution");
  ASSERT_EQ(b.status, PlanStatus::Ok);
  EXPECT_GT(b.stats.at("fine_leaves"), 100.0) << "obstacle edges split the tree down to single cells";
}

TEST(AdaptiveResolution, DenseWaypointsFollowTheDistanceToObstacles) {
  const ToolParams tool{0.1, 0.02};
  const Wall wall = rectWall(5, 3, {rect(2, 1, 1, 1)});
  const PlanResult sparse = planWith(wall, tool, {}, "adaptive-resolution");
  const PlanResult dense = planWith(wall, tool, {{"dense_waypoints", "true"}}, "adaptive-resolution");
  ASSERT_EQ(dense.status, PlanStatus::Ok);
  EXPECT_GT(dense.path.waypoints.size(), 20 * sparse.path.waypoints.size());
  EXPECT_TRUE(test::isValidPath(wall, tool, dense.path));
  // The same geometry, but where it follows F's round boundary: the sparse path as arcs, the dense
  // one as F's chords (within 5e-5 m of them; 4.9e-5 m shorter in all).
  EXPECT_TRUE(sparse.path.hasArcs());
  EXPECT_FALSE(dense.path.hasArcs());
  EXPECT_NEAR(pathLengths(dense.path).total, pathLengths(sparse.path).total, 1e-4) << "same geometry";
  EXPECT_NEAR(coverage(wall, tool, dense.path).coverage_reachable, coverage(wall, tool, sparse.path).coverage_reachable, 1e-6);
  // Every step: at most 5 mm near the window or the wall edge (gap <= 0.1 m from the tool's
  // edge), at most 1 cm within 0.5 m, at most 2 cm elsewhere.
  const ClearanceField field(wall);
  int near = 0, far = 0;
  for (std::size_t i = 0; i + 1 < dense.path.waypoints.size(); ++i) {
    const Point a = dense.path.waypoints[i], b = dense.path.waypoints[i + 1];
    const SegmentClearance m = field.measure(a, b);
    const double gap = std::fmin(m.boundary_distance, m.obstacle_distance) - tool.radius();
    const double step = distance(a, b);
    if (gap <= 0.1) {
      EXPECT_LE(step, 0.005 + 1e-9);
      ++near;
    } else if (gap <= 0.5) {
      EXPECT_LE(step, 0.01 + 1e-9);
    } else {
      EXPECT_LE(step, 0.02 + 1e-9);
      ++far;
    }
  }
  EXPECT_GT(near, 100);
  EXPECT_GT(far, 10);
}

TEST(SweepDirectionSearch, FindsTheLongSideOfARotatedWallAndBeatsEveryFixedDirection) {
  // A 6 m x 1.5 m wall turned by 30 degrees: rows along the long side turn least.
  const Wall wall = test::turnedRectWall(6.0, 1.5, 30.0);
  const ToolParams tool{0.1, 0.02};
  const PlanResult searched = planWith(wall, tool, {{"direction_search", "true"}}, "zigzag");
  ASSERT_EQ(searched.status, PlanStatus::Ok);
  EXPECT_NEAR(searched.stats.at("sweep_angle_deg"), 30.0, 1.0);
  EXPECT_TRUE(test::isValidPath(wall, tool, searched.path));
  EXPECT_GE(searched.stats.at("direction_evaluations"), 36.0);
  const double best = sweepCost(searched.path, 1.0);
  EXPECT_NEAR(best, searched.stats.at("direction_cost"), 1e-9);
  for (const char* angle : {"0", "45", "90", "135"}) {
    const PlanResult fixed = planWith(wall, tool, {{"sweep_angle", angle}}, "zigzag");
    EXPECT_LE(best, sweepCost(fixed.path, 1.0) + 1e-9) << angle;
  }
  const PlanResult again = planWith(wall, tool, {{"direction_search", "true"}}, "zigzag");
  EXPECT_EQ(again.stats.at("sweep_angle_deg"), searched.stats.at("sweep_angle_deg")) << "deterministic";
}

// objective: time minimises the problem's time model: the cost the search reports is the path's
// duration under that model.
TEST(SweepDirectionSearch, TheTimeObjectiveMinimisesTheProblemsClock) {
  const std::vector<Wall> walls = {test::turnedRectWall(6.0, 1.5, 30.0), generateWall("industrial", 5, 0),
                                   generateWall("facade", 5, 0)};
  const ToolParams tool{0.1, 0.02};
  MotionLimits clock;
  clock.speed = 3.0;
  clock.acceleration = 1.0;
  clock.stops = MotionLimits::Stops::Waypoints;
  for (const char* planner : {"zigzag", "trapezoidal", "boustrophedon"})
    for (const Wall& wall : walls) {
      const PlannerInfo& info = findPlanner(planner);
      Problem problem;
      problem.wall = &wall;
      problem.tool = tool;
      problem.motion = clock;
      problem.params = resolveParams(info, {{"direction_search", "true"}, {"objective", "time"}});
      const PlanResult timed = runPlanner(info, problem, Budget());
      ASSERT_EQ(timed.status, PlanStatus::Ok) << planner << " " << wall.name;
      EXPECT_TRUE(test::isValidPath(wall, tool, timed.path)) << planner << " " << wall.name;
      EXPECT_NEAR(timed.stats.at("direction_cost"), motion(timed.path, clock).duration_s, 1e-9);
      problem.params = resolveParams(info, {{"direction_search", "true"}, {"objective", "length"}});
      const PlanResult by_length = runPlanner(info, problem, Budget());
      ASSERT_EQ(by_length.status, PlanStatus::Ok);
      // Each objective plans only its two best estimated directions, so the time objective can miss
      // the length objective's pick by a little (on the default experiment's walls it was faster
      // on 69-74 and slower on 8-11 of 327); never by much.
      EXPECT_LE(motion(timed.path, clock).duration_s, motion(by_length.path, clock).duration_s * 1.05)
          << planner << " " << wall.name;
    }
}

}  // namespace
}  // namespace coverbench
