// The tool's shape (docs/metrics.md#tool-shapes) through configs, run keys, the results database,
// `coverbench runs`, shards, plan files and the command line: a line tool's runs are keyed,
// stored, listed and scored as a line, a rectangle's as a rectangle of its depth; a disk's keep
// everything they had.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "coverbench/results_db.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

class ToolShapeRuns : public test::CommandTest {
 protected:
  /// Runs zigzag and spiral on one 2 x 1 m wall with a window and the config's `tool:` section (and
  /// `extra` after it); the results database.
  std::string experiment(const std::string& name, const std::string& tool, const std::string& extra = "") {
    fs::create_directories(dir_ / "walls");
    std::ofstream(dir_ / "walls" / "a.json")
        << R"({"name": "a", "width": 2, "height": 1, "obstacles": [{"type": "rect", "x": 0.8, "y": 0.3, "width": 0.3, "height": 0.3}]})";
    const std::string config = write(name + ".yaml", "name: " + name + "\noutput: " + name +
                                                         "\ndatasets:\n  - folder: walls\nplanners: [zigzag, spiral]\n" + tool + extra);
    const test::CommandRun r = run("run " + config + " --no-report");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return (dir_ / name / "results.sqlite").string();
  }
  std::string runs(const std::string& db, const std::string& flags) {
    std::string out;
    const test::CommandRun r = run("runs " + db + " " + flags, &out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }
};

TEST_F(ToolShapeRuns, ALineToolsRunsAreKeyedStoredListedAndScoredAsALine) {
  const std::string disk = experiment("disk", "tool:\n  width: 0.2\n");
  const std::string named = experiment("named", "tool:\n  width: 0.2\n  shape: disk\n");
  const std::string line = experiment("line", "tool:\n  width: 0.2\n  shape: line\n");
  // `shape: disk` is the default: the same keys; a line's keys are others.
  const std::string disk_keys = test::sqlRows(disk, "SELECT base_key FROM runs ORDER BY base_key");
  EXPECT_EQ(test::sqlRows(named, "SELECT base_key FROM runs ORDER BY base_key"), disk_keys);
  EXPECT_NE(test::sqlRows(line, "SELECT base_key FROM runs ORDER BY base_key"), disk_keys);
  EXPECT_EQ(test::sqlRows(disk, "SELECT COUNT(*) FROM run_tool_shape"), "0\n");
  EXPECT_EQ(test::sqlRows(line, "SELECT shape, COUNT(*) FROM run_tool_shape GROUP BY shape"), "line|2\n");
  const ResultSet l = ResultsDb(line, ResultsDb::Mode::ReadOnly).load(), d = ResultsDb(disk, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(l.runs.size(), 2u);
  ASSERT_EQ(d.runs.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const ResultRow& r = l.runs[i];
    EXPECT_TRUE(r.tool.isLine());
    EXPECT_EQ(std::string(toString(r.status)), "ok") << r.reason;
    // zigzag plans the line itself; spiral plans for its circumscribed disk and says so.
    if (r.planner.rfind("zigzag", 0) == 0)
      EXPECT_EQ(r.reason.find("circumscribed"), std::string::npos) << r.reason;
    else
      EXPECT_NE(r.reason.find("planned for the line tool's circumscribed disk"), std::string::npos) << r.reason;
    // Its R is the wall minus the window grown by c: larger than the disk's.
    EXPECT_NEAR(r.metrics.at("reachable_area"), 2.0 - (0.34 * 0.34 - (4 - M_PI) * 0.02 * 0.02), 2e-6);
  }
  EXPECT_LT(d.runs[0].metrics.at("reachable_area"), l.runs[0].metrics.at("reachable_area"));
  // Listed with its shape: in the tool's label, and in a column present only when some run has one.
  EXPECT_NE(runs(line, "--list").find("line s=0.2 m, c=0.02 m"), std::string::npos) << runs(line, "--list");
  EXPECT_EQ(runs(line, "").rfind("key,dataset,wall,wall_hash,planner,params,planner_version,tool_width,clearance,tool_shape,", 0), 0u);
  EXPECT_EQ(nlohmann::json::parse(runs(line, "--format json"))[0]["tool_shape"], "line");
  EXPECT_EQ(runs(disk, "").find("tool_shape"), std::string::npos);
  EXPECT_EQ(runs(disk, "--format json").find("tool_shape"), std::string::npos);
  // Its stored path redrawn is a line's: the run's tool read back with its shape.
  const std::string key = test::sqlRows(line, "SELECT key FROM runs LIMIT 1").substr(0, 12);
  EXPECT_TRUE(ResultsDb(line, ResultsDb::Mode::ReadOnly).storedRun(key).tool.isLine());
  // A database without the table (one made before shapes) reads its runs as disks.
  test::sqlRows(line, "DROP TABLE run_tool_shape");
  for (const ResultRow& r : ResultsDb(line, ResultsDb::Mode::ReadOnly).load().runs) EXPECT_FALSE(r.tool.isLine());
}

// A disk and a line of the same width in one experiment are two tools: each planner has a column
// of each, and a run pairs only with runs of its own tool.
TEST_F(ToolShapeRuns, BothShapesInOneExperimentAreTwoToolsNeverPooled) {
  const std::string db = experiment("both", "tool:\n  width: 0.2\n  shape: [disk, line]\n");
  const ResultSet rs = ResultsDb(db, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 4u);
  std::vector<std::string> columns = rs.planners;
  std::sort(columns.begin(), columns.end());
  EXPECT_EQ(columns, (std::vector<std::string>{"spiral @ line s=0.2 m, c=0.02 m", "spiral @ s=0.2 m, c=0.02 m",
                                               "zigzag @ line s=0.2 m, c=0.02 m", "zigzag @ s=0.2 m, c=0.02 m"}));
  for (const ResultRow& r : rs.runs) {
    EXPECT_EQ(r.planner.find(" @ line ") != std::string::npos, r.tool.isLine()) << r.planner;
    EXPECT_EQ(r.pairing.size() >= 5 && r.pairing.substr(r.pairing.size() - 5) == "/line", r.tool.isLine()) << r.pairing;
  }
  // The explorer's summaries (its tool facet: toolAndProfileLabel) carry the shape too.
  ResultsDb results(db, ResultsDb::Mode::ReadOnly);
  std::set<std::string> labels;
  for (const ResultsDb::RunSummary& r : results.runSummaries(results.experiments().back().id)) labels.insert(toolAndProfileLabel(r.tool));
  EXPECT_EQ(labels, (std::set<std::string>{"line s=0.2 m, c=0.02 m", "s=0.2 m, c=0.02 m"}));
}

// Rectangles of two depths beside a line of their width: three tools, each keyed, stored, listed
// and paired on its own. spiral plans for the rectangle's circumscribed disk and says so, zigzag
// for the rectangle itself; every path is valid as a rectangle; a database without run_tool_depth
// refuses a rectangle's run.
TEST_F(ToolShapeRuns, ARectanglesRunsAreKeyedStoredListedAndScoredWithItsDepth) {
  const std::string db = experiment("rect", "tool:\n  width: 0.2\n  shape: [line, rectangle]\n  depth: [0.05, 0.1]\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT shape, COUNT(*) FROM run_tool_shape GROUP BY shape"), "line|2\nrectangle|4\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT depth, COUNT(*) FROM run_tool_depth GROUP BY depth"), "0.05|2\n0.1|2\n");
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(DISTINCT base_key) FROM runs"), "6\n");
  const ResultSet rs = ResultsDb(db, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 6u);
  std::set<std::string> columns(rs.planners.begin(), rs.planners.end()), pairings;
  EXPECT_TRUE(columns.count("zigzag @ rectangle s=0.2 m, d=0.05 m, c=0.02 m")) << *columns.begin();
  EXPECT_TRUE(columns.count("zigzag @ rectangle s=0.2 m, d=0.1 m, c=0.02 m"));
  EXPECT_TRUE(columns.count("zigzag @ line s=0.2 m, c=0.02 m"));
  for (const ResultRow& r : rs.runs) {
    pairings.insert(r.pairing);
    EXPECT_EQ(r.metrics.at("valid"), 1.0);
    if (r.planner.rfind("zigzag", 0) == 0) {
      // zigzag plans the shape itself: a rectangle 0.1 m deep cannot turn near enough to the
      // window's sides to paint all of R, and the run says so.
      EXPECT_EQ(r.reason.find("circumscribed"), std::string::npos) << r.reason;
      if (r.status != RunStatus::Ok) {
        EXPECT_EQ(std::string(toString(r.status)), "partial") << r.planner << ": " << r.reason;
        EXPECT_NE(r.reason.find("where it cannot turn at a row end"), std::string::npos) << r.reason;
      }
      continue;
    }
    EXPECT_EQ(std::string(toString(r.status)), "ok") << r.planner << ": " << r.reason;
    if (!r.tool.isRectangle()) continue;
    // 2R = sqrt(0.2^2 + 0.05^2) = 0.2062 m, sqrt(0.2^2 + 0.1^2) = 0.2236 m.
    const std::string disk = r.tool.depth == 0.05 ? "0.2062" : "0.2236";
    EXPECT_NE(r.reason.find("planned for the rectangle tool's circumscribed disk (diameter sqrt(s^2 + d^2) = " + disk + " m)"),
              std::string::npos) << r.reason;
  }
  EXPECT_EQ(pairings.size(), 3u);  // a run pairs only with runs of its own tool
  EXPECT_NE(runs(db, "--list").find("rectangle s=0.2 m, d=0.1 m, c=0.02 m"), std::string::npos);
  EXPECT_EQ(runs(db, "").rfind("key,dataset,wall,wall_hash,planner,params,planner_version,tool_width,clearance,tool_shape,tool_depth,", 0), 0u);
  const std::string key = test::sqlRows(db, "SELECT run_key FROM run_tool_depth WHERE depth = 0.1 LIMIT 1").substr(0, 12);
  const ResultsDb::StoredRun stored = ResultsDb(db, ResultsDb::Mode::ReadOnly).storedRun(key);
  EXPECT_TRUE(stored.tool.isRectangle());
  EXPECT_EQ(stored.tool.depth, 0.1);
  test::sqlRows(db, "DROP TABLE run_tool_depth");
  EXPECT_THROW(ResultsDb(db, ResultsDb::Mode::ReadOnly).load(), std::exception);
}

TEST_F(ToolShapeRuns, ShardsMergeWithTheirShapes) {
  experiment("walls", "");
  const std::string config = write("shard.yaml", "name: shard\noutput: shard\ndatasets:\n  - folder: walls\n"
                                                 "planners: [zigzag, spiral]\ntool:\n  width: [0.2, 0.3]\n  shape: line\n");
  for (const char* shard : {"0/2", "1/2"}) ASSERT_EQ(run("run " + config + " --shard " + shard).exit_code, 0) << shard;
  const std::string shards = (dir_ / "shard" / "shards").string(), merged = (dir_ / "merged.sqlite").string();
  ASSERT_EQ(run("merge " + merged + " " + shards + "/shard-0-of-2.sqlite " + shards + "/shard-1-of-2.sqlite").exit_code, 0);
  EXPECT_EQ(test::sqlRows(merged, "SELECT COUNT(*) FROM run_tool_shape"), "4\n");
  EXPECT_EQ(test::sqlRows(merged, "SELECT COUNT(*) FROM runs"), "4\n");
}

TEST_F(ToolShapeRuns, AShapeThatIsNotBuiltIsOneLineNamingTheField) {
  fs::create_directories(dir_ / "walls");
  std::ofstream(dir_ / "walls" / "a.json") << R"({"name": "a", "width": 2, "height": 1})";
  auto refused = [&](const std::string& name, const std::string& body, const std::string& expected) {
    const std::string config = write(name + ".yaml", "name: " + name + "\noutput: " + name +
                                                         "\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n" + body);
    const test::CommandRun r = run("run " + config + " --no-report");
    EXPECT_EQ(r.exit_code, 2) << name;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / name / "results.sqlite")) << name;
  };
  refused("square", "tool:\n  shape: square\n", "square.yaml:7: tool.shape: must be disk, line or rectangle, got 'square'");
  refused("twice", "tool:\n  shape: [line, line]\n", "twice.yaml:7: tool.shape: lists line twice");
  refused("car", "tool:\n  shape: line\nvehicle:\n  model: car\n", "tool.shape: a line tool is not built for a car yet");
  refused("nodepth", "tool:\n  shape: rectangle\n", "nodepth.yaml:7: tool.depth: is missing: a rectangle tool's depth along the heading, m");
  refused("diskdepth", "tool:\n  shape: line\n  depth: 0.1\n", "diskdepth.yaml:8: tool.depth: belongs to a rectangle tool");
  refused("thin", "tool:\n  shape: rectangle\n  depth: 0\n", "thin.yaml:8: tool.depth: must be in [0.001, 10], got 0");
  refused("rcar", "tool:\n  shape: rectangle\n  depth: 0.1\nvehicle:\n  model: car\n", "tool.shape: a rectangle tool is not built for a car yet");
}

TEST_F(ToolShapeRuns, PlanAndMetricsTakeTheShapeAndPlanFilesCarryIt) {
  fs::create_directories(dir_ / "walls");
  const std::string wall = write("a.json", R"({"name": "a", "width": 2, "height": 1})");
  const std::string plan = (dir_ / "plan.json").string();
  std::string out;
  ASSERT_EQ(run("plan --wall " + wall + " --planner spiral --tool-width 0.2 --tool-shape line --out " + plan, &out).exit_code, 0);
  EXPECT_NE(out.find("circumscribed disk"), std::string::npos) << out;
  const nlohmann::json doc = nlohmann::json::parse(slurp(plan));
  EXPECT_EQ(doc["tool_shape"], "line");
  // Scored again from the file, as a line (its shape read back), and as a disk when told so.
  std::string line_json, disk_json;
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + plan, &line_json).exit_code, 0);
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + plan + " --tool-shape disk", &disk_json).exit_code, 0);
  const double line_r = nlohmann::json::parse(line_json)["reachable_area"].get<double>();
  EXPECT_NEAR(line_r, 2.0, 1e-9);  // no obstacles: the whole wall
  EXPECT_EQ(line_r, doc["metrics"]["reachable_area"].get<double>());
  EXPECT_LT(nlohmann::json::parse(disk_json)["reachable_area"].get<double>(), line_r);
  // A rectangle's plan file carries its depth; scored again from it, as that rectangle.
  const std::string rect_plan = (dir_ / "rect.json").string();
  ASSERT_EQ(run("plan --wall " + wall + " --planner zigzag --tool-width 0.2 --tool-shape rectangle --tool-depth 0.1 --out " + rect_plan, &out).exit_code, 0) << out;
  const nlohmann::json rect_doc = nlohmann::json::parse(slurp(rect_plan));
  EXPECT_EQ(rect_doc["tool_shape"], "rectangle");
  EXPECT_EQ(rect_doc["tool_depth"], 0.1);
  EXPECT_EQ(rect_doc["metrics"]["valid"], true);
  std::string rect_json, shallow_json;
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + rect_plan, &rect_json).exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(rect_json)["swept_area"], rect_doc["metrics"]["swept_area"]);
  ASSERT_EQ(run("metrics --wall " + wall + " --plan " + rect_plan + " --tool-depth 0.05", &shallow_json).exit_code, 0);
  EXPECT_LT(nlohmann::json::parse(shallow_json)["swept_area"].get<double>(), rect_doc["metrics"]["swept_area"].get<double>());
  const test::CommandRun deep = run("plan --wall " + wall + " --planner zigzag --tool-shape line --tool-depth 0.1 --out " + (dir_ / "bad.json").string());
  EXPECT_EQ(deep.exit_code, 2);
  EXPECT_NE(deep.err.find("tool_depth: a depth belongs to a rectangle; a line has none"), std::string::npos) << deep.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.json"));
  // A disk's plan file has no key, as before shapes.
  const std::string disk_plan = (dir_ / "disk.json").string();
  ASSERT_EQ(run("plan --wall " + wall + " --planner zigzag --out " + disk_plan).exit_code, 0);
  EXPECT_FALSE(nlohmann::json::parse(slurp(disk_plan)).contains("tool_shape"));
  // An unknown shape: one line, exit 2, nothing written.
  const test::CommandRun bad = run("plan --wall " + wall + " --planner zigzag --tool-shape triangle --out " + (dir_ / "bad.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--tool-shape: tool.shape: must be disk, line or rectangle, got 'triangle'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.json"));
  const test::CommandRun bytes = run("plan --wall " + wall + " --planner zigzag --tool-shape \"$(printf 'li\\377ne\\001')\" --out " + (dir_ / "bad.json").string());
  EXPECT_EQ(bytes.exit_code, 2);
  EXPECT_NE(bytes.err.find("got 'li\\xffne\\x01'"), std::string::npos) << bytes.err;
  EXPECT_EQ(std::count(bytes.err.begin(), bytes.err.end(), '\n'), 1) << bytes.err;
  std::ofstream(dir_ / "odd.json") << R"({"waypoints": [[0.5, 0.5], [1, 0.5]], "tool_on": [true], "tool_shape": "blob"})";
  const test::CommandRun odd = run("metrics --wall " + wall + " --plan " + (dir_ / "odd.json").string());
  EXPECT_EQ(odd.exit_code, 2);
  EXPECT_NE(odd.err.find("tool_shape: must be \"disk\", \"line\" or \"rectangle\""), std::string::npos) << odd.err;
}

}  // namespace
}  // namespace coverbench
