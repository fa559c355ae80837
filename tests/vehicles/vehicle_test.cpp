// Vehicle models (docs/vehicles.md): the gantry's lifted moves as the fast engine, the exact judge,
// the duration model, the path builder, plan files and experiment configs see them, against
// hand-computed values; and every planner covering every free component under a gantry.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::CommandRun;
using test::rect;
using test::rectWall;

const ToolParams kTool{0.2, 0.05};  // r = 0.1, c = 0.05

VehicleModel gantry(double lift_s = 1.0, double lower_s = 1.0) {
  VehicleModel v;
  v.kind = VehicleModel::Kind::Gantry;
  v.lift_s = lift_s;
  v.lower_s = lower_s;
  return v;
}

Path path(Point start, std::vector<std::pair<Point, bool>> moves) {
  Path p;
  p.moveTo(start, false);
  for (const auto& [q, on] : moves) p.moveTo(q, on);
  return p;
}

// A 4 x 2 m wall with a window from x 1.5 to 2.5, y 0.5 to 1.5. The path paints left of the window,
// crosses it with the tool off, and paints right of it. Nearest the window the disk keeps
// 0.2 - r = 0.1 m; nearest the wall's edge 0.3 - r = 0.2 m.
const Wall kWindowWall = rectWall(4, 2, {rect(1.5, 0.5, 1, 1)});
const Path kOverTheWindow = path({0.3, 1.0}, {{{1.3, 1.0}, true}, {{2.7, 1.0}, false}, {{3.7, 1.0}, true}});

TEST(Gantry, ALiftedMoveMayCrossAWindowADraggedToolMayNot) {
  const Validity dragged = checkValidity(kWindowWall, kTool, kOverTheWindow);
  EXPECT_FALSE(dragged.valid);
  EXPECT_EQ(dragged.too_close, 1u);
  EXPECT_EQ(dragged.violating, std::vector<std::size_t>{1});
  EXPECT_NEAR(dragged.min_clearance, -0.1, 1e-12);  // the centre crosses the window: -r

  const Validity lifted = checkValidity(kWindowWall, kTool, kOverTheWindow, gantry());
  EXPECT_TRUE(lifted.valid);
  EXPECT_EQ(lifted.violations, 0u);
  EXPECT_NEAR(lifted.min_clearance, 0.1, 1e-12);  // over the lowered segments only
  EXPECT_NEAR(lifted.min_boundary_gap, 0.2, 1e-12);

  EXPECT_FALSE(judge::judgeValidity(kWindowWall, kTool, kOverTheWindow).valid);
  EXPECT_TRUE(judge::judgeValidity(kWindowWall, kTool, kOverTheWindow, gantry()).valid);
}

TEST(Gantry, TheToolOnStillKeepsItsClearance) {
  Path painted = kOverTheWindow;
  painted.tool_on[1] = true;  // painting across the window
  const Validity v = checkValidity(kWindowWall, kTool, painted, gantry());
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.too_close, 1u);
  EXPECT_EQ(v.violating, std::vector<std::size_t>{1});
  EXPECT_FALSE(judge::judgeValidity(kWindowWall, kTool, painted, gantry()).valid);
}

TEST(Gantry, LiftedMovesStayInTheWallsBoundingBox) {
  // An L-shaped wall: a lifted move across the notch leaves the wall but not its bounding box.
  Wall l;
  l.name = "L";
  l.boundary = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};
  const Path across = path({3.5, 0.5}, {{{0.5, 2.5}, false}});
  EXPECT_FALSE(checkValidity(l, kTool, across).valid);
  EXPECT_EQ(checkValidity(l, kTool, across).outside_boundary, 1u);
  EXPECT_TRUE(checkValidity(l, kTool, across, gantry()).valid);
  EXPECT_TRUE(judge::judgeValidity(l, kTool, across, gantry()).valid);

  // Ending 0.05 m from the box's right side: the disk (r = 0.1) pokes 0.05 m out.
  const Path out = path({3.5, 0.5}, {{{3.95, 0.5}, false}});
  const Validity v = checkValidity(l, kTool, out, gantry());
  EXPECT_FALSE(v.valid);
  EXPECT_EQ(v.outside_boundary, 1u);
  EXPECT_EQ(judge::judgeValidity(l, kTool, out, gantry()).outside_boundary, 1u);
  // Exactly touching the box's side is allowed (the disk stays inside, closed).
  EXPECT_TRUE(checkValidity(l, kTool, path({3.5, 0.5}, {{{3.9, 0.5}, false}}), gantry()).valid);
  EXPECT_TRUE(judge::judgeValidity(l, kTool, path({3.5, 0.5}, {{{3.75, 0.5}, false}}), gantry()).valid);
}

TEST(Gantry, DurationStopsAtEveryLiftAndAddsItsTimes) {
  // Three 1 m pieces in a straight line: on, off, on. v = 0.3 m/s, a = 0.5 m/s^2.
  const Path p = path({0, 0}, {{{1, 0}, true}, {{2, 0}, false}, {{3, 0}, true}});
  // Holonomic: one 3 m run, 3 / 0.3 + 0.3 / 0.5 = 10.6 s.
  const Motion dragged = motion(p);
  EXPECT_NEAR(dragged.duration_s, 10.6, 1e-12);
  EXPECT_EQ(dragged.lifts, 0u);
  // Gantry (lift 2 s, lower 1 s): three 1 m runs of 1 / 0.3 + 0.6 s each, and two painted runs,
  // each lowered and lifted: 3 * (10 / 3 + 0.6) + 2 * 3 = 17.8 s.
  const Motion lifted = motion(p, MotionLimits{}, gantry(2.0, 1.0));
  EXPECT_NEAR(lifted.duration_s, 17.8, 1e-12);
  EXPECT_EQ(lifted.lifts, 2u);
  EXPECT_EQ(lifted.turns, 0u);
  // Free lifts: only the stops remain.
  EXPECT_NEAR(motion(p, MotionLimits{}, gantry(0.0, 0.0)).duration_s, 11.8, 1e-12);
}

TEST(Gantry, TheTimelineWaitsWhereTheToolIsLoweredAndLifted) {
  const Path p = path({0, 0}, {{{1, 0}, true}, {{2, 0}, false}, {{3, 0}, true}});
  const Timeline t = timeline(p, MotionLimits{}, gantry(2.0, 1.0));  // lift 2 s, lower 1 s
  // Lowered before each painted run, lifted before the move after it and at the end; every 1 m
  // run takes 1 / 0.3 + 0.6 s.
  const double run = 1.0 / 0.3 + 0.6;
  EXPECT_EQ(t.wait_s, (std::vector<double>{1.0, 2.0, 1.0}));
  ASSERT_EQ(t.arrive_s.size(), 4u);
  EXPECT_NEAR(t.arrive_s[1], 1.0 + run, 1e-12);
  EXPECT_NEAR(t.arrive_s[2], 1.0 + run + 2.0 + run, 1e-12);
  EXPECT_NEAR(t.arrive_s[3], 1.0 + run + 2.0 + run + 1.0 + run, 1e-12);
  EXPECT_NEAR(t.end_s, t.arrive_s[3] + 2.0, 1e-12);
  EXPECT_NEAR(t.end_s, motion(p, MotionLimits{}, gantry(2.0, 1.0)).duration_s, 1e-12);
}

TEST(Gantry, ThePathBuilderCrossesStraightWithTheToolLifted) {
  const Point a{1.0, 1.0}, b{3.0, 1.0};  // either side of the window
  Workspace dragged_ws(kWindowWall, kTool);
  PathBuilder dragged(dragged_ws);
  dragged.start(a);
  ASSERT_TRUE(dragged.moveTo(b, true));
  EXPECT_GT(dragged.path().waypoints.size(), 2u) << "routed around the window";
  EXPECT_EQ(dragged.transits(), 1u);
  EXPECT_EQ(dragged.liftedCrossings(), 0u);

  Workspace lifted_ws(kWindowWall, kTool, gantry());
  PathBuilder lifted(lifted_ws);
  lifted.start(a);
  ASSERT_TRUE(lifted.moveTo(b, true));
  ASSERT_EQ(lifted.path().waypoints.size(), 2u);
  EXPECT_FALSE(lifted.path().tool_on[0]) << "the tool is lifted, not painting";
  EXPECT_EQ(lifted.transits(), 0u);
  EXPECT_EQ(lifted.liftedCrossings(), 1u);
  // A free straight move keeps the tool as asked.
  ASSERT_TRUE(lifted.moveTo({3.0, 1.8}, true));
  EXPECT_TRUE(lifted.path().tool_on[1]);
  EXPECT_TRUE(test::isValidPath(kWindowWall, kTool, lifted.path(), gantry()));
}

TEST(Gantry, EveryPlannerCoversBothSidesOfAGapNarrowerThanTheTool) {
  const Wall split = loadWallFile(test::sourcePath("datasets/conformance/narrow_gap_disconnected.json"));
  const ToolParams tool{0.1, 0.02};
  for (const PlannerInfo& info : registeredPlanners()) {
    Problem problem;
    problem.wall = &split;
    problem.tool = tool;
    problem.vehicle = gantry();
    problem.params = resolveParams(info, {});
    const PlanResult r = runPlanner(info, problem, Budget(std::chrono::seconds(60)));
    EXPECT_EQ(r.status, PlanStatus::Ok) << info.name << ": " << r.reason;
    EXPECT_EQ(r.free_components, 2u) << info.name;
    EXPECT_EQ(r.covered_components, 2u) << info.name;
    EXPECT_TRUE(r.reason.empty()) << info.name << ": " << r.reason;
    EXPECT_GE(r.stats.at("lifted_crossings"), 1.0) << info.name;
    ASSERT_TRUE(test::isValidPath(split, tool, r.path, gantry())) << info.name;
    EXPECT_FALSE(checkValidity(split, tool, r.path).valid) << info.name << ": a dragged tool could not do this";
    const PathMetrics m = computeMetrics(split, tool, r.path, gantry());
    EXPECT_GE(m.coverage.coverage_reachable, info.min_coverage_reachable) << info.name;
    EXPECT_GE(m.motion.lifts, 2u) << info.name;
  }
}

// Under a gantry every planner covers every free component of walls of the narrow and random
// families (the default experiment's generators and seed), every path valid under the gantry's
// rules by both the fast engine and the exact judge, and keeps its declared minimum coverage there
// too (the conformance suite checks it where F is connected). Where the fast figure falls short,
// the exact judge decides: narrow-s1-0013 has a gap of exactly 2 r + c (0.12 m) under an obstacle,
// a neck of F of zero width that the fast engine's integer polygons keep (with a band of R around
// it) and the exact doubles do not; the judge's interval spans both.
class GantryFamilies : public testing::TestWithParam<std::string> {};

TEST_P(GantryFamilies, EveryPlannerCoversEveryComponentOfNarrowAndRandomWalls) {
  const PlannerInfo& info = findPlanner(GetParam());
  // As experiments/gantry.yaml runs them: the grid planners with their corner spurs.
  const bool grid = info.name == "spanning-tree" || info.name == "adaptive-resolution";
  const Params params = resolveParams(info, grid ? std::vector<std::pair<std::string, std::string>>{{"corner_spurs", "true"}}
                                                 : std::vector<std::pair<std::string, std::string>>{});
  const ToolParams tool{0.1, 0.02};
  std::size_t split_walls = 0;
  for (const char* family : {"narrow", "random"}) {
    std::vector<double> covered;
    for (std::size_t i = 0; i < 16; ++i) {
      const Wall wall = generateWall(family, 1, i);
      Problem problem;
      problem.wall = &wall;
      problem.tool = tool;
      problem.vehicle = gantry();
      problem.params = params;
      const PlanResult r = runPlanner(info, problem, Budget(std::chrono::seconds(60)));
      ASSERT_TRUE(r.hasPath()) << wall.name << ": " << r.reason;
      EXPECT_EQ(r.status, PlanStatus::Ok) << wall.name << ": " << r.reason;
      EXPECT_EQ(r.covered_components, r.free_components) << wall.name;
      split_walls += r.free_components > 1;
      ASSERT_TRUE(test::isValidPath(wall, tool, r.path, gantry())) << wall.name;
      const PathMetrics m = computeMetrics(wall, tool, r.path, gantry());
      covered.push_back(m.coverage.coverage_reachable);
      if (m.coverage.coverage_reachable >= info.min_coverage_reachable) continue;
      const judge::ExactCoverage exact = judge::judgeCoverage(wall, tool, r.path);
      EXPECT_GE(exact.coverage_reachable.upper, info.min_coverage_reachable)
          << wall.name << ": fast " << m.coverage.coverage_reachable << ", exact [" << exact.coverage_reachable.lower
          << ", " << exact.coverage_reachable.upper << "]";
    }
    // Issue 16's target: a median of at least 0.999 over the family's walls.
    std::sort(covered.begin(), covered.end());
    EXPECT_GE((covered[7] + covered[8]) / 2.0, 0.999) << family << " median";
  }
  EXPECT_GE(split_walls, 16u) << "most narrow walls have several free components (what the gantry is for)";
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, GantryFamilies, testing::ValuesIn(test::plannerNames()), test::plannerTestName);

class VehicleFiles : public test::CommandTest {
 protected:
  std::string loadError(const std::string& text) {
    return test::inputError([&] { loadPlanFile(write("plan.json", text)); });
  }
  std::string configError(const std::string& text) {
    return test::inputError([&] { loadExperimentConfig(write("exp.yaml", text)); });
  }
};

TEST_F(VehicleFiles, PlanFilesCarryAGantryAndHolonomicOnesStayAsTheyWere) {
  PlanFile plan;
  plan.planner = "zigzag";
  plan.wall = "w";
  plan.result.status = PlanStatus::Ok;
  plan.result.path = kOverTheWindow;
  const std::string holonomic = planFileJson(plan);
  EXPECT_EQ(holonomic.find("vehicle"), std::string::npos);
  plan.vehicle = gantry(2.5, 0.5);
  const std::string lifted = planFileJson(plan);
  EXPECT_NE(lifted.find(" \"vehicle\": {\"model\":\"gantry\",\"lift_s\":2.5,\"lower_s\":0.5},\n"), std::string::npos) << lifted;
  const LoadedPlan back = loadPlanFile(write("p.json", lifted));
  ASSERT_TRUE(back.vehicle.has_value());
  EXPECT_EQ(back.vehicle->kind, VehicleModel::Kind::Gantry);
  EXPECT_EQ(back.vehicle->lift_s, 2.5);
  EXPECT_EQ(back.vehicle->lower_s, 0.5);
  EXPECT_FALSE(loadPlanFile(write("h.json", holonomic)).vehicle.has_value());

  const std::string path = R"("waypoints": [[0.3, 1.0], [1.3, 1.0]], "tool_on": [true])";
  EXPECT_NE(loadError("{" + path + R"(, "vehicle": {"model": "tank"}})").find("plan.json: vehicle.model: must be"),
            std::string::npos);
  EXPECT_NE(loadError("{" + path + R"(, "vehicle": {"model": "gantry", "lift_s": -1}})")
                .find("plan.json: vehicle.lift_s: must be in [0, 3600] s, got -1"),
            std::string::npos);
  EXPECT_NE(loadError("{" + path + R"(, "vehicle": "gantry"})").find("plan.json: vehicle: must be an object"),
            std::string::npos);
}

TEST_F(VehicleFiles, ConfigsNameAVehicleAndOnlyAGantryChangesTheRunKeys) {
  const std::string base = "name: v\noutput: out\ndatasets:\n  - family: narrow\n    count: 1\n    seed: 1\n"
                           "planners:\n  - zigzag\n";
  const ExperimentConfig plain = loadExperimentConfig(write("a.yaml", base));
  const ExperimentConfig holonomic = loadExperimentConfig(write("b.yaml", base + "vehicle:\n  model: holonomic\n"));
  const ExperimentConfig lifted =
      loadExperimentConfig(write("c.yaml", base + "vehicle:\n  model: gantry\n  lift_s: 2\n  lower_s: 0.5\n"));
  EXPECT_TRUE(plain.vehicle.isDefault());
  EXPECT_TRUE(holonomic.vehicle.isDefault());
  ASSERT_EQ(lifted.vehicle.kind, VehicleModel::Kind::Gantry);
  EXPECT_EQ(lifted.vehicle.lift_s, 2.0);
  EXPECT_EQ(lifted.vehicle.lower_s, 0.5);
  const std::vector<WallEntry> walls = loadWalls(plain);
  const std::vector<RunSpec> a = expandRuns(plain, walls), b = expandRuns(holonomic, walls), c = expandRuns(lifted, walls);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].key, b[0].key) << "naming the default changes nothing";
  EXPECT_NE(a[0].key, c[0].key);

  // The gantry's run: covers both parts of the narrow wall, valid by its rules, timed with lifts.
  const RunRecord rec = executeRun(c[0]);
  EXPECT_EQ(rec.status, RunStatus::Ok) << rec.reason;
  EXPECT_TRUE(rec.valid);
  EXPECT_GE(rec.stats.at("lifted_crossings"), 1.0);

  EXPECT_NE(configError(base + "vehicle:\n  model: tank\n").find("exp.yaml:10: vehicle.model: must be holonomic, gantry or car, not 'tank'"),
            std::string::npos);
  EXPECT_NE(configError(base + "vehicle:\n  model: gantry\n  lift_s: -2\n").find("vehicle.lift_s"), std::string::npos);
  EXPECT_NE(configError(base + "vehicle:\n  lift_s: 2\n").find("vehicle.model: missing"), std::string::npos);
  EXPECT_NE(configError(base + "vehicle:\n  model: holonomic\n  lift_s: 2\n").find("belong to a gantry"), std::string::npos);
  EXPECT_NE(configError(base + "vehicle:\n  model: gantry\n  speed: 2\n").find("vehicle.speed"), std::string::npos);
}

// As a user runs it: plan for a gantry, score the plan file (which carries the vehicle), override it.
class VehicleCommands : public test::CommandTest {};

TEST_F(VehicleCommands, PlanAndScoreForAGantry) {
  const std::string wall = test::sourcePath("datasets/conformance/narrow_gap_disconnected.json");
  const std::string plan = (dir_ / "plan.json").string(), svg = (dir_ / "plan.svg").string();
  CommandRun r = run("plan --wall " + wall + " --planner zigzag --vehicle gantry --lift-s 2 --out " + plan + " --svg " + svg);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = slurp(plan);
  EXPECT_NE(text.find(" \"vehicle\": {\"model\":\"gantry\",\"lift_s\":2.0,\"lower_s\":1.0},\n"), std::string::npos);
  EXPECT_NE(text.find("\"status\": \"ok\""), std::string::npos);
  EXPECT_NE(slurp(svg).find("class=\"lifted\""), std::string::npos);
  std::string out;
  r = run("metrics --wall " + wall + " --plan " + plan, &out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(out.find("\"valid\": true"), std::string::npos);
  r = run("metrics --wall " + wall + " --plan " + plan + " --vehicle holonomic --judge exact", &out);
  EXPECT_EQ(r.exit_code, 3) << "judged as a dragged tool the lifted crossings are violations";
  EXPECT_NE(out.find("\"valid\": false"), std::string::npos);

  r = run("plan --wall " + wall + " --planner zigzag --vehicle tank --out " + plan);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "coverbench: --vehicle: vehicle: must be holonomic, gantry or car, not 'tank'\n");
  r = run("plan --wall " + wall + " --planner zigzag --lift-s 2 --out " + plan);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("belong to a gantry"), std::string::npos) << r.err;
}

TEST(Gantry, PicturesDrawLiftedMovesAsLifted) {
  const std::string dragged = pathPicture(kWindowWall, kTool, VehicleModel{}, kOverTheWindow, "t");
  const std::string lifted = pathPicture(kWindowWall, kTool, gantry(), kOverTheWindow, "t");
  EXPECT_EQ(dragged.find("class=\"lifted\""), std::string::npos);
  EXPECT_NE(dragged.find("transit (tool off)"), std::string::npos);
  EXPECT_NE(dragged.find("class=\"violation\""), std::string::npos) << "a dragged tool crossing the window";
  EXPECT_NE(lifted.find("class=\"lifted\""), std::string::npos);
  EXPECT_NE(lifted.find("lifted (tool off)"), std::string::npos);
  EXPECT_EQ(lifted.find("class=\"violation\""), std::string::npos);
}

}  // namespace
}  // namespace coverbench
