// The command line: bad input gives one line naming file, field and problem, a non-zero exit and
// no output file; good input gives a plan file and a picture.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdlib>
#include <iterator>

#include "coverbench/experiment.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/registry.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

using Cli = test::CommandTest;
using test::CommandRun;

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST_F(Cli, PlansAWallAndWritesPlanAndPicture) {
  const std::string out = (dir_ / "plan.json").string(), svg = (dir_ / "plan.svg").string();
  const CommandRun r = run("plan --wall " + test::sourcePath("datasets/canonical/living_room_north.json") +
                    " --planner zigzag --out " + out + " --svg " + svg);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::ifstream plan(out);
  std::stringstream text;
  text << plan.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"ok\""), std::string::npos);
  EXPECT_NE(text.str().find("\"valid\": true"), std::string::npos);
  EXPECT_TRUE(fs::file_size(svg) > 1000);
}

/// The value of `"key": number` in a JSON text (one key per line, as the metrics command prints).
double jsonNumber(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  return std::stod(text.substr(at + key.size() + 3));
}

// `metrics --judge exact`: the exact judge's figures beside the fast engine's, the fast values
// inside (or within the stated bound of) its intervals, the same bytes at every run (the time goes
// to stderr), exit 3 when the path is invalid, and a one-line error for a bad --arc-vertices.
TEST_F(Cli, MetricsWithTheExactJudge) {
  const std::string wall = write("wall.json", R"({ "name": "hand", "width": 4.0, "height": 2.0, "obstacles": [] })");
  const std::string plan = write("plan.json", R"({ "waypoints": [[1, 1], [3, 1], [3.5, 1.5]], "tool_on": [true, false] })");
  std::string out, again;
  const std::string args = "metrics --wall " + wall + " --plan " + plan + " --tool-width 0.2 --clearance 0 --judge exact --arc-vertices 64";
  const CommandRun r = run(args, &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("exact judge: "), std::string::npos) << r.err;
  ASSERT_EQ(run(args, &again).exit_code, 0);
  EXPECT_EQ(out, again);
  const nlohmann::json doc = nlohmann::json::parse(out);
  const double swept = 0.4 + M_PI * 0.01;
  EXPECT_EQ(doc["exact_judge"]["valid"], true);
  EXPECT_EQ(doc["exact_judge"]["arc_vertices"], 64);
  EXPECT_LE(doc["exact_judge"]["swept_area"][0].get<double>(), swept);
  EXPECT_GE(doc["exact_judge"]["swept_area"][1].get<double>(), swept);
  EXPECT_EQ(doc["fast_outside_exact"]["valid_agrees"], true);
  EXPECT_LE(std::fabs(doc["fast_outside_exact"]["coverage_reachable"].get<double>()), fastErrorBound(0.2));
  EXPECT_NEAR(doc["metrics"]["swept_area"].get<double>(), swept, 1e-4);

  const std::string window = write("window.json", R"({ "name": "w", "width": 4.0, "height": 2.0,
    "obstacles": [ { "type": "rect", "x": 1.8, "y": 0.8, "width": 0.4, "height": 0.4 } ] })");
  EXPECT_EQ(run("metrics --wall " + window + " --plan " + plan + " --tool-width 0.2 --clearance 0 --judge exact", &out).exit_code, 3);
  EXPECT_EQ(nlohmann::json::parse(out)["exact_judge"]["too_close"], 1);

  const CommandRun e = run("metrics --wall " + wall + " --plan " + plan + " --judge exact --arc-vertices 12", &out);
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_EQ(lines(e.err), 1) << e.err;
  EXPECT_NE(e.err.find("arc_vertices: must be a multiple of 8"), std::string::npos) << e.err;
  EXPECT_TRUE(out.empty()) << out;
}

// `car-ceiling`: JSON with the estimate and the pieces of F it chose among (two rooms joined by a
// slit no tool passes: a path stays in one, so the estimate, and the largest piece, are at most
// the larger room's 0.6 of R); a turn radius that is not positive is one line naming it, exit 2 and nothing on stdout.
TEST_F(Cli, CarCeilingPrintsTheBestPieceOfF) {
  const std::string wall = write("rooms.json", R"({ "name": "rooms", "boundary": [[0, 0], [3, 0], [3, 0.9], [4, 0.9], [4, 0],
      [6, 0], [6, 2], [4, 2], [4, 0.96], [3, 0.96], [3, 2], [0, 2]], "obstacles": [] })");
  std::string out;
  const CommandRun r = run("car-ceiling --wall " + wall + " --turn-radius 0.3", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(out);
  EXPECT_EQ(doc["pieces_of_f"], 2);
  EXPECT_GT(doc["interior"].get<double>(), 0.55);
  EXPECT_LT(doc["with_ends"].get<double>(), 0.62);
  EXPECT_GE(doc["viable_components"].get<int>(), 2);  // a car circles in each room
  EXPECT_NEAR(doc["largest_piece"].get<double>(), 0.6, 0.03);
  std::string none;
  const CommandRun bad = run("car-ceiling --wall " + wall + " --turn-radius 0", &none);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(lines(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("turn"), std::string::npos) << bad.err;
  EXPECT_TRUE(none.empty()) << none;
}

// `car-ceiling` holds the turn radius to the range `plan` holds a car to, with the same one line:
// 1e20 m is a car that cannot turn (it reported 1.0), 1e-9 m one that asked for memory without end.
TEST_F(Cli, CarCeilingHoldsTheTurnRadiusToPlansRange) {
  const std::string wall = test::sourcePath("datasets/canonical/living_room_north.json");
  for (const std::string radius : {"1e20", "1e-9", "0.001", "101"}) {
    std::string ceiling_out, plan_out;
    const CommandRun ceiling = run("car-ceiling --wall " + wall + " --turn-radius " + radius, &ceiling_out);
    const CommandRun plan = run("plan --wall " + wall + " --planner zigzag --vehicle car --turn-radius " + radius +
                                    " --out " + (dir_ / "p.json").string(),
                                &plan_out);
    EXPECT_EQ(ceiling.exit_code, 2) << radius << ": " << ceiling_out;
    EXPECT_EQ(lines(ceiling.err), 1) << ceiling.err;
    EXPECT_NE(ceiling.err.find("command line: vehicle.turn_radius: must be in [0.01, 100] m"), std::string::npos)
        << radius << ": " << ceiling.err;
    EXPECT_EQ(ceiling.err, plan.err) << radius;
    EXPECT_TRUE(ceiling_out.empty()) << ceiling_out;
  }
}

TEST_F(Cli, MetricsScoresAHandWrittenPlan) {
  // A 4 m x 2 m wall, tool 0.2 m, no clearance needed; one 2 m pass written by hand, with only
  // the two required fields. Closed forms: |S| = 0.2 * 2 + pi * 0.1^2; R is the 4 x 2 rectangle
  // with corners rounded to r = 0.1, |R| = 8 - (4 - pi) * 0.01.
  const std::string wall = write("wall.json", R"({ "name": "hand", "width": 4.0, "height": 2.0, "obstacles": [] })");
  const std::string plan = write("plan.json", R"({ "waypoints": [[1, 1], [3, 1], [3.5, 1.5]], "tool_on": [true, false] })");
  std::string out;
  const CommandRun r = run("metrics --wall " + wall + " --plan " + plan + " --tool-width 0.2 --clearance 0", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double swept = 0.4 + M_PI * 0.01, reachable = 8.0 - (4.0 - M_PI) * 0.01;
  EXPECT_NEAR(jsonNumber(out, "swept_area"), swept, 1e-4);
  EXPECT_NEAR(jsonNumber(out, "reachable_area"), reachable, 1e-4);
  EXPECT_NEAR(jsonNumber(out, "coverage_reachable"), swept / reachable, 1e-5);
  EXPECT_NEAR(jsonNumber(out, "coverage_wall"), swept / 8.0, 1e-5);
  EXPECT_NEAR(jsonNumber(out, "length_cover"), 2.0, 1e-12);
  EXPECT_NEAR(jsonNumber(out, "length_transit"), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(jsonNumber(out, "turns"), 1.0);
  EXPECT_EQ(jsonNumber(out, "overlap"), 0.0);
  EXPECT_NE(out.find("\"valid\": true"), std::string::npos) << out;

  // A plan through the middle of a window is scored and reported invalid (exit 3).
  const std::string window = write("window.json", R"({ "name": "w", "width": 4.0, "height": 2.0,
    "obstacles": [ { "type": "rect", "x": 1.8, "y": 0.8, "width": 0.4, "height": 0.4 } ] })");
  EXPECT_EQ(run("metrics --wall " + window + " --plan " + plan + " --tool-width 0.2 --clearance 0", &out).exit_code, 3);
  EXPECT_NE(out.find("\"valid\": false"), std::string::npos) << out;

  // Missing tool_on: one line naming the file and the field.
  const std::string bad = write("bad.json", R"({ "waypoints": [[1, 1], [3, 1]] })");
  const CommandRun e = run("metrics --wall " + wall + " --plan " + bad, &out);
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_EQ(lines(e.err), 1) << e.err;
  EXPECT_NE(e.err.find("bad.json"), std::string::npos) << e.err;
  EXPECT_NE(e.err.find("tool_on"), std::string::npos) << e.err;
}

// A config's time model (`motion:`): the durations it stores are the metrics command's under the
// same model, the cost per turn is its own metric, the run keys change, and the report's first
// line names the model.
TEST_F(Cli, ATimeModelChangesDurationsTheRunKeysAndTheReportsFirstLine) {
  fs::create_directories(dir_ / "walls");
  const std::string wall = write("walls/w.json", R"({"name": "w", "width": 3, "height": 1.5, "obstacles": [
    {"type": "rect", "x": 1.2, "y": 0.5, "width": 0.4, "height": 0.4}]})");
  const std::string base = "output: OUT\ndatasets:\n  - folder: walls\nplanners: [zigzag]\ntool: {width: 0.2, clearance: 0.02}\n";
  auto config = [&](const std::string& name, const std::string& extra) {
    std::string text = "name: " + name + "\n" + base + extra;
    text.replace(text.find("OUT"), 3, name);
    return write(name + ".yaml", text);
  };
  ASSERT_EQ(run("run " + config("plain", "") + " --no-report").exit_code, 0);
  ASSERT_EQ(run("run " + config("eth", "motion: {speed: 3, acceleration: 1, stops: waypoints, turn_cost_s: 5}\n") +
                " --no-report").exit_code, 0);
  const std::string plain_db = (dir_ / "plain" / "results.sqlite").string(), eth_db = (dir_ / "eth" / "results.sqlite").string();
  const std::string duration = "SELECT value FROM metrics WHERE name = 'duration_s'";
  EXPECT_NE(test::sqlRows(plain_db, "SELECT key FROM runs"), test::sqlRows(eth_db, "SELECT key FROM runs"));
  EXPECT_NE(test::sqlRows(plain_db, duration), test::sqlRows(eth_db, duration));
  EXPECT_EQ(test::sqlRows(plain_db, "SELECT COUNT(*) FROM metrics WHERE name = 'turn_cost_s'"), "0\n");
  EXPECT_EQ(test::sqlRows(eth_db, "SELECT m.value = 5 * t.value FROM metrics m JOIN metrics t ON t.run_key = m.run_key "
                                  "WHERE m.name = 'turn_cost_s' AND t.name = 'turns'"),
            "1\n");
  // The same path scored by the metrics command under the same model gives the stored duration.
  std::string out;
  ASSERT_EQ(run("plan --wall " + wall + " --planner zigzag --tool-width 0.2 --clearance 0.02 --out " +
                (dir_ / "p.json").string()).exit_code, 0);
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + (dir_ / "p.json").string() +
                " --speed 3 --acceleration 1 --stops waypoints --turn-cost 5", &out).exit_code, 0) << out;
  EXPECT_NEAR(std::stod(test::sqlRows(eth_db, duration)), jsonNumber(out, "duration_s"), 1e-9);
  EXPECT_NEAR(std::stod(test::sqlRows(eth_db, "SELECT value FROM metrics WHERE name = 'turn_cost_s'")),
              jsonNumber(out, "turn_cost_s"), 1e-9);
  ASSERT_EQ(run("report " + eth_db + " --format md", &out).exit_code, 0);
  EXPECT_NE(out.find("Time model of duration\\_s: v 3 m/s, a 1 m/s2, stops at every waypoint, 5 s per turn (turn\\_cost\\_s)."),
            std::string::npos) << out.substr(0, 600);
  ASSERT_EQ(run("report " + plain_db + " --format md", &out).exit_code, 0);
  EXPECT_NE(out.find("Time model of duration\\_s: v 0.3 m/s, a 0.5 m/s2, stops at turns over 30 degrees."), std::string::npos)
      << out.substr(0, 600);
  const CommandRun bad = run("run " + config("bad", "motion: {stops: everywhere}\n"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.yaml:7: motion.stops: must be turns or waypoints, got 'everywhere'"), std::string::npos) << bad.err;

  // The clock that turns (docs/metrics.md): stored durations equal the metrics command's, and
  // exceed the same path's length / v by its turning at omega.
  ASSERT_EQ(run("run " + config("ipa", "motion: {speed: 0.3, acceleration: inf, rotation_speed: 0.52}\n") + " --no-report").exit_code, 0);
  const std::string ipa_db = (dir_ / "ipa" / "results.sqlite").string();
  EXPECT_NE(test::sqlRows(plain_db, "SELECT key FROM runs"), test::sqlRows(ipa_db, "SELECT key FROM runs"));
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + (dir_ / "p.json").string() +
                " --speed 0.3 --acceleration inf --rotation-speed 0.52", &out).exit_code, 0) << out;
  EXPECT_NEAR(std::stod(test::sqlRows(ipa_db, duration)), jsonNumber(out, "duration_s"), 1e-9);
  // By hand: three sides of a 2 x 1 m rectangle, 5 m and two quarter turns.
  const std::string box = write("box.json", R"({"waypoints": [[0.2, 0.2], [2.2, 0.2], [2.2, 1.2], [0.2, 1.2]],
    "tool_on": [true, true, true]})");
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + box + " --speed 0.3 --acceleration inf --rotation-speed 0.52", &out)
                .exit_code, 0) << out;
  EXPECT_NEAR(jsonNumber(out, "duration_s"), 5.0 / 0.3 + M_PI / 0.52, 1e-9) << out;
  ASSERT_EQ(run("report " + ipa_db + " --format md", &out).exit_code, 0);
  EXPECT_NE(out.find("v 0.3 m/s, no ramp, stops at turns over 30 degrees, rotates in place at 0.52 rad/s."), std::string::npos)
      << out.substr(0, 600);
  const CommandRun fast = run("run " + config("fast", "motion: {rotation_speed: 101}\n"));
  EXPECT_EQ(fast.exit_code, 2);
  EXPECT_NE(fast.err.find("fast.yaml:7: motion.rotation_speed: must be in [0, 100], got 101"), std::string::npos) << fast.err;
}

TEST_F(Cli, DatasetGenerateIsByteIdenticalAcrossInvocations) {
  std::string out;
  ASSERT_EQ(run("dataset generate --family stairwell --count 3 --seed 11 --out " + (dir_ / "a").string(), &out).exit_code, 0);
  ASSERT_EQ(run("dataset generate --family stairwell --count 3 --seed 11 --out " + (dir_ / "b").string(), &out).exit_code, 0);
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "a")) {
    EXPECT_EQ(slurp(entry.path().string()), slurp((dir_ / "b" / entry.path().filename()).string())) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 4);  // three walls and the manifest
  ASSERT_EQ(run("dataset show " + (dir_ / "a").string(), &out).exit_code, 0);
  EXPECT_NE(out.find("walls: 3"), std::string::npos) << out;
  const CommandRun bad = run("dataset generate --family stairwel --count 3 --out " + (dir_ / "c").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(lines(bad.err), 1) << bad.err;
  EXPECT_NE(bad.err.find("unknown family 'stairwel'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "c"));
}

TEST_F(Cli, RunRejectsABadConfigBeforeAnyRunAndReportsAGoodOne) {
  const std::string bad = write("bad.yaml", "name: x\noutput: out\ndatasets:\n  - suite: seed-cases\nplanners:\n  - zigzag\ntool:\n  widht: 0.1\n");
  const CommandRun r = run("run " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.yaml:8: tool.widht: unknown key (did you mean 'width'?)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "nothing is written for a bad config";

  const std::string good = write("good.yaml", "name: x\noutput: out\ndatasets:\n  - family: residential\n    count: 2\n    seed: 3\nplanners: [all]\n");
  std::string out;
  ASSERT_EQ(run("run " + good, &out).exit_code, 0) << out;
  const std::string runs = std::to_string(2 * registeredPlanners().size());
  EXPECT_NE(out.find("(" + runs + " executed, 0 already stored)"), std::string::npos) << out;
  const std::string md = slurp((dir_ / "out" / "report" / "report.md").string());
  EXPECT_NE(md.find("## Run outcomes per planner"), std::string::npos);
  ASSERT_EQ(run("report " + (dir_ / "out" / "results.sqlite").string() + " --format md", &out).exit_code, 0);
  EXPECT_EQ(out, md);
  ASSERT_EQ(run("run " + good, &out).exit_code, 0);
  EXPECT_NE(out.find("(0 executed, " + runs + " already stored)"), std::string::npos) << out;
  EXPECT_EQ(slurp((dir_ / "out" / "report" / "report.md").string()), md);
  EXPECT_EQ(run("report " + (dir_ / "out" / "results.sqlite").string() + " --format html").exit_code, 2);
  ASSERT_EQ(run("report " + (dir_ / "out" / "results.sqlite").string() + " --baseline spiral", &out).exit_code, 0);
  EXPECT_NE(out.find("| zigzag | spiral | coverage\\_reachable |"), std::string::npos) << out;
  EXPECT_EQ(run("report " + (dir_ / "out" / "results.sqlite").string() + " --baseline nobody").exit_code, 2);

  // Any stored run can be redrawn from the database alone.
  const ExperimentConfig config = loadExperimentConfig(good);
  const std::vector<WallEntry> walls = loadWalls(config);
  const std::string key = expandRuns(config, walls).front().key;
  const std::string svg = (dir_ / "run.svg").string();
  ASSERT_EQ(run("redraw " + (dir_ / "out" / "results.sqlite").string() + " --run " + key.substr(0, 10) + " --svg " + svg, &out)
                .exit_code, 0) << out;
  EXPECT_NE(slurp(svg).find("<svg"), std::string::npos);
  EXPECT_EQ(run("redraw " + (dir_ / "out" / "results.sqlite").string() + " --run 000000000 --svg " + svg).exit_code, 2);
}

// `redraw --coat-svg` draws a stored run's coat from its experiment's flux profile and time
// model: the picture `metrics --coat-svg` draws of the same path with that profile and clock (a
// redraw that missed the profile would fail, one that missed the clock would draw another coat),
// all but the title. A run whose tool has no profile: one line, nothing written.
TEST_F(Cli, RedrawDrawsARunsCoatAsMetricsDoes) {
  fs::create_directories(dir_ / "walls");
  write("walls/w.json", R"({"name": "w", "width": 2.0, "height": 1.2, "obstacles": [
        {"type": "rect", "x": 0.8, "y": 0.4, "width": 0.4, "height": 0.3}]})");
  const std::string config = write("coat.yaml", "name: coat\noutput: out\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n"
                                                "tool:\n  width: 0.3\n  profile: {kind: beta, beta: 2.5}\nmotion:\n  speed: 0.5\n");
  const CommandRun ran = run("run " + config + " --no-report");
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  const std::string db = (dir_ / "out" / "results.sqlite").string();
  const ExperimentConfig c = loadExperimentConfig(config);
  const std::string key = expandRuns(c, loadWalls(c)).front().key;
  const std::string wall = (dir_ / "wall.json").string(), plan = (dir_ / "plan.json").string();
  {
    ResultsDb results(db, ResultsDb::Mode::ReadOnly);
    const ResultsDb::StoredRun stored = results.storedRun(key);
    ASSERT_TRUE(stored.tool.profile.set());
    EXPECT_EQ(stored.motion.speed, 0.5);
    ASSERT_GT(stored.path.segments(), 0u);
    writeFileAtomically(wall, wallToJson(stored.wall));
    PlanFile file;
    file.planner = "zigzag";
    file.wall = stored.wall.name;
    file.tool = stored.tool;
    file.result.path = stored.path;
    writeFileAtomically(plan, planFileJson(file));
  }
  const std::string redrawn = (dir_ / "redrawn.svg").string(), scored = (dir_ / "scored.svg").string();
  std::string out;
  ASSERT_EQ(run("redraw " + db + " --run " + key.substr(0, 12) + " --svg " + (dir_ / "run.svg").string() + " --coat-svg " + redrawn, &out)
                .exit_code, 0) << out;
  EXPECT_NE(out.find("its coat -> " + redrawn), std::string::npos) << out;
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + plan + " --profile beta --beta 2.5 --speed 0.5 --coat-svg " + scored).exit_code, 0);
  auto untitled = [](std::string svg) {  // the title is the one line in bold
    const std::size_t at = svg.find("font-weight=\"bold\">");
    EXPECT_NE(at, std::string::npos);
    return svg.erase(at, svg.find("</text>", at) - at);
  };
  const std::string a = slurp(redrawn), b = slurp(scored);
  EXPECT_NE(a.find("coat thickness"), std::string::npos);
  EXPECT_EQ(untitled(a), untitled(b));
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + plan + " --profile beta --beta 2.5 --coat-svg " + scored).exit_code, 0);
  EXPECT_NE(untitled(a), untitled(slurp(scored))) << "the default clock lays another coat";

  const std::string plain = write("plain.yaml", "name: plain\noutput: plain\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n");
  ASSERT_EQ(run("run " + plain + " --no-report").exit_code, 0);
  const ExperimentConfig p = loadExperimentConfig(plain);
  const std::string plain_key = expandRuns(p, loadWalls(p)).front().key;
  const std::string none = (dir_ / "none.svg").string();
  const CommandRun refused = run("redraw " + (dir_ / "plain" / "results.sqlite").string() + " --run " + plain_key.substr(0, 12) +
                                 " --svg " + none + " --coat-svg " + (dir_ / "none-coat.svg").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(lines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("--coat-svg: tool.profile: run " + plain_key.substr(0, 12) + "'s tool has no flux profile"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(none));
  EXPECT_FALSE(fs::exists(dir_ / "none-coat.svg"));
}

TEST_F(Cli, ReportFolderIsAllOrNothingAndNeverReplacesAUsersFolder) {
  const std::string config = write("r.yaml", "name: r\noutput: out\ndatasets:\n  - family: residential\n    count: 1\n    seed: 3\nplanners: [zigzag, spiral]\n");
  ASSERT_EQ(run("run " + config + " --no-report").exit_code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "report")) << "--no-report writes none";
  const std::string db = (dir_ / "out" / "results.sqlite").string();
  // A folder of the user's is refused, and left as it was.
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "notes.txt") << "keep";
  CommandRun r = run("report " + db + " --format html --out " + (dir_ / "mine").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("is a folder that is not a CoverBench report"), std::string::npos) << r.err;
  EXPECT_EQ(slurp((dir_ / "mine" / "notes.txt").string()), "keep");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "mine"), fs::directory_iterator()), 1);
  // The analysis missing: one line naming what to install, nothing written, nothing left behind.
  std::string printed;
  setenv("COVERBENCH_PYTHON", (dir_ / "no-python").c_str(), 1);
  r = run("report " + db + " --format html --out " + (dir_ / "rep").string(), &printed);
  unsetenv("COVERBENCH_PYTHON");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("python3-matplotlib python3-scipy"), std::string::npos) << r.err;
  EXPECT_EQ(printed, "");
  EXPECT_FALSE(fs::exists(dir_ / "rep"));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find("staging"), std::string::npos) << entry.path();
  // A report there is written, and written again over itself.
  ASSERT_EQ(run("report " + db + " --format html --out " + (dir_ / "rep").string()).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "index.html"));
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "report.tex"));
  ASSERT_EQ(run("report " + db + " --format html --out " + (dir_ / "rep").string()).exit_code, 0);
  EXPECT_EQ(run("report " + db + " --format pdf").exit_code, 2);
}

TEST_F(Cli, RunLimitsBecomeStatusesInTheTables) {
  // 20 KiB of address space beyond the worker's is far below what any planner needs on a facade
  // at s = 0.05 m (megabytes; a run needing less may fit in the heap a worker inherits free from
  // the runner, as on residential walls at 0.1 m); a microsecond of time expires before the
  // first budget check.
  const std::string memory = write("m.yaml", "name: m\noutput: m\ndatasets:\n  - family: facade\n    count: 2\n    seed: 3\nplanners: [all]\ntool:\n  width: 0.05\nlimits:\n  memory_mb: 0.02\n");
  ASSERT_EQ(run("run " + memory).exit_code, 0);
  const std::string md = slurp((dir_ / "m" / "report" / "report.md").string());
  EXPECT_NE(md.find("| zigzag | 2 | 0 | 2 | 0.0 % |"), std::string::npos) << md;  // runs, ok, memory_limit, success
  EXPECT_NE(md.find("memory\\_limit"), std::string::npos) << md;  // escaped: Markdown would set _x_ in italics
  const std::string time = write("t.yaml", "name: t\noutput: t\ndatasets:\n  - family: facade\n    count: 1\n    seed: 3\nplanners: [all]\nlimits:\n  time_s: 0.000001\n");
  ASSERT_EQ(run("run " + time).exit_code, 0);
  const std::string tmd = slurp((dir_ / "t" / "report" / "report.md").string());
  EXPECT_NE(tmd.find("| timeout |"), std::string::npos) << tmd;
}

// GDAL (110 shared libraries, 0.1 s of CPU at each start) is loaded by an import only: the
// loader's own account (LD_DEBUG=files names each library it opens) of a plan and of an import.
TEST_F(Cli, OnlyAnImportLoadsGdal) {
  const std::string wkt = write("w.wkt", "POLYGON ((0 0, 10 0, 10 5, 0 5, 0 0), (2 2, 3 2, 3 3, 2 3, 2 2))\n");
  const std::string plan = (dir_ / "plan.json").string();
  ::setenv("LD_DEBUG", "files", 1);
  const CommandRun planned = run("plan --wall " + test::sourcePath("datasets/canonical/seed_5x5_1obs.json") +
                                 " --planner zigzag --out " + plan);
  const CommandRun imported = run("dataset import " + wkt + " --out " + (dir_ / "imported").string());
  ::setenv("COVERBENCH_GDAL_PLUGIN", "/nonexistent/libcoverbench_gdal.so", 1);
  const CommandRun refused = run("dataset import " + wkt + " --out " + (dir_ / "refused").string());
  ::unsetenv("COVERBENCH_GDAL_PLUGIN");
  ::unsetenv("LD_DEBUG");
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_EQ(planned.err.find("libgdal"), std::string::npos) << "a plan loaded GDAL";
  EXPECT_NE(imported.err.find("libgdal"), std::string::npos) << "the import did not load GDAL through the plug-in?";
  EXPECT_NE(imported.err.find("libcoverbench_gdal.so"), std::string::npos);
  // A plug-in that cannot be opened: one line, exit 2, nothing written.
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("coverbench: GDAL: (plug-in): cannot be opened, so this format cannot be imported: "
                             "/nonexistent/libcoverbench_gdal.so does not exist\n"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "refused"));
}

// OMPL (with Boost's libraries, ODE, FCL) and cpp-httplib (with OpenSSL and Brotli) are loaded
// only by what uses them, through their plug-ins: the loader's own account (LD_DEBUG=files) of
// --version, a plan, a plan with a sampling transit and `serve`. A plug-in that cannot be opened
// is one line naming the file.
TEST_F(Cli, OnlyTheirCommandsLoadOmplAndHttplib) {
  const std::string wall = test::sourcePath("datasets/canonical/seed_5x5_1obs.json");
  const std::string plan = (dir_ / "plan.json").string(), sampled = (dir_ / "sampled.json").string();
  ::setenv("LD_DEBUG", "files", 1);
  const CommandRun version = run("--version");
  const CommandRun planned = run("plan --wall " + wall + " --planner boustrophedon --out " + plan);
  const CommandRun sampling = run("plan --wall " + wall + " --planner boustrophedon --transit rrtstar --out " + sampled);
  const CommandRun served = run("serve --port 65536");  // the server's own check refuses the port
  ::unsetenv("LD_DEBUG");
  ::setenv("COVERBENCH_OMPL_PLUGIN", "/nonexistent/libcoverbench_ompl.so", 1);
  const CommandRun no_ompl = run("plan --wall " + wall + " --planner boustrophedon --transit rrtstar --out " +
                                 (dir_ / "no_ompl.json").string());
  ::unsetenv("COVERBENCH_OMPL_PLUGIN");
  ::setenv("COVERBENCH_SERVE_PLUGIN", "/nonexistent/libcoverbench_serve.so", 1);
  const CommandRun no_server = run("serve --port 0");
  // A FIFO in its place is refused, not read (dlopen would wait for a writer for ever).
  const std::string fifo = (dir_ / "libcoverbench_serve.so").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  ::setenv("COVERBENCH_SERVE_PLUGIN", fifo.c_str(), 1);
  const CommandRun fifo_server = run("serve --port 0");
  ::unsetenv("COVERBENCH_SERVE_PLUGIN");

  ASSERT_EQ(version.exit_code, 0) << version.err;
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  for (const CommandRun* r : {&version, &planned})
    for (const char* lib : {"libompl", "libcoverbench_ompl", "libcpp-httplib", "libssl", "libbrotli", "libcoverbench_serve"})
      EXPECT_EQ(r->err.find(lib), std::string::npos) << lib << " loaded by " << (r == &version ? "--version" : "plan");
  // The sampling transit loads OMPL through its plug-in and plans.
  ASSERT_EQ(sampling.exit_code, 0) << sampling.err;
  EXPECT_NE(sampling.err.find("libcoverbench_ompl.so"), std::string::npos);
  EXPECT_NE(sampling.err.find("libompl"), std::string::npos);
  EXPECT_EQ(sampling.err.find("libcpp-httplib"), std::string::npos);
  EXPECT_NE(slurp(sampled).find("\"status\": \"ok\""), std::string::npos);
  // `serve` loads httplib through its plug-in, whose refusal is the command's one line and exit 2.
  EXPECT_EQ(served.exit_code, 2) << served.err;
  EXPECT_NE(served.err.find("libcoverbench_serve.so"), std::string::npos);
  EXPECT_NE(served.err.find("libcpp-httplib"), std::string::npos);
  EXPECT_NE(served.err.find("coverbench: --port: port: must be from 0 to 65535, got 65536\n"), std::string::npos) << served.err;
  // Without the plug-ins: the file named, in one line.
  EXPECT_EQ(no_ompl.exit_code, 2);
  EXPECT_EQ(no_ompl.err, "coverbench: OMPL: (plug-in): cannot be opened, so the sampling transit planners cannot run: "
                         "/nonexistent/libcoverbench_ompl.so does not exist\n");
  EXPECT_FALSE(fs::exists(dir_ / "no_ompl.json"));
  EXPECT_EQ(no_server.exit_code, 2);
  EXPECT_EQ(no_server.err, "coverbench: cpp-httplib: (plug-in): cannot be opened, so the explorer cannot be served: "
                           "/nonexistent/libcoverbench_serve.so does not exist\n");
  EXPECT_EQ(fifo_server.exit_code, 2);
  EXPECT_EQ(fifo_server.err, "coverbench: cpp-httplib: (plug-in): cannot be opened, so the explorer cannot be served: " + fifo +
                                 " is not a regular file\n");
}

TEST_F(Cli, BadWallGivesOneLineAndNoOutput) {
  const std::string wall = write("bad.json", R"({"width": 5, "height": -1})");
  const std::string out = (dir_ / "plan.json").string();
  const CommandRun r = run("plan --wall " + wall + " --planner zigzag --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(wall + ": height: must be positive"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, BadParameterGivesOneLineAndNoOutput) {
  const std::string out = (dir_ / "plan.json").string();
  const CommandRun r = run("plan --wall " + test::sourcePath("datasets/canonical/seed_1x1_empty.json") +
                    " --planner spiral --param overlap=1.5 --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--param: overlap: 1.5 is out of range"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, BadToolWidthAndUnknownPlanner) {
  const std::string wall = test::sourcePath("datasets/canonical/seed_1x1_empty.json");
  const std::string out = (dir_ / "plan.json").string();
  CommandRun r = run("plan --wall " + wall + " --planner zigzag --tool-width -0.1 --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tool_width: must be in [0.001, 10] m"), std::string::npos) << r.err;
  r = run("plan --wall " + wall + " --planner nope --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--planner: nope: unknown planner"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, PlannerFailureIsWrittenWithStatusAndNonZeroExit) {
  const std::string out = (dir_ / "plan.json").string();
  const CommandRun r = run("plan --wall " + test::sourcePath("datasets/conformance/exactly_tool_height.json") +
                    " --planner zigzag --out " + out);
  EXPECT_EQ(r.exit_code, 3);
  std::ifstream plan(out);
  std::stringstream text;
  text << plan.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"no_reachable_area\""), std::string::npos) << text.str();
}

TEST_F(Cli, SameInputsGiveByteIdenticalPlanFilesApartFromTheMeasuredSection) {
  // boustrophedon reports its own sub-timings: they too belong to the measured section.
  const std::string wall = test::sourcePath("datasets/canonical/gable_round_window.json");
  auto plan_text = [&](const std::string& planner, const std::string& name) {
    const std::string out = (dir_ / name).string();
    EXPECT_EQ(run("plan --wall " + wall + " --planner " + planner + " --out " + out).exit_code, 0);
    return slurp(out);
  };
  for (const char* planner : {"spiral", "boustrophedon"}) {
    const std::string a = plan_text(planner, "a.json"), b = plan_text(planner, "b.json");
    const std::size_t at = a.find("\n \"measured\": {\n");
    ASSERT_NE(at, std::string::npos) << a;
    EXPECT_EQ(a.substr(0, at), b.substr(0, b.find("\n \"measured\": {\n"))) << planner;
    // The measured section is the last key and holds only measurements.
    const std::string measured = a.substr(at);
    EXPECT_EQ(measured.find("\n \""), measured.rfind("\n \"")) << measured;  // no other top-level key after it
    EXPECT_NE(measured.find("\"plan_time_ms\""), std::string::npos);
    EXPECT_NE(measured.find("\"planner_ms\""), std::string::npos);
    EXPECT_EQ(a.substr(0, at).find("_ms\""), std::string::npos) << "a timing outside the measured section";
  }
}

}  // namespace
}  // namespace coverbench
