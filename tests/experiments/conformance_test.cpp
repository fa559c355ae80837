// The conformance suite every registered planner must pass: on every conformance wall, a valid
// path or a clear failure status, deterministically; and the same over many generated walls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "coverbench/conformance.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

struct Case {
  std::string planner;
  std::string wall_file;
  ToolParams tool;
  std::vector<std::pair<std::string, std::string>> params;
};

std::string caseName(const Case& c) {
  std::string name = c.planner + "__" + c.wall_file.substr(c.wall_file.find_last_of('/') + 1);
  name = name.substr(0, name.rfind('.'));
  if (c.tool.tool_width != 0.1) name += "__s" + std::to_string(static_cast<int>(c.tool.tool_width * 1000));
  for (const auto& [k, v] : c.params) name += "__" + k + v;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

void PrintTo(const Case& c, std::ostream* os) { *os << caseName(c); }

/// Plans and checks the planner contract: ok means a well-formed, exactly valid path; anything
/// else means no path and a reason.
testing::AssertionResult honours(const PlannerInfo& info, const Wall& wall, const ToolParams& tool,
                                 const Params& params, PlanResult* out = nullptr, const VehicleModel& vehicle = {}) {
  Problem problem;
  problem.wall = &wall;
  problem.tool = tool;
  problem.vehicle = vehicle;
  problem.params = params;
  PlanResult r = runPlanner(info, problem, Budget(std::chrono::seconds(60)));
  if (out) *out = r;
  if (r.hasPath()) {
    if (r.status == PlanStatus::Partial && !r.leftPartsOut())
      return testing::AssertionFailure() << "partial without saying what was left out";
    if (r.status == PlanStatus::Partial && r.reason.empty()) return testing::AssertionFailure() << "partial without a reason";
    testing::AssertionResult valid = test::isValidPath(wall, tool, r.path, vehicle);
    if (!valid) return valid << " (" << info.name << " on " << wall.name << ")";
    return testing::AssertionSuccess();
  }
  if (r.status == PlanStatus::Error) return testing::AssertionFailure() << "error status: " << r.reason;
  if (r.reason.empty()) return testing::AssertionFailure() << "failure status without a reason";
  if (!r.path.waypoints.empty()) return testing::AssertionFailure() << "failure status with a path";
  return testing::AssertionSuccess();
}

class Conformance : public testing::TestWithParam<Case> {};

TEST_P(Conformance, ValidOrClearFailureAndDeterministic) {
  const Case& c = GetParam();
  const Wall wall = loadWallFile(c.wall_file);
  const PlannerInfo& info = findPlanner(c.planner);
  const Params params = resolveParams(info, c.params);
  PlanResult first, second;
  ASSERT_TRUE(honours(info, wall, c.tool, params, &first));
  ASSERT_TRUE(honours(info, wall, c.tool, params, &second));
  ASSERT_EQ(first.path.waypoints.size(), second.path.waypoints.size());
  for (std::size_t i = 0; i < first.path.waypoints.size(); ++i) {
    ASSERT_EQ(first.path.waypoints[i].x, second.path.waypoints[i].x) << "waypoint " << i;
    ASSERT_EQ(first.path.waypoints[i].y, second.path.waypoints[i].y) << "waypoint " << i;
  }
  EXPECT_EQ(first.path.tool_on, second.path.tool_on);
  EXPECT_EQ(first.unreachable_parts, 0u) << "every part of the covered component is reached: " << first.reason;

  // The status the wall calls for (coverbench/conformance.hpp: the definition the report card
  // checks), with any parameters.
  const ExpectedOutcome expected = expectedOutcome(wall, c.tool);
  EXPECT_EQ(first.status, expected.status) << expected.why << ": " << first.reason;
  // The declared minimum coverage, with default parameters, where the free region is connected
  // (a planner covers one component; the others cannot be reached without leaving F).
  if (c.params.empty() && first.status == PlanStatus::Ok && expected.free_components == 1) {
    const double covered = coverage(wall, c.tool, first.path).coverage_reachable;
    EXPECT_GE(covered, info.min_coverage_reachable) << c.planner << " declares this minimum";
  }
}

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (const PlannerInfo& p : registeredPlanners())
    for (const std::string& f : test::conformanceWallFiles()) {
      cases.push_back({p.name, f, ToolParams{0.1, 0.02}, {}});
      cases.push_back({p.name, f, ToolParams{0.05, 0.0}, {}});
    }
  // Variants as parameters.
  for (const char* angle : {"30", "90", "137.5"})
    cases.push_back({"zigzag", test::sourcePath("datasets/canonical/living_room_north.json"), {}, {{"sweep_angle", angle}}});
  for (const char* wall : {"datasets/canonical/living_room_north.json", "datasets/conformance/rotated_polygons.json"})
    cases.push_back({"zigzag", test::sourcePath(wall), {}, {{"direction_search", "true"}}});
  for (const char* passes : {"0", "3"})
    cases.push_back({"zigzag", test::sourcePath("datasets/conformance/garden_circles.json"), {}, {{"boundary_passes", passes}}});
  cases.push_back({"zigzag", test::sourcePath("datasets/conformance/stairwell.json"), {}, {{"overlap", "0.3"}}});
  cases.push_back({"spiral", test::sourcePath("datasets/conformance/stairwell.json"), {}, {{"overlap", "0.3"}}});
  for (const char* wall : {"datasets/conformance/garden_circles.json", "datasets/conformance/stairwell.json",
                           "datasets/conformance/overlapping_cluster.json", "datasets/conformance/rotated_polygons.json",
                           "datasets/canonical/living_room_north.json", "datasets/canonical/gable_round_window.json"}) {
    for (const char* variant : {"return", "stop", "spiral-stc"})
      cases.push_back({"spanning-tree", test::sourcePath(wall), {}, {{"variant", variant}}});
    cases.push_back({"spanning-tree", test::sourcePath(wall), {}, {{"tree", "mst"}}});
    cases.push_back({"spanning-tree", test::sourcePath(wall), {}, {{"tree", "mst"}, {"variant", "spiral-stc"}}});
    cases.push_back({"spanning-tree", test::sourcePath(wall), {}, {{"neighbour_order", "LDRU"}}});
    cases.push_back({"adaptive-resolution", test::sourcePath(wall), {}, {{"dense_waypoints", "true"}}});
    for (const char* planner : {"spanning-tree", "adaptive-resolution"})
      cases.push_back({planner, test::sourcePath(wall), {}, {{"corner_spurs", "true"}}});
  }
  for (const char* planner : {"trapezoidal", "boustrophedon"})
    for (const char* wall : {"datasets/conformance/garden_circles.json", "datasets/conformance/stairwell.json",
                             "datasets/conformance/rotated_polygons.json", "datasets/canonical/living_room_north.json"}) {
      for (const char* order : {"dfs", "greedy"}) cases.push_back({planner, test::sourcePath(wall), {}, {{"order", order}}});
      cases.push_back({planner, test::sourcePath(wall), {}, {{"boundary_loop", "false"}}});
      cases.push_back({planner, test::sourcePath(wall), {}, {{"sweep_angle", "37"}}});
      cases.push_back({planner, test::sourcePath(wall), {}, {{"overlap", "0.3"}}});
      cases.push_back({planner, test::sourcePath(wall), {}, {{"direction_search", "true"}}});
    }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, Conformance, testing::ValuesIn(allCases()),
                         [](const testing::TestParamInfo<Case>& param_info) { return caseName(param_info.param); });

// The definition of what a correct planner must do on each conformance wall
// (coverbench/conformance.hpp, used by `coverbench conformance` too) against outcomes worked out by
// hand from the walls' geometry (r = s / 2; the tool's centre keeps r from the edge and r + c from
// obstacles):
// - exactly_tool_height (2 x 0.1 m): at s = 0.1 no room (F empty); at s = 0.05 a strip 0.05 m high.
// - barely_wider_than_tool (2 x 0.1006 m): 0.6 mm of room at s = 0.1 (more than F's 2 x 55 um margin).
// - narrow_gap_disconnected: a window 1.08 m high on a 1.2 m wall leaves a 0.12 m gap, which needs
//   r + r + c = 0.12 m at s = 0.1 (F splits: zero width) and 0.05 m at s = 0.05 (one piece).
// - narrow_passage_open: a 0.16 m gap, more than the 0.12 m needed at s = 0.1.
// - overlapping_cluster: the pocket enclosed by the first rectangle's right edge, the second's lower
//   edge and the circle (centre (1.9, 1), radius 0.3) fits a disc of radius at most
//   0.124 / (1 + sqrt 2) = 0.051 m from the corner (1.6, 1.3): a second piece at s = 0.05, c = 0
//   (needs 0.025) but not at s = 0.1, c = 0.02 (needs 0.07).
// - rotated_polygons: the triangle crossing the boundary cuts off the corner (5.8..6, 0..0.2) whose
//   point (5.95, 0.05) is 0.05 m from both edges and 0.0707 m from the triangle: a second piece at
//   both tools.
// - the canonical walls and the other conformance walls: obstacles that enclose no pocket, one piece.
TEST(ConformanceWalls, TheDefinitionGivesTheOutcomesWorkedOutByHand) {
  const std::map<std::string, std::pair<std::size_t, std::size_t>> pieces = {  // F's pieces at s = 0.1 and at s = 0.05
      {"exactly_tool_height", {0, 1}},     {"barely_wider_than_tool", {1, 1}}, {"narrow_gap_disconnected", {2, 1}},
      {"narrow_passage_open", {1, 1}},     {"overlapping_cluster", {1, 2}},    {"rotated_polygons", {2, 2}},
      {"gable_clockwise", {1, 1}},         {"gable_counter_clockwise", {1, 1}}, {"garden_circles", {1, 1}},
      {"stairwell", {1, 1}},               {"facade_20x9_24win", {1, 1}},      {"gable_round_window", {1, 1}},
      {"l_shape_clockwise", {1, 1}},       {"living_room_north", {1, 1}},      {"overlapping_touching", {1, 1}},
      {"seed_10x10_5obs", {1, 1}},         {"seed_10x8_3obs", {1, 1}},         {"seed_1x1_empty", {1, 1}},
      {"seed_5x5_1obs", {1, 1}},           {"seed_5x5_3obs", {1, 1}}};
  const std::vector<std::string> files = wallFilesIn(conformanceWallFolders(COVERBENCH_SOURCE_DIR));
  ASSERT_EQ(files, test::conformanceWallFiles());
  ASSERT_EQ(files.size(), pieces.size());
  ASSERT_EQ(conformanceTools().size(), 2u);
  for (const std::string& file : files) {
    const std::string stem = std::filesystem::path(file).stem().string();
    ASSERT_EQ(pieces.count(stem), 1u) << stem;
    const Wall wall = loadWallFile(file);
    for (std::size_t t = 0; t < 2; ++t) {
      const std::size_t n = t == 0 ? pieces.at(stem).first : pieces.at(stem).second;
      const ExpectedOutcome e = expectedOutcome(wall, conformanceTools()[t]);
      EXPECT_EQ(e.free_components, n) << stem << " tool " << t;
      EXPECT_EQ(e.status, n == 0 ? PlanStatus::NoReachableArea : n == 1 ? PlanStatus::Ok : PlanStatus::Partial)
          << stem << " tool " << t;
    }
  }
}

TEST(ConformanceWalls, ExpectedOutcomes) {
  // Every planner on every conformance wall at both tools does what the definition calls for
  // (checkConformance, as the report card checks it), and reports F's pieces as the definition
  // counts them: a partial plan names the disconnected components it left out.
  for (const PlannerInfo& p : registeredPlanners()) {
    const Params params = resolveParams(p, {});
    forEachConformanceProblem(p, test::conformanceWallFiles(), params, [&](const std::string&, Problem& problem) {
      const Wall& wall = *problem.wall;
      const ToolParams& tool = problem.tool;
      const JudgedPlan judged = planAndJudge(p, problem, Budget(std::chrono::seconds(60)));
      const ExpectedOutcome expected = expectedOutcome(wall, tool);
      const std::string where = p.name + " on " + wall.name + " at s = " + std::to_string(tool.tool_width);
      const ConformanceCheck check = checkConformance(expected, judged, p.min_coverage_reachable, true);
      EXPECT_TRUE(check.passed()) << where << ": " << check.cause;
      const PlanResult& r = judged.result;
      if (!r.hasPath()) return;
      EXPECT_EQ(r.free_components, expected.free_components) << where;
      EXPECT_EQ(r.covered_components, 1u) << where;
      if (expected.status == PlanStatus::Partial) {
        EXPECT_NE(r.reason.find("disconnected"), std::string::npos) << where << " must say what it left out: " << r.reason;
      }
    });
  }
}

// The card's verdicts, each from a judged plan made by hand: a failure status fails whatever the
// wall, naming the status and the reason; a status other than the wall's fails, naming both; a
// promise below the declared coverage fails; the expected status with a reason passes.
TEST(ConformanceWalls, EachVerdictNamesItsCause) {
  const ExpectedOutcome one{PlanStatus::Ok, 1, "F is one piece"};
  const ExpectedOutcome split{PlanStatus::Partial, 2, "F is in 2 pieces"};
  const ExpectedOutcome none{PlanStatus::NoReachableArea, 0, "F is empty: the tool fits nowhere"};
  auto judged = [](RunStatus verdict, PlanStatus status, const std::string& reason, double coverage) {
    JudgedPlan j;
    j.verdict = verdict;
    j.result.status = status;
    j.result.reason = j.reason = reason;
    if (status == PlanStatus::Ok || status == PlanStatus::Partial) j.result.path.waypoints = {{0, 0}, {1, 0}};
    j.result.path.tool_on = {true};
    j.metrics.coverage.coverage_reachable = coverage;
    return j;
  };
  const ConformanceCheck crash = checkConformance(
      none, judged(RunStatus::Crash, PlanStatus::Crash, "the planner's process exited with code 1", NAN), 0.0, true);
  EXPECT_FALSE(crash.passed());
  EXPECT_EQ(crash.cause, "crash (the planner's process exited with code 1); no_reachable_area expected: F is empty: the tool fits nowhere");
  for (RunStatus bad : {RunStatus::Timeout, RunStatus::MemoryLimit, RunStatus::Error, RunStatus::InvalidOutput,
                        RunStatus::MetricsError})
    EXPECT_EQ(checkConformance(one, judged(bad, PlanStatus::Ok, "why", 1.0), 0.0, true).cause,
              std::string(toString(bad)) + " (why); ok expected: F is one piece");
  EXPECT_EQ(checkConformance(one, judged(RunStatus::Partial, PlanStatus::Partial, "12 % covered", 0.12), 0.0, true).cause,
            "partial (12 % covered); ok expected: F is one piece");
  EXPECT_EQ(checkConformance(split, judged(RunStatus::Ok, PlanStatus::Ok, "", 0.6), 0.0, true).cause,
            "ok; partial expected: F is in 2 pieces");
  EXPECT_EQ(checkConformance(split, judged(RunStatus::Partial, PlanStatus::Partial, "", 0.6), 0.0, true).cause,
            "partial without a reason; partial expected: F is in 2 pieces");
  EXPECT_EQ(checkConformance(one, judged(RunStatus::Ok, PlanStatus::Ok, "", 0.5), 0.995, true).cause,
            "ok at coverage_reachable 0.5000, below the declared 0.9950");
  EXPECT_TRUE(checkConformance(one, judged(RunStatus::Ok, PlanStatus::Ok, "", 0.5), 0.995, false).passed())
      << "the promise is for default parameters";
  EXPECT_TRUE(checkConformance(split, judged(RunStatus::Partial, PlanStatus::Partial, "left one out", 0.6), 0.0, true).passed());
  EXPECT_TRUE(
      checkConformance(none, judged(RunStatus::NoReachableArea, PlanStatus::NoReachableArea, "no room", NAN), 0.0, true).passed());
  EXPECT_EQ(checkConformance(none, judged(RunStatus::NoReachableArea, PlanStatus::NoReachableArea, "", NAN), 0.0, true).cause,
            "no_reachable_area without a reason; no_reachable_area expected: F is empty: the tool fits nowhere");
}

TEST(FamilyWalls, EveryPlannerAndVariantValidOnEveryGeneratedFamily) {
  // Two walls of every generator family (the 50 m `stress` walls run in the default experiment,
  // which checks every path too), every planner with its defaults, and the grid planner's variants.
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> configs;
  for (const PlannerInfo& p : registeredPlanners()) configs.push_back({p.name, {}});
  for (const char* variant : {"return", "stop", "spiral-stc"}) configs.push_back({"spanning-tree", {{"variant", variant}}});
  configs.push_back({"spanning-tree", {{"tree", "mst"}}});
  configs.push_back({"adaptive-resolution", {{"dense_waypoints", "true"}}});
  for (const char* planner : {"spanning-tree", "adaptive-resolution"}) configs.push_back({planner, {{"corner_spurs", "true"}}});
  std::vector<Wall> walls;
  for (const FamilyInfo& family : wallFamilies()) {
    // The field family is planned at its own scale (FieldWalls below).
    if (family.fixed_suite || family.name == "stress" || family.name == "field") continue;
    for (std::size_t i = 0; i < 2; ++i) walls.push_back(generateWall(family.name, 42, i));
  }
  for (const Wall& wall : test::sampled(walls)) {
    for (const auto& [planner, settings] : configs) {
      const PlannerInfo& info = findPlanner(planner);
      PlanResult r;
      ASSERT_TRUE(honours(info, wall, {0.1, 0.02}, resolveParams(info, settings), &r)) << wall.name << " " << planner;
      EXPECT_EQ(r.unreachable_parts, 0u) << wall.name << " " << planner << ": " << r.reason;
    }
  }
}

class GeneratedWalls : public testing::TestWithParam<std::string> {};

TEST_P(GeneratedWalls, ValidOnManyRandomWalls) {
  const PlannerInfo& info = findPlanner(GetParam());
  const Params params = resolveParams(info, {});
  int ok = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    const Wall wall = test::randomWall(seed);
    PlanResult r;
    ASSERT_TRUE(honours(info, wall, {0.1, 0.02}, params, &r)) << "seed " << seed;
    EXPECT_EQ(r.unreachable_parts, 0u) << "seed " << seed << ": " << r.reason;
    ok += r.hasPath();
  }
  EXPECT_GE(ok, 55) << "almost every random wall has room for the tool";
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, GeneratedWalls, testing::ValuesIn(test::plannerNames()), test::plannerTestName);


// Field scale: a 100 m polygon with 15 buildings at s = 3 m (the published polygon sets' sweep
// width), and walls of the field family at 1-6 m: every planner plans them validly.
TEST(FieldScale, EveryPlannerPlansAHundredMetrePolygonWithFifteenBuildingsAndFieldWalls) {
  std::vector<std::pair<Wall, ToolParams>> cases = {
      {loadWallFile(test::sourcePath("bench/walls/field_100m_15_buildings.json")), ToolParams{3.0, 0.0}}};
  ASSERT_EQ(cases[0].first.obstacles.size(), 15u);
  for (std::size_t i = 0; i < 3; ++i) cases.push_back({generateWall("field", 3, i), ToolParams{1.0 + 2.5 * static_cast<double>(i), 0.0, {}}});
  for (const PlannerInfo& info : registeredPlanners())
    for (const auto& [wall, tool] : cases) {
      PlanResult r;
      ASSERT_TRUE(honours(info, wall, tool, resolveParams(info, {}), &r)) << wall.name << " " << info.name;
      EXPECT_EQ(r.status, PlanStatus::Ok) << wall.name << " " << info.name << ": " << r.reason;
    }
}

// A limit of one kind of planner applies to that kind: the 100 m field doubled to 200 m at a 5 cm
// tool is 1.6e7 tool-sized cells, past the grid planners' 1e7. The sweep planners plan it (in
// milliseconds); the grid planners end with invalid_input and say why. (Spiral, which offsets the
// region once per ring, plans it too, in about 20 s here: too long for this suite; the command is
// in docs/file_formats.md#limits-on-inputs.)
TEST(FieldScale, AFieldTooFineForAGridIsPlannedBySweepsAndRefusedByGridPlanners) {
  Wall wall = loadWallFile(test::sourcePath("bench/walls/field_100m_15_buildings.json"));
  for (Point& p : wall.boundary) p = p * 2.0;
  for (Obstacle& o : wall.obstacles)
    for (Point& p : o.polygon) p = p * 2.0;
  const ToolParams tool{0.05, 0.0};
  for (const char* planner : {"zigzag", "trapezoidal", "boustrophedon"}) {
    const PlanResult r = test::planWith(planner, wall, tool);
    ASSERT_EQ(r.status, PlanStatus::Ok) << planner << ": " << r.reason;
    EXPECT_TRUE(checkValidity(wall, tool, r.path).valid) << planner;
  }
  for (const char* planner : {"spanning-tree", "adaptive-resolution"}) {
    const PlanResult r = test::planWith(planner, wall, tool);
    EXPECT_EQ(r.status, PlanStatus::InvalidInput) << planner;
    EXPECT_NE(r.reason.find("1.6e+07 tool-sized cells"), std::string::npos) << r.reason;
    EXPECT_NE(r.reason.find("the sweep planners need no grid"), std::string::npos) << r.reason;
  }
}

class StartAndEnd : public testing::TestWithParam<std::string> {};

// Every planner begins at the given start and ends at the given end (reached with the tool off),
// validly, on the canonical walls, the conformance walls and random walls; a start outside F is
// joined to F by an approach leg, or refused with the nearest point of F where no leg reaches.
TEST_P(StartAndEnd, EveryPathBeginsAtTheStartAndEndsAtTheEnd) {
  const ToolParams tool{0.1, 0.02};
  std::vector<Wall> walls;
  for (const std::string& file : test::conformanceWallFiles()) walls.push_back(loadWallFile(file));
  for (unsigned seed = 1; seed <= 10; ++seed) walls.push_back(test::randomWall(seed));
  int planned = 0;
  for (Wall wall : walls) {
    wall.start = test::freePointNear(wall, tool, true);
    wall.end = test::freePointNear(wall, tool, false);
    if (!wall.start || !wall.end) continue;  // no room for the tool
    const PlanResult r = test::planWith(GetParam(), wall, tool);
    if (!r.hasPath()) {
      // Only where the start and the end lie in parts of F the path cannot reach (narrow walls).
      EXPECT_NE(r.reason.find("no tool-off move connects"), std::string::npos) << wall.name << ": " << r.reason;
      continue;
    }
    ++planned;
    ASSERT_FALSE(r.path.waypoints.empty()) << wall.name;
    EXPECT_TRUE(r.path.waypoints.front() == *wall.start) << wall.name;
    EXPECT_TRUE(r.path.waypoints.back() == *wall.end) << wall.name;
    EXPECT_TRUE(test::isValidPath(wall, tool, r.path)) << wall.name;
  }
  EXPECT_GE(planned, static_cast<int>(walls.size()) - 4);
  // A start and an end on the wall's edge, where the tool overhangs it (a dock): joined to the
  // nearest points of F by straight depot legs. F is the free region as planners compute it:
  // eroded by r = 0.05 m and a margin of 5.5e-5 m, so the legs are 0.050055 m long.
  Wall wall = test::rectWall(2, 1);
  wall.start = Point{0.0, 0.5};
  wall.end = Point{2.0, 0.5};
  const PlanResult r = test::planWith(GetParam(), wall, tool);
  ASSERT_TRUE(r.hasPath()) << r.reason;
  const auto& w = r.path.waypoints;
  EXPECT_TRUE(w.front() == *wall.start);
  EXPECT_TRUE(w.back() == *wall.end);
  EXPECT_NEAR(w[1].x, 0.050055, 1e-6);
  EXPECT_NEAR(w[1].y, 0.5, 1e-9);
  EXPECT_FALSE(r.path.tool_on.front());
  EXPECT_FALSE(r.path.tool_on.back());
  EXPECT_EQ(r.stats.at("depot_legs"), 2.0);
  EXPECT_NEAR(r.stats.at("depot_length"), 2 * 0.050055, 1e-6);
  EXPECT_TRUE(test::isValidPath(wall, tool, r.path));
  EXPECT_EQ(checkValidity(wall, tool, r.path).depot_legs, 2u);
  // A start in the window (x from 1 to 1.2, y from 0.4 to 0.6) or on its edge: refused.
  Wall window = test::rectWall(2, 1, {test::rect(1.0, 0.4, 0.2, 0.2)});
  for (const Point start : {Point{1.1, 0.5}, Point{1.0005, 0.5}, Point{1.0, 0.5}}) {
    window.start = start;
    const PlanResult refused = test::planWith(GetParam(), window, tool);
    EXPECT_EQ(refused.status, PlanStatus::InvalidInput);
    EXPECT_EQ(refused.reason, "start (" + shortNumber(start.x) + ", 0.5) lies in obstacles[0] (inside it or on its edge), where the tool's centre may never be");
  }
  // A start outside the wall (a wall built in code: wall files refuse it when read).
  window.start = Point{-0.5, 0.5};
  EXPECT_EQ(test::planWith(GetParam(), window, tool).reason, "start (-0.5, 0.5) lies outside the wall");
}

// A dock at the corner (0, 0) of a 2 m x 1 m wall and one at (0, 0.5) in the 2 cm slot between
// the left edge and a window (x from 0.02 to 0.3, y from 0.3 to 0.7): every planner plans, both
// judges accept the depot legs. The corner's leg is straight to F's corner (0.050055, 0.050055);
// the slot's is routed around the window's corner (0.02, 0.3) to F's nearest point. F as planners
// compute it is conservative: eroded by r and a margin of 5.5e-5 m, its clearance round the
// corner cut square, so that point is (0.050055, 0.3 - 0.070055) (or the same above the window):
// 0.201 m to the corner, then 0.0762 m.
TEST_P(StartAndEnd, DocksAtACornerAndBehindAnObstacleAreJoinedByDepotLegs) {
  const ToolParams tool{0.1, 0.02};
  Wall corner = test::rectWall(2, 1);
  corner.start = corner.end = Point{0.0, 0.0};
  const PlanResult r = test::planWith(GetParam(), corner, tool);
  ASSERT_TRUE(r.hasPath()) << r.reason;
  EXPECT_EQ(r.stats.at("depot_legs"), 2.0);
  EXPECT_NEAR(r.stats.at("depot_length"), 2 * std::sqrt(2.0) * 0.050055, 1e-5);
  EXPECT_TRUE(test::isValidPath(corner, tool, r.path));
  EXPECT_EQ(judge::judgeValidity(corner, tool, r.path).depot_legs, 2u);

  Wall slot = test::rectWall(2, 1, {test::rect(0.02, 0.3, 0.28, 0.4)});
  slot.start = Point{0.0, 0.5};
  const PlanResult s = test::planWith(GetParam(), slot, tool);
  ASSERT_TRUE(s.hasPath()) << s.reason;
  EXPECT_EQ(s.stats.at("depot_legs"), 1.0);
  const double routed = std::hypot(0.02, 0.2) + std::hypot(0.050055 - 0.02, 0.070055);
  EXPECT_NEAR(s.stats.at("depot_length"), routed, 2e-5);
  EXPECT_TRUE(test::isValidPath(slot, tool, s.path));
  const Validity fast = checkValidity(slot, tool, s.path);
  const judge::ExactValidity exact = judge::judgeValidity(slot, tool, s.path);
  EXPECT_EQ(fast.depot_legs, 1u);
  EXPECT_EQ(exact.depot_legs, 1u);
  EXPECT_NEAR(fast.depot_length, s.stats.at("depot_length"), 1e-9);
  EXPECT_NEAR(exact.depot_length, s.stats.at("depot_length"), 1e-9);
  // A car (whose smoothing drives only in F) is refused the corner's leg, saying so.
  Problem car;
  car.wall = &corner;
  car.tool = tool;
  car.vehicle.kind = VehicleModel::Kind::Car;
  const PlannerInfo& info = findPlanner(GetParam());
  // (a planner that plans for the car itself takes no start yet: it is given car_plan: smoothed)
  car.params = info.plans_for_car ? resolveParams(info, {{"car_plan", "smoothed"}}) : resolveParams(info, {});
  const PlanResult refused = runPlanner(info, car, Budget(std::chrono::seconds(60)));
  EXPECT_EQ(refused.status, PlanStatus::InvalidInput);
  EXPECT_NE(refused.reason.find("and a car is not given a depot leg to it"), std::string::npos) << refused.reason;
}

// The published 100 m field (12 holes; tests/data/field-12-holes.json, shared's fixture) starts
// and ends at (0, 0), a vertex of its boundary: every planner plans, and both judges accept the
// two depot legs there, each the straight move to F's corner (r + 5.5e-5 m, r + 5.5e-5 m).
TEST_P(StartAndEnd, TheFieldStartsAndEndsAtItsCorner) {
  const ToolParams tool{0.1, 0.02};  // the published benchmark's
  Wall field = loadWallFile(test::sourcePath("tests/data/field-12-holes.json"));
  field.start = field.end = Point{0.0, 0.0};
  const PlanResult r = test::planWith(GetParam(), field, tool);
  ASSERT_TRUE(r.hasPath()) << r.reason;
  EXPECT_TRUE(r.path.waypoints.front() == *field.start);
  EXPECT_TRUE(r.path.waypoints.back() == *field.end);
  EXPECT_EQ(r.stats.at("depot_legs"), 2.0);
  EXPECT_NEAR(r.stats.at("depot_length"), 2 * std::sqrt(2.0) * (0.05 + 5.5e-5), 1e-6);
  EXPECT_TRUE(test::isValidPath(field, tool, r.path));
  const judge::ExactValidity exact = judge::judgeValidity(field, tool, r.path);
  EXPECT_EQ(exact.depot_legs, 2u);
  EXPECT_NEAR(exact.depot_length, r.stats.at("depot_length"), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(AllPlanners, StartAndEnd, testing::ValuesIn(test::plannerNames()), test::plannerTestName);

}  // namespace
}  // namespace coverbench
