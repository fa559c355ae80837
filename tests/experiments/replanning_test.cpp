// Replanning around surprises (docs/replanning.md): cutting a path, drawing the obstacles that
// appear, the detour and replan repairs against hand-computed cases, every planner's repaired
// paths valid on generated walls (fast engine and exact judge), configs, the database, the report
// data and the command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/replanning.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

using test::CommandRun;
using test::rect;
using test::rectWall;

const ToolParams kTool{0.1, 0.02};  // r = 0.05, r + c = 0.07

Path path(Point start, std::vector<std::pair<Point, bool>> moves) {
  Path p;
  p.moveTo(start, false);
  for (const auto& [q, on] : moves) p.moveTo(q, on);
  return p;
}

double length(const Path& p) {
  double total = 0.0;
  for (std::size_t i = 0; i < p.segments(); ++i) total += distance(p.waypoints[i], p.waypoints[i + 1]);
  return total;
}

TEST(CutPath, SplitsTheSegmentAtTheFractionOfTheLengthAndKeepsItsToolState) {
  // 2 m painted, then 1 m tool off: 3 m long.
  const Path p = path({0, 0}, {{{2, 0}, true}, {{2, 1}, false}});
  const PathCut half = cutPath(p, 0.5);  // at 1.5 m: on the painted segment
  EXPECT_EQ(half.position, (Point{1.5, 0}));
  EXPECT_DOUBLE_EQ(half.length, 1.5);
  ASSERT_EQ(half.executed.waypoints.size(), 2u);
  EXPECT_EQ(half.executed.waypoints[1], (Point{1.5, 0}));
  EXPECT_TRUE(half.executed.tool_on[0]);
  ASSERT_EQ(half.remainder.waypoints.size(), 3u);
  EXPECT_EQ(half.remainder.waypoints[0], (Point{1.5, 0}));
  EXPECT_TRUE(half.remainder.tool_on[0]) << "the cut segment's rest keeps the tool on";
  EXPECT_FALSE(half.remainder.tool_on[1]);

  const PathCut at_corner = cutPath(p, 2.0 / 3.0);  // exactly at (2, 0)
  EXPECT_EQ(at_corner.position, (Point{2, 0}));
  EXPECT_EQ(at_corner.executed.segments(), 1u);
  EXPECT_EQ(at_corner.remainder.segments(), 1u);
  EXPECT_FALSE(at_corner.remainder.tool_on[0]);

  const PathCut start = cutPath(p, 0.0), end = cutPath(p, 1.0);
  EXPECT_EQ(start.position, (Point{0, 0}));
  EXPECT_EQ(start.executed.segments(), 0u);
  EXPECT_EQ(start.remainder.segments(), 2u);
  EXPECT_EQ(end.position, (Point{2, 1}));
  EXPECT_EQ(end.remainder.segments(), 0u);
  EXPECT_DOUBLE_EQ(end.length, 3.0);
}

/// A zigzag over a 6 x 3 m wall with one window, as the planner makes it.
struct Planned {
  Wall wall = rectWall(6.0, 3.0, {rect(4.5, 1.0, 0.8, 0.8)});
  Path path;
  Planned() {
    const PlanResult r = test::planWith("zigzag", wall, kTool);
    EXPECT_EQ(r.status, PlanStatus::Ok) << r.reason;
    path = r.path;
  }
  /// The path cut at `fraction` with nothing appearing.
  Surprise unchanged(double fraction) const {
    Surprise s;
    s.cut = cutPath(path, fraction);
    s.wall = wall;
    return s;
  }
};

/// The problem on the surprise's wall with kTool.
Problem problemOn(const Surprise& s) {
  Problem problem;
  problem.wall = &s.wall;
  problem.tool = kTool;
  return problem;
}

TEST(Surprise, ObstaclesAreDrawnFromTheSeedAheadOfTheRobotAndKeepClearOfIt) {
  const Planned p;
  ReplanningSpec spec;
  spec.at = {0.4};
  spec.obstacles = 3;
  const Surprise a = makeSurprise(p.wall, kTool, p.path, 0.4, spec, 7);
  const Surprise again = makeSurprise(p.wall, kTool, p.path, 0.4, spec, 7);
  const Surprise other = makeSurprise(p.wall, kTool, p.path, 0.4, spec, 8);
  ASSERT_EQ(a.obstacles.size(), 3u);
  EXPECT_EQ(a.requested, 3u);
  EXPECT_EQ(wallToJson(a.wall), wallToJson(again.wall)) << "same seed, same obstacles";
  EXPECT_NE(wallToJson(a.wall), wallToJson(other.wall)) << "another seed, other obstacles";
  EXPECT_EQ(a.wall.obstacles.size(), p.wall.obstacles.size() + 3);
  const Box box = boundingBox(p.wall.boundary);
  for (const Obstacle& o : a.obstacles) {
    EXPECT_EQ(o.label.rfind("surprise: ", 0), 0u) << o.label;
    for (const Point& q : o.polygon) {
      EXPECT_EQ(q.x, std::round(q.x * 1000.0) / 1000.0) << "millimetres";
      EXPECT_GE(q.x, box.min_x);
      EXPECT_LE(q.x, box.max_x);
      EXPECT_GE(q.y, box.min_y);
      EXPECT_LE(q.y, box.max_y);
    }
    EXPECT_GT(distanceSegmentFilledRing(a.cut.position, a.cut.position, o.polygon), kTool.radius() + kTool.clearance)
        << "an obstacle never appears where the robot stands";
  }
  // Each is centred near the painted remainder: within half its size (plus the jitter) of it.
  for (const Obstacle& o : a.obstacles) {
    const Box b = boundingBox(o.polygon);
    double nearest = INFINITY;
    for (std::size_t i = 0; i < a.cut.remainder.segments(); ++i)
      if (a.cut.remainder.tool_on[i])
        nearest = std::min(nearest, distanceSegmentFilledRing(a.cut.remainder.waypoints[i], a.cut.remainder.waypoints[i + 1], o.polygon));
    EXPECT_EQ(nearest, 0.0) << "box " << b.min_x << " " << b.min_y << ": in the robot's way";
  }
  // Only the kinds asked for.
  spec.kinds = {SurpriseKind::Duct};
  for (const Obstacle& o : makeSurprise(p.wall, kTool, p.path, 0.4, spec, 3).obstacles) {
    EXPECT_EQ(o.label, "surprise: duct");
    const Box b = boundingBox(o.polygon);
    EXPECT_LE(std::min(b.width(), b.height()), 0.12 + 1e-9) << "a duct is thin";
  }
}

// One pass along y = 1 from x = 0.5 to 3.5 on a 4 x 2 wall; a 0.4 x 1 m obstacle appears across it
// at x 1.8 to 2.2. The tool (r + c = 0.07) can paint up to x = 1.73 and again from x = 2.27.
TEST(Detour, PaintsTheFreeStretchesOfABlockedPassAndGoesAroundTheObstacle) {
  const Wall wall = rectWall(4.0, 2.0);
  const Path plan = path({0.5, 1.0}, {{{3.5, 1.0}, true}});
  Surprise s;
  s.fraction = 0.1;
  s.cut = cutPath(plan, 0.1);  // at x = 0.8
  s.obstacles = {rect(1.8, 0.5, 0.4, 1.0)};
  s.wall = rectWall(4.0, 2.0, s.obstacles);
  Problem problem = problemOn(s);
  const Repair r = repairByDetour(s, problem);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.blocked_m, 0.54, 1e-5);
  EXPECT_TRUE(r.leftOut());
  EXPECT_EQ(r.transits, 1u);
  EXPECT_EQ(r.kept_moves, 1u);
  EXPECT_EQ(r.unreachable_moves, 0u);
  EXPECT_NE(r.reason.find("0.540 m of painting the obstacles block"), std::string::npos) << r.reason;
  // Painted: 0.5 to 1.73 and 2.27 to 3.5, exactly what is free.
  double painted = 0.0;
  for (std::size_t i = 0; i < r.path.segments(); ++i)
    if (r.path.tool_on[i]) painted += distance(r.path.waypoints[i], r.path.waypoints[i + 1]);
  EXPECT_NEAR(painted, 3.0 - 0.54, 2e-5);
  EXPECT_EQ(r.path.waypoints[r.cut_waypoint], (Point{0.8, 1.0}));
  EXPECT_TRUE(test::isValidPath(s.wall, kTool, r.repairedPart()));
  EXPECT_TRUE(test::isValidPath(wall, kTool, s.cut.executed));
  EXPECT_FALSE(checkValidity(wall, kTool, plan).violations) << "the original was valid";
  EXPECT_TRUE(checkValidity(s.wall, kTool, plan).violations) << "and crosses the new obstacle";

  // A gantry lifts over the obstacle instead of going around it (still painting only what is free).
  problem.vehicle.kind = VehicleModel::Kind::Gantry;
  const Repair lifted = repairByDetour(s, problem);
  EXPECT_EQ(lifted.transits, 0u);
  EXPECT_NEAR(lifted.blocked_m, 0.54, 1e-5);
  EXPECT_TRUE(test::isValidPath(s.wall, kTool, lifted.repairedPart(), problem.vehicle));
}

TEST(Detour, AnUnchangedWallRepairsToTheSamePath) {
  const Planned p;
  const Surprise s = p.unchanged(0.5);
  const Repair r = repairByDetour(s, problemOn(s));
  EXPECT_FALSE(r.leftOut());
  EXPECT_EQ(r.transits, 0u);
  // The plan's arcs are repaired as their chords (straightenedForReplanning).
  EXPECT_NEAR(length(r.path), length(straightenedForReplanning(p.path)), 1e-9);
  EXPECT_EQ(r.path.tool_on, [&] {  // the cut adds one waypoint inside a segment, or none
    Path joined = s.cut.executed;
    for (std::size_t i = 0; i < s.cut.remainder.segments(); ++i) joined.moveTo(s.cut.remainder.waypoints[i + 1], s.cut.remainder.tool_on[i]);
    return joined.tool_on;
  }());
}

TEST(Replan, KeepsOnlyMovesThatPaintSomethingNew) {
  const Planned p;
  Surprise s = p.unchanged(0.5);
  const Problem problem = problemOn(s);
  // Repaired from the same plan on an unchanged wall: the executed half's moves are dropped, the
  // rest kept; the repaired path paints what the original did.
  const Repair r = repairFromPlan(s, problem, p.path);
  ASSERT_TRUE(r.ok);
  EXPECT_FALSE(r.leftOut());
  const Path plan = straightenedForReplanning(p.path);  // the moves it repairs from: F's arcs as chords
  EXPECT_GT(plan.waypoints.size(), p.path.waypoints.size());
  std::size_t executed_on = 0, all_on = 0;
  for (bool on : s.cut.executed.tool_on) executed_on += on;
  for (bool on : plan.tool_on) all_on += on;
  EXPECT_GE(r.dropped_moves + 1, executed_on) << "every move of the executed half is painted already (the cut one may not be)";
  EXPECT_LE(r.dropped_moves, executed_on + 1);
  EXPECT_EQ(r.kept_moves + r.dropped_moves, all_on);
  const PathMetrics before = computeMetrics(p.wall, kTool, plan), after = computeMetrics(s.wall, kTool, r.path);
  EXPECT_GE(after.coverage.coverage_reachable, before.coverage.coverage_reachable - 1e-9);
  EXPECT_TRUE(test::isValidPath(s.wall, kTool, r.repairedPart()));

  // Cut at the start: nothing is painted yet, every move is kept.
  s.cut = cutPath(p.path, 0.0);
  const Repair all = repairFromPlan(s, problem, p.path);
  EXPECT_EQ(all.dropped_moves, 0u);
  EXPECT_EQ(all.kept_moves, all_on);
}

/// Every planner on generated walls, obstacles at 0.3 and 0.7, both repairs: every repaired path
/// is valid (its executed part on the old wall, the rest on the new) by the fast engine and the
/// exact judge; dragged (holonomic) on every family but the huge stress walls, lifted (gantry) on
/// the families of split walls.
class ReplanningPlanners : public testing::TestWithParam<std::string> {};

TEST_P(ReplanningPlanners, EveryRepairedPathIsValid) {
  const PlannerInfo& info = findPlanner(GetParam());
  ReplanningSpec spec;
  spec.at = {0.3, 0.7};
  spec.obstacles = 2;
  VehicleModel gantry;
  gantry.kind = VehicleModel::Kind::Gantry;
  using Families = std::vector<std::pair<std::string, std::size_t>>;
  const std::vector<std::pair<VehicleModel, Families>> cases{
      {VehicleModel{},
       {{"residential", 3}, {"facade", 2}, {"gable", 2}, {"stairwell", 2}, {"industrial", 1}, {"random", 4}, {"narrow", 3}}},
      {gantry, {{"narrow", 3}, {"random", 3}}}};
  std::size_t repairs = 0, placed = 0, blocked = 0;
  for (const auto& [vehicle, families] : cases) {
    for (const auto& [family, count] : families) {
      for (std::size_t i = 0; i < count; ++i) {
        const Wall wall = generateWall(family, 5, i);
        Problem problem;
        problem.wall = &wall;
        problem.tool = kTool;
        problem.vehicle = vehicle;
        problem.params = resolveParams(info, {});
        const PlanResult plan = runPlanner(info, problem, Budget());
        if (!plan.hasPath()) continue;
        for (double f : spec.at) {
          const Surprise s = makeSurprise(wall, kTool, plan.path, f, spec, 11 + i);
          placed += s.obstacles.size();
          Problem changed = problem;
          changed.wall = &s.wall;
          const PlanResult again = runPlanner(info, changed, Budget());
          std::vector<Repair> done{repairByDetour(s, changed)};
          if (again.hasPath()) done.push_back(repairFromPlan(s, changed, again.path));
          for (const Repair& r : done) {
            ++repairs;
            ASSERT_TRUE(r.ok);
            blocked += r.blocked_m > 0.0;
            const std::string where = wall.name + " at " + std::to_string(f) + " (" + toString(vehicle.kind) + ")";
            EXPECT_TRUE(test::isValidPath(s.wall, kTool, r.repairedPart(), vehicle)) << where;
            EXPECT_TRUE(test::isValidPath(wall, kTool, s.cut.executed, vehicle)) << where;
            EXPECT_EQ(r.path.waypoints[r.cut_waypoint], s.cut.position);
          }
        }
      }
    }
  }
  EXPECT_GE(repairs, 90u);
  EXPECT_GE(placed, 90u) << "obstacles find a place on almost every wall";
  EXPECT_GE(blocked, 20u) << "and are in the way: detours leave blocked stretches";
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, ReplanningPlanners, testing::ValuesIn(test::plannerNames()), test::plannerTestName);

class ReplanningExperiments : public test::CommandTest {
 protected:
  std::string configError(const std::string& text) {
    return test::inputError([&] { loadExperimentConfig(write("exp.yaml", text)); });
  }
  const std::string base_ = "name: r\noutput: out\ndatasets:\n  - family: facade\n    count: 2\n    seed: 3\n"
                            "planners:\n  - zigzag\n  - spiral\n";
};

TEST_F(ReplanningExperiments, TheConfigSectionIsCheckedAndOnlyReplanningChangesTheRunKeys) {
  const ExperimentConfig plain = loadExperimentConfig(write("a.yaml", base_));
  const ExperimentConfig replan = loadExperimentConfig(
      write("b.yaml", base_ + "replanning:\n  at: [0.3, 0.7]\n  obstacles: 2\n  kinds: [ladder, duct]\n  repairs: detour\n"));
  EXPECT_FALSE(plain.replanning.enabled());
  ASSERT_TRUE(replan.replanning.enabled());
  EXPECT_EQ(replan.replanning.at, (std::vector<double>{0.3, 0.7}));
  EXPECT_EQ(replan.replanning.obstacles, 2);
  EXPECT_EQ(replan.replanning.kinds, (std::vector<SurpriseKind>{SurpriseKind::Ladder, SurpriseKind::Duct}));
  EXPECT_EQ(replan.replanning.repairs, (std::vector<RepairMethod>{RepairMethod::Detour}));
  EXPECT_EQ(replan.replanning.describe(), "at=0.29999999999999999,0.69999999999999996 obstacles=2 kinds=ladder,duct repairs=detour");
  const std::vector<WallEntry> walls = loadWalls(plain);
  const std::vector<RunSpec> a = expandRuns(plain, walls), b = expandRuns(replan, walls);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NE(a[i].key, b[i].key);
  // Without the section the base key is as before replanning existed (what it was made of then).
  RunSpec older = a[0];
  older.replanning = {};
  EXPECT_EQ(runBaseKey(older), a[0].base_key);

  const std::string at = base_ + "replanning:\n";
  EXPECT_NE(configError(at + "  obstacles: 2\n").find("exp.yaml:11: replanning.at: missing"), std::string::npos);
  // The range says what it takes: 0 and 1 are both refused, and it says so.
  EXPECT_NE(configError(at + "  at: 1\n").find("replanning.at: must be in (0, 1), got 1"), std::string::npos);
  EXPECT_NE(configError(at + "  at: 0\n").find("replanning.at: must be in (0, 1), got 0"), std::string::npos);
  EXPECT_NE(configError(at + "  at: [0.5, 0.5]\n").find("replanning.at: lists 0.5 twice"), std::string::npos);
  EXPECT_NE(configError(at + "  at: 0.5\n  obstacles: 0\n").find("replanning.obstacles: must be in [1, 20]"), std::string::npos);
  EXPECT_NE(configError(at + "  at: 0.5\n  kinds: [crane]\n").find("replanning.kinds: must be scaffolding, ladder or duct, not 'crane'"),
            std::string::npos);
  EXPECT_NE(configError(at + "  at: 0.5\n  repairs: [pray]\n").find("replanning.repairs: must be replan or detour, not 'pray'"),
            std::string::npos);
  EXPECT_NE(configError(at + "  at: 0.5\n  when: never\n").find("replanning.when"), std::string::npos);
}

TEST_F(ReplanningExperiments, RepairsAreStoredReportedAndDrawn) {
  const std::string config =
      write("exp.yaml", base_ + "replanning:\n  at: [0.3, 0.7]\n  obstacles: 2\n");
  std::string out;
  CommandRun r = run("run " + config + " --no-report", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string db = (dir_ / "out" / "results.sqlite").string();
  // 2 walls x 2 planners x 2 fractions x 2 repairs, each scored, every repaired path valid.
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*), SUM(valid), SUM(status = 'invalid_output'), SUM(path IS NOT NULL) FROM replans"),
            "16|16|0|16\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT repair, COUNT(*) FROM replans GROUP BY repair"), "detour|8\nreplan|8\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*) FROM replan_figures WHERE name = 'coverage_reachable' AND value > 0.5"), "16\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*) FROM replans WHERE repair = 'replan' AND repair_ms IS NULL"), "0\n");

  ResultsDb results(db, ResultsDb::Mode::ReadOnly);
  const ResultSet rs = results.load();
  std::size_t rows = 0;
  for (const ResultRow& row : rs.runs) {
    ASSERT_EQ(row.replans.size(), 4u);
    EXPECT_EQ(row.replans[0].fraction, 0.3);
    EXPECT_EQ(row.replans[0].repair, "replan");
    EXPECT_EQ(row.replans[1].repair, "detour");
    EXPECT_EQ(row.replans[3].fraction, 0.7);
    for (const ReplanRow& p : row.replans) {
      EXPECT_TRUE(p.figures.count("scratch_coverage_reachable"));
      EXPECT_TRUE(p.figures.count("added_length_m"));
    }
    ++rows;
  }
  EXPECT_EQ(rows, 4u);

  // The same config again: nothing runs again, the stored repairs are the same (but for time).
  const std::string figures_sql = "SELECT run_key, position, name, value FROM replan_figures ORDER BY 1, 2, 3";
  const std::string before = test::sqlRows(db, figures_sql);
  r = run("run " + config + " --no-report", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::sqlRows(db, figures_sql), before);

  // The report has a replanning section; its data carries every repair.
  ASSERT_EQ(run("report " + db + " --format html --out " + (dir_ / "report").string()).exit_code, 0);
  const std::string page = slurp((dir_ / "report" / "index.html").string());
  EXPECT_NE(page.find("<section id=\"replanning\">"), std::string::npos);
  EXPECT_NE(page.find("facade: replanning after surprise obstacles"), std::string::npos);
  EXPECT_NE(slurp((dir_ / "report" / "report_data.json").string()).find("\"replans\""), std::string::npos);

  // redraw draws a repair: the new obstacles and the repaired path.
  const std::string key = test::sqlRows(db, "SELECT run_key FROM replans WHERE position = 1 LIMIT 1").substr(0, 12);
  const std::string svg = (dir_ / "repair.svg").string();
  r = run("redraw " + db + " --run " + key + " --replan 1 --svg " + svg, &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(out.find("-> " + svg), std::string::npos);
  EXPECT_NE(slurp(svg).find("surprise: "), std::string::npos);
  r = run("redraw " + db + " --run " + key + " --replan 4 --svg " + svg);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--replan: replan: run " + key + " has 4 repairs (numbers 0 to 3), not number 4"), std::string::npos) << r.err;
}

TEST_F(ReplanningExperiments, ExperimentsWithoutTheSectionStoreNoRepairs) {
  std::string out;
  ASSERT_EQ(run("run " + write("exp.yaml", base_) + " --no-report", &out).exit_code, 0);
  const std::string db = (dir_ / "out" / "results.sqlite").string();
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*) FROM replans"), "0\n");
  ASSERT_EQ(run("report " + db + " --format html --out " + (dir_ / "report").string()).exit_code, 0);
  EXPECT_EQ(slurp((dir_ / "report" / "index.html").string()).find("id=\"replanning\""), std::string::npos);
  EXPECT_EQ(slurp((dir_ / "report" / "report_data.json").string()).find("\"replans\""), std::string::npos);
}

}  // namespace
}  // namespace coverbench
