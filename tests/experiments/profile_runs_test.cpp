// The tool's flux profile in the results database and in `coverbench runs` (docs/deposition.md):
// stored for the runs that have one, listed beside the tool; runs without one, and databases made
// before the profile was stored, read and list as they did.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <map>

#include "coverbench/results_db.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

class ProfileRuns : public test::CommandTest {
 protected:
  /// Runs zigzag on one 2 x 1 m wall with the config's `tool:` section; the results database.
  std::string experiment(const std::string& name, const std::string& tool) {
    fs::create_directories(dir_ / "walls");
    std::ofstream(dir_ / "walls" / "a.json") << R"({"name": "a", "width": 2, "height": 1})";
    const std::string config =
        write(name + ".yaml", "name: " + name + "\noutput: " + name + "\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n" + tool);
    const test::CommandRun r = run("run " + config + " --no-report");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return (dir_ / name / "results.sqlite").string();
  }
  /// `coverbench runs DB FLAGS`'s output.
  std::string runs(const std::string& db, const std::string& flags) {
    std::string out;
    const test::CommandRun r = run("runs " + db + " " + flags, &out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }
  /// The listing, the CSV and the JSON.
  std::string all(const std::string& db) { return runs(db, "--list") + runs(db, "") + runs(db, "--format json"); }
};

TEST(FluxProfileLabel, NamesTheKindItsValueAndWhatIsNotTheDefault) {
  FluxProfile p;
  EXPECT_EQ(p.label(), "");
  p.kind = FluxProfile::Kind::Uniform;
  EXPECT_EQ(p.label(), "uniform");
  p.kind = FluxProfile::Kind::Beta;
  p.beta = 2.5;
  EXPECT_EQ(p.label(), "beta 2.5");
  p.kind = FluxProfile::Kind::Gaussian;
  p.sigma = 0.02;
  p.rate = 2e-6;
  p.depth = 0.05;
  EXPECT_EQ(p.label(), "gaussian 0.02 m, 2e-06 m3/s, fan depth 0.05 m");
  p.flow = FluxProfile::Flow::Speed;
  EXPECT_EQ(p.label(), "gaussian 0.02 m, 2e-06 m3/s, fan depth 0.05 m, flow follows speed");
  EXPECT_EQ(p.describe(0.2), "gaussian profile, sigma 0.02 m, 2e-06 m3/s, fan depth 0.05 m, flow follows speed");
}

TEST_F(ProfileRuns, ARunWithAProfileIsStoredAndListedWithIt) {
  const std::string db = experiment("coat", "tool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 2.5, rate: 2e-6}\n");
  const ResultSet rs = ResultsDb(db, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 2u);
  for (const ResultRow& r : rs.runs) {
    EXPECT_EQ(r.tool.profile.kind, FluxProfile::Kind::Beta);
    EXPECT_EQ((std::vector<double>{r.tool.profile.beta, r.tool.profile.rate, r.tool.profile.depth}),
              (std::vector<double>{2.5, 2e-6, 0.0}));
    EXPECT_TRUE(r.metrics.count("thickness_cv")) << r.key;
  }
  const std::string list = runs(db, "--list");
  EXPECT_NE(list.find("  zigzag  s=0.2 m, c=0.02 m, beta 2.5, 2e-06 m3/s  walls/a\n"), std::string::npos) << list;
  EXPECT_NE(list.find("  zigzag  s=0.3 m, c=0.02 m, beta 2.5, 2e-06 m3/s  walls/a\n"), std::string::npos) << list;
  const std::string csv = runs(db, "");
  EXPECT_EQ(csv.rfind("key,dataset,wall,wall_hash,planner,params,planner_version,tool_width,clearance,profile,", 0), 0u) << csv;
  EXPECT_NE(csv.find(",0.3,0.02,\"beta 2.5, 2e-06 m3/s\","), std::string::npos) << csv;
  const nlohmann::json json = nlohmann::json::parse(runs(db, "--format json"));
  ASSERT_EQ(json.size(), 2u);
  EXPECT_EQ(json[0]["profile"], "beta 2.5, 2e-06 m3/s");
  // The explorer's tool facet names the profile beside the tool (toolAndProfileLabel).
  ResultsDb results(db, ResultsDb::Mode::ReadOnly);
  std::set<std::string> tools;
  for (const ResultsDb::RunSummary& r : results.runSummaries(results.experiments().back().id)) tools.insert(toolAndProfileLabel(r.tool));
  EXPECT_EQ(tools, (std::set<std::string>{"s=0.2 m, c=0.02 m, beta 2.5, 2e-06 m3/s", "s=0.3 m, c=0.02 m, beta 2.5, 2e-06 m3/s"}));
}

/// How many runs have the base keys of the plain profile's runs below (pinned: commit 682a1a8).
constexpr const char* kPlainKeyRuns =
    "SELECT COUNT(*) FROM runs WHERE base_key IN ('5b02f92382e4ac9106d8bed1bb7975a7096d7c82acb8335e03ac7cf21d8dd595', "
    "'ad871fbf70325c885e9a58de9a3af2a0ff584f58e6dd29ad827d6a0c6c90452e')";

// A profile's target thickness: stored (run_profile_target), listed, scored against, and part of
// the run key only when there is one. The base keys of the run above (no target) are those the
// build before the target gave it (commit 682a1a8: `coverbench run` of this config).
TEST_F(ProfileRuns, ATargetIsStoredListedAndKeyedOnlyWhenSet) {
  const std::string plain = experiment("coat", "tool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 2.5, rate: 2e-6}\n");
  EXPECT_EQ(test::sqlRows(plain, "SELECT base_key FROM runs ORDER BY base_key"),
            "5b02f92382e4ac9106d8bed1bb7975a7096d7c82acb8335e03ac7cf21d8dd595\n"
            "ad871fbf70325c885e9a58de9a3af2a0ff584f58e6dd29ad827d6a0c6c90452e\n");
  EXPECT_EQ(test::sqlRows(plain, "SELECT COUNT(*) FROM run_profile_target"), "0\n");
  EXPECT_EQ(runs(plain, "--list").find("target"), std::string::npos);
  const std::string aimed =
      experiment("aimed", "tool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 2.5, rate: 2e-6, target: 25}\n");
  EXPECT_EQ(test::sqlRows(aimed, kPlainKeyRuns),
            "0\n");
  EXPECT_EQ(test::sqlRows(aimed, "SELECT DISTINCT target FROM run_profile_target"), "25.0\n");
  const ResultSet with = ResultsDb(aimed, ResultsDb::Mode::ReadOnly).load(), without = ResultsDb(plain, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(with.runs.size(), 2u);
  ASSERT_EQ(without.runs.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(with.runs[i].tool.profile.target, 25.0);
    EXPECT_EQ(without.runs[i].tool.profile.target, 0.0);
  }
  const std::string list = runs(aimed, "--list");
  EXPECT_NE(list.find("  zigzag  s=0.3 m, c=0.02 m, beta 2.5, 2e-06 m3/s, target 25 um  walls/a\n"), std::string::npos) << list;
  // The same paths (the planner reads no target), the same mean, other shares.
  std::map<double, const ResultRow*> by_width;
  for (const ResultRow& r : without.runs) by_width[r.tool.tool_width] = &r;
  for (const ResultRow& r : with.runs) {
    const ResultRow& o = *by_width.at(r.tool.tool_width);
    EXPECT_EQ(r.metrics.at("thickness_mean"), o.metrics.at("thickness_mean"));
    EXPECT_EQ(r.metrics.at("thickness_cv"), o.metrics.at("thickness_cv"));
    EXPECT_NE(r.metrics.at("even_share"), o.metrics.at("even_share"));
  }
  // A database made before run_profile_target reads its runs without a target.
  test::sqlRows(aimed, "DROP TABLE run_profile_target");
  for (const ResultRow& r : ResultsDb(aimed, ResultsDb::Mode::ReadOnly).load().runs) EXPECT_EQ(r.tool.profile.target, 0.0);
}

TEST_F(ProfileRuns, RunsWithoutAProfileAndDatabasesFromBeforeItListAsBefore) {
  const std::string plain = experiment("plain", "");
  const std::string before = all(plain);
  EXPECT_EQ(before.find("profile"), std::string::npos);
  EXPECT_EQ(test::sqlRows(plain, "SELECT COUNT(*) FROM run_profile"), "0\n");
  // A database made before run_profile (the table dropped: the only difference): the same bytes.
  test::sqlRows(plain, "DROP TABLE run_profile");
  EXPECT_EQ(all(plain), before);
  // Runs of a profile in such a database read as disk tools without one.
  const std::string coat = experiment("coat", "tool:\n  profile: {kind: uniform}\n");
  EXPECT_NE(runs(coat, "--list").find("c=0.02 m, uniform  "), std::string::npos);
  test::sqlRows(coat, "DROP TABLE run_profile");
  for (const ResultRow& r : ResultsDb(coat, ResultsDb::Mode::ReadOnly).load().runs) EXPECT_FALSE(r.tool.profile.set());
  EXPECT_EQ(runs(coat, "--list").find("uniform"), std::string::npos);
}

// Shards merge with their runs' profiles; a shard made before run_profile merges as disk tools.
// A gun whose flow follows the speed: stored (run_profile_flow), listed, part of the run key only
// when it does (a constant flow keeps the keys pinned above), scored with its coat (no build-up
// where the tool brakes into zigzag's row ends: a thinner mean coat that varies less), merged
// from shards, and a database made before the table reads as constant flows.
TEST_F(ProfileRuns, AFlowThatFollowsTheSpeedIsStoredListedAndKeyedOnlyWhenSet) {
  const std::string plain = experiment("coat", "tool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 2.5, rate: 2e-6}\n");
  EXPECT_EQ(test::sqlRows(plain, "SELECT COUNT(*) FROM run_profile_flow"), "0\n");
  EXPECT_EQ(all(plain).find("flow"), std::string::npos);
  const std::string tool = "tool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 2.5, rate: 2e-6, flow: speed}\n";
  const std::string following = experiment("following", tool);
  EXPECT_EQ(test::sqlRows(following, kPlainKeyRuns),
            "0\n");
  EXPECT_EQ(test::sqlRows(following, "SELECT flow, COUNT(*) FROM run_profile_flow GROUP BY flow"), "speed|2\n");
  const ResultSet with = ResultsDb(following, ResultsDb::Mode::ReadOnly).load(), without = ResultsDb(plain, ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(with.runs.size(), 2u);
  std::map<double, const ResultRow*> by_width;
  for (const ResultRow& r : without.runs) by_width[r.tool.tool_width] = &r;
  for (const ResultRow& r : with.runs) {
    EXPECT_EQ(r.tool.profile.flow, FluxProfile::Flow::Speed);
    const ResultRow& o = *by_width.at(r.tool.tool_width);
    EXPECT_EQ(o.tool.profile.flow, FluxProfile::Flow::Constant);
    EXPECT_EQ(r.metrics.at("length_total"), o.metrics.at("length_total"));  // the same path
    EXPECT_LT(r.metrics.at("thickness_cv"), o.metrics.at("thickness_cv")) << r.tool.tool_width;
    EXPECT_LT(r.metrics.at("thickness_mean"), o.metrics.at("thickness_mean")) << r.tool.tool_width;
  }
  const std::string list = runs(following, "--list");
  EXPECT_NE(list.find("  zigzag  s=0.3 m, c=0.02 m, beta 2.5, 2e-06 m3/s, flow follows speed  walls/a\n"), std::string::npos) << list;
  // Shards merge with the table.
  const std::string config = write("shard.yaml", "name: shard\noutput: shard\ndatasets:\n  - folder: walls\nplanners: [zigzag]\n" + tool);
  for (const char* shard : {"0/2", "1/2"}) ASSERT_EQ(run("run " + config + " --shard " + shard).exit_code, 0) << shard;
  const std::string shards = (dir_ / "shard" / "shards").string(), merged = (dir_ / "merged.sqlite").string();
  ASSERT_EQ(run("merge " + merged + " " + shards + "/shard-0-of-2.sqlite " + shards + "/shard-1-of-2.sqlite").exit_code, 0);
  EXPECT_EQ(test::sqlRows(merged, "SELECT flow, COUNT(*) FROM run_profile_flow GROUP BY flow"), "speed|2\n");
  // A flow this build does not know (a damaged database) is one line naming the file and the table.
  test::sqlRows(merged, "UPDATE run_profile_flow SET flow = 'fa' || char(27) || 'st'");
  const test::CommandRun damaged = run("runs " + merged + " --list");
  EXPECT_EQ(damaged.exit_code, 2) << damaged.err;
  EXPECT_EQ(damaged.err, "coverbench: " + merged + ": run_profile_flow.flow: must be constant or speed, got 'fa\\x1bst'\n");
  // A database made before run_profile_flow reads its runs as constant flows.
  test::sqlRows(following, "DROP TABLE run_profile_flow");
  for (const ResultRow& r : ResultsDb(following, ResultsDb::Mode::ReadOnly).load().runs)
    EXPECT_EQ(r.tool.profile.flow, FluxProfile::Flow::Constant);
}

TEST_F(ProfileRuns, ShardsMergeWithTheirProfiles) {
  experiment("coat", "");  // the wall
  const std::string config = write("shard.yaml", "name: shard\noutput: shard\ndatasets:\n  - folder: walls\n"
                                                 "planners: [zigzag, spiral]\ntool:\n  width: [0.2, 0.3]\n  profile: {kind: beta, beta: 3}\n");
  for (const char* shard : {"0/2", "1/2"}) ASSERT_EQ(run("run " + config + " --shard " + shard).exit_code, 0) << shard;
  const std::string shards = (dir_ / "shard" / "shards").string(), merged = (dir_ / "merged.sqlite").string();
  ASSERT_EQ(run("merge " + merged + " " + shards + "/shard-0-of-2.sqlite " + shards + "/shard-1-of-2.sqlite").exit_code, 0);
  const std::string list = runs(merged, "--list");
  EXPECT_EQ(std::count(list.begin(), list.end(), '\n'), 4) << list;
  EXPECT_EQ(test::sqlRows(merged, "SELECT DISTINCT kind, beta, rate, depth FROM run_profile"), "beta|3.0|1.0e-06|0.0\n");
  EXPECT_EQ(test::sqlRows(merged, "SELECT COUNT(*) FROM run_profile"), "4\n");
  EXPECT_EQ(std::count(list.begin(), list.end(), ','), 8) << list;  // "s=.., c=.., beta 3" on each
  EXPECT_NE(list.find("c=0.02 m, beta 3  "), std::string::npos) << list;
  // Shard 0 holds some of the runs, shard 1 the others; without shard 1's table only shard 0's keep it.
  const std::string first = test::sqlRows(shards + "/shard-0-of-2.sqlite", "SELECT COUNT(*) FROM run_profile");
  EXPECT_NE(first, "0\n");
  EXPECT_NE(first, "4\n");
  test::sqlRows(shards + "/shard-1-of-2.sqlite", "DROP TABLE run_profile");
  const std::string again = (dir_ / "again.sqlite").string();
  ASSERT_EQ(run("merge " + again + " " + shards + "/shard-0-of-2.sqlite " + shards + "/shard-1-of-2.sqlite").exit_code, 0);
  EXPECT_EQ(test::sqlRows(again, "SELECT COUNT(*) FROM run_profile"), first);
  EXPECT_EQ(test::sqlRows(again, "SELECT COUNT(*) FROM runs"), "4\n");
}

// tests/data/pre_profile: a database written by the build before run_profile (commit 42adf54), and
// what that build's `coverbench runs` printed for it.
TEST_F(ProfileRuns, ADatabaseFromBeforeRunProfileListsAsItsBuildListedIt) {
  const fs::path fixture = test::sourcePath("tests/data/pre_profile");
  const std::string db = (dir_ / "results.sqlite").string();
  fs::copy_file(fixture / "results.sqlite", db);  // opening it makes -wal and -shm files beside it
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*) FROM sqlite_master WHERE name = 'run_profile'"), "0\n");
  auto same = [&](const std::string& when) {
    for (const char* e : {"1", "2"}) {
      const std::string golden = (fixture / "runs.").string() + e;
      EXPECT_EQ(runs(db, std::string("--experiment ") + e + " --list"), slurp(golden + ".list")) << when << e;
      EXPECT_EQ(runs(db, std::string("--experiment ") + e), slurp(golden + ".csv")) << when << e;
      EXPECT_EQ(runs(db, std::string("--experiment ") + e + " --format json"), slurp(golden + ".json")) << when << e;
    }
  };
  same("read only: ");
  // Its runs are disk tools without a profile, also the one run with a profile then (experiment 2).
  const ResultSet coat = ResultsDb(db, ResultsDb::Mode::ReadOnly).load(2);
  ASSERT_EQ(coat.runs.size(), 1u);
  EXPECT_FALSE(coat.runs[0].tool.profile.set());
  EXPECT_TRUE(coat.runs[0].metrics.count("thickness_cv"));
  // Opened to write, it gains the (empty) table, and still lists the same.
  { ResultsDb writable(db, ResultsDb::Mode::ReadWrite); }
  EXPECT_EQ(test::sqlRows(db, "SELECT COUNT(*) FROM run_profile"), "0\n");
  same("after opening to write: ");
}

}  // namespace
}  // namespace coverbench
