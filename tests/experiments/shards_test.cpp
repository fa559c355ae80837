// Sharded experiments: the partition of runs into shards, `run --shard`, `merge` (equal to a
// single-process run key by key, idempotent, refusing what cannot be merged), a killed shard that
// resumes, and the Slurm job scripts. The real Slurm cluster test is tests/slurm/slurm_test.sh.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>

#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/shards.hpp"
#include "coverbench/slurm.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

const char* const kConfig = R"(name: sharded
output: out
datasets:
  - suite: seed-cases
  - family: residential
    count: 12
    seed: 4
planners: [all]
tool:
  width: 0.1
  clearance: 0.02
threads: 2
)";

using test::inputError;

TEST(ShardParsing, AcceptsIOverNAndNamesWhatIsWrong) {
  EXPECT_EQ(toString(parseShard("0/8")), "0/8");
  EXPECT_EQ(parseShard("7/8").index, 7u);
  EXPECT_EQ(parseShard("0/1").count, 1u);
  EXPECT_EQ(parseShard("99999/100000").index, 99999u);
  for (const char* bad : {"8/8", "9/8", "a/b", "1", "", "/", "-1/4", "01/4", "1/04", "0/0", "0/100001", "1/ 4", " 1/4",
                          "1/4/2", "1.0/4", "99999999999999999999/4"}) {
    const std::string e = inputError([&] { parseShard(bad); });
    EXPECT_NE(e.find("--shard: shard:"), std::string::npos) << "'" << bad << "' gave: " << e;
  }
}

class Shards : public test::CommandTest {
 protected:
  /// The config's runs, keys filled in (as the runner expands them).
  std::vector<RunSpec> runsOf(const std::string& text, const std::string& name, std::vector<WallEntry>& walls,
                              ExperimentConfig& config) {
    config = loadExperimentConfig(write(name, text));
    walls = loadWalls(config);
    return expandRuns(config, walls);
  }
  std::string db(const std::string& relative) { return (dir_ / relative).string(); }
};

TEST_F(Shards, ThePartitionCoversEveryRunOnceAndNoRunMovesWhenTheConfigGrows) {
  std::vector<WallEntry> walls, grown_walls;
  ExperimentConfig config, grown_config;
  const std::vector<RunSpec> runs = runsOf(kConfig, "a.yaml", walls, config);
  std::string grown = kConfig;
  grown.replace(grown.find("count: 12"), 9, "count: 30");
  const std::vector<RunSpec> more = runsOf(grown, "b.yaml", grown_walls, grown_config);
  ASSERT_EQ(runs.size(), (9u + 12u) * 6u);
  ASSERT_GT(more.size(), runs.size());
  std::map<std::string, unsigned> grown_shard;
  for (unsigned n : {1u, 2u, 3u, 7u, 64u}) {
    for (const RunSpec& r : more) grown_shard[r.base_key] = shardOf(r, n);
    std::vector<std::size_t> sizes(n, 0);
    for (const RunSpec& r : runs) {
      const unsigned s = shardOf(r, n);
      ASSERT_LT(s, n);
      ++sizes[s];
      EXPECT_EQ(grown_shard.at(r.base_key), s) << "a grown config moved a run to another shard";
    }
    std::size_t total = 0;
    for (std::size_t s : sizes) total += s;
    EXPECT_EQ(total, runs.size());
    if (n == 3) {  // 126 runs, 42 expected per shard: the hash spreads them (binomial sd 5.3)
      for (std::size_t s : sizes) EXPECT_GE(s, 25u);
    }
  }
  // By hand: the shard is the base key's first 16 hex digits modulo N.
  const RunSpec& r = runs.front();
  const unsigned long long bits = std::stoull(r.base_key.substr(0, 16), nullptr, 16);
  EXPECT_EQ(shardOf(r, 5), static_cast<unsigned>(bits % 5));
  EXPECT_EQ(shardOf(r, 1), 0u);
}

// Every axis a config can have (datasets, a parameter sweep, tool widths x clearances, transit
// planners; repetitions and replanning make no runs of their own) is counted once, by the
// expansion: each shard's count of the config's runs is the whole expansion's.
TEST_F(Shards, EveryShardCountsEveryAxisOfTheConfigAsTheExpansionDoes) {
  const std::string text = R"(name: axes
output: out
datasets:
  - suite: seed-cases
  - family: facade
    count: 2
    seed: 3
planners:
  - name: zigzag
    params:
      sweep_angle: [0, 90]
  - boustrophedon
tool:
  width: [0.1, 0.2]
  clearance: [0.0, 0.02, 0.05]
transit:
  planner: [visibility, rrtstar, bitstar]
  iterations: 100
replanning:
  at: [0.5]
  repairs: [replan, detour]
repetitions: 2
)";
  std::vector<WallEntry> walls;
  ExperimentConfig config;
  const std::vector<RunSpec> all = runsOf(text, "axes.yaml", walls, config);
  // By hand: 11 walls x (2 + 1) planner configurations x 2 widths x 3 clearances x 3 transits.
  ASSERT_EQ(walls.size(), 11u);
  EXPECT_EQ(all.size(), 11u * 3u * 6u * 3u);
  EXPECT_EQ(plannedRuns(config), all.size());
  std::set<std::string> keys;
  for (const RunSpec& r : all) keys.insert(r.key);
  EXPECT_EQ(keys.size(), all.size()) << "two expanded runs share a key";
  std::size_t in_shards = 0;
  for (unsigned i = 0; i < 5; ++i) {
    std::size_t expanded = 0;
    const std::vector<RunSpec> mine =
        expandRuns(config, walls, [i](const RunSpec& r) { return shardOf(r, 5) == i; }, &expanded);
    EXPECT_EQ(expanded, all.size()) << "shard " << i << "/5 counts the config's runs otherwise";
    in_shards += mine.size();
  }
  EXPECT_EQ(in_shards, all.size());
}

// A config with a transit list, sharded and merged, equals one process (the shards used to record
// the config's runs without the transit axis, and the merge refused them).
TEST_F(Shards, AConfigWithATransitListMergesAfterShardingAndEqualsOneProcess) {
  const std::string text = R"(name: transits
output: out
datasets:
  - suite: seed-cases
planners: [zigzag]
tool:
  width: 0.1
  clearance: 0.02
transit:
  planner: [visibility, rrtstar]
  iterations: 200
seed: 1
)";
  fs::create_directories(dir_ / "single");
  std::ofstream(dir_ / "single" / "c.yaml") << text;
  ASSERT_EQ(run("run " + (dir_ / "single" / "c.yaml").string() + " --no-report").exit_code, 0);
  const std::string cfg = write("c.yaml", text);
  std::string out, shards;
  for (int i = 0; i < 3; ++i) {
    const test::CommandRun r = run("run " + cfg + " --shard " + std::to_string(i) + "/3", &out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(out.find("of the config's 18 runs"), std::string::npos) << out;
    shards += " " + db("out/shards/shard-" + std::to_string(i) + "-of-3.sqlite");
  }
  const test::CommandRun merged = run("merge " + db("out/results.sqlite") + shards, &out);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(out.find("18 runs, 18 copied"), std::string::npos) << out;
  EXPECT_EQ(test::dumpRuns(db("out/results.sqlite")), test::dumpRuns(db("single/out/results.sqlite")));
}

TEST_F(Shards, ShardedThenMergedEqualsOneProcessRunKeyByRunKeyAndMergingAgainChangesNothing) {
  fs::create_directories(dir_ / "single");
  const std::string single_cfg = (dir_ / "single" / "c.yaml").string();
  std::ofstream(single_cfg) << kConfig;
  ASSERT_EQ(run("run " + single_cfg + " --no-report").exit_code, 0);
  const std::string reference = test::dumpRuns(db("single/out/results.sqlite"));
  ASSERT_NE(reference.find("126|126"), std::string::npos) << reference.substr(0, 200);

  const std::string cfg = write("c.yaml", kConfig);
  std::string out;
  std::size_t shard_runs = 0;
  for (int i = 0; i < 3; ++i) {
    const test::CommandRun r = run("run " + cfg + " --shard " + std::to_string(i) + "/3", &out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(out.find("shard " + std::to_string(i) + "/3"), std::string::npos) << out;
    EXPECT_NE(out.find("of the config's 126 runs"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "report")) << "a shard alone writes no report";
    const std::string shard = db("out/shards/shard-" + std::to_string(i) + "-of-3.sqlite");
    shard_runs += std::stoul(test::sqlRows(shard, "SELECT COUNT(*) FROM runs"));
    // A shard lists every wall but stores the content of its own runs' walls only.
    EXPECT_EQ(test::sqlRows(shard, "SELECT COUNT(*) FROM experiment_walls"), "21\n");
    EXPECT_EQ(test::sqlRows(shard, "SELECT COUNT(*) FROM walls"), test::sqlRows(shard, "SELECT COUNT(DISTINCT wall_hash) FROM runs"));
  }
  EXPECT_EQ(shard_runs, 126u);
  const std::string shards = db("out/shards/shard-0-of-3.sqlite") + " " + db("out/shards/shard-2-of-3.sqlite") + " " +
                             db("out/shards/shard-1-of-3.sqlite");
  const test::CommandRun merged = run("merge " + db("out/results.sqlite") + " " + shards, &out);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(out.find("126 runs, 126 copied, 0 already there, 0 stored twice"), std::string::npos) << out;
  EXPECT_EQ(test::dumpRuns(db("out/results.sqlite")), reference);
  // The merged experiment lists every run, says it was merged, and reports like any other.
  EXPECT_EQ(test::sqlRows(db("out/results.sqlite"), "SELECT COUNT(*) FROM experiment_runs"), "126\n");
  EXPECT_EQ(test::sqlRows(db("out/results.sqlite"), "SELECT COUNT(*) FROM walls"), "21\n");
  EXPECT_EQ(test::sqlRows(db("out/results.sqlite"), "SELECT COUNT(*), SUM(runs) FROM merged_shards"), "3|126\n");
  std::string table;
  ASSERT_EQ(run("runs " + db("out/results.sqlite") + " --list", &table).exit_code, 0);
  std::string single_table;
  ASSERT_EQ(run("runs " + db("single/out/results.sqlite") + " --list", &single_table).exit_code, 0);
  EXPECT_EQ(table, single_table);

  // Idempotent: the same merge again writes nothing; the file's bytes stay as they are.
  const std::string before = slurp(db("out/results.sqlite"));
  ASSERT_EQ(run("merge " + db("out/results.sqlite") + " " + shards, &out).exit_code, 0);
  EXPECT_NE(out.find("nothing changed"), std::string::npos) << out;
  EXPECT_TRUE(slurp(db("out/results.sqlite")) == before) << "the merged file's bytes changed";
  EXPECT_EQ(test::dumpRuns(db("out/results.sqlite")), reference);

  // A plain run of the config afterwards finds every run stored and does no planner work.
  ASSERT_EQ(run("run " + cfg + " --no-report", &out).exit_code, 0);
  EXPECT_NE(out.find("(0 executed, 126 already stored"), std::string::npos) << out;
}

TEST_F(Shards, AKilledShardResumesAndTheMergeRefusesUntilItHas) {
  const std::string cfg = write("c.yaml", kConfig);
  for (int i : {0, 2}) ASSERT_EQ(run("run " + cfg + " --shard " + std::to_string(i) + "/3").exit_code, 0);
  // Shard 1's own run count (35 of the 126): a file killed after its last run was stored is whole.
  std::vector<WallEntry> walls;
  ExperimentConfig config;
  const std::vector<RunSpec> runs = runsOf(kConfig, "count.yaml", walls, config);
  const long shard1_runs = std::count_if(runs.begin(), runs.end(), [](const RunSpec& r) { return shardOf(r, 3) == 1; });
  ASSERT_GT(shard1_runs, 1);
  // kill -9 shard 1 mid-way until it is caught with some but not all of its runs stored.
  const std::string shard1 = db("out/shards/shard-1-of-3.sqlite");
  // The kill comes later after a kill before any run was stored, sooner after one that came too
  // late, so slow builds (sanitizers) are caught mid-way as well.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(0.0, 0.15);
  double delay_s = 0.25;
  bool caught = false;
  for (int attempt = 0; attempt < 30 && !caught; ++attempt) {
    // The file and SQLite's files beside it: a -wal or -shm left by the last killed attempt would
    // be read as part of a new file of the same name.
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(shard1 + suffix);
    const test::CommandRun r = run("--version > /dev/null; timeout -s KILL " + std::to_string(delay_s + jitter(rng)) + " " +
                                   std::string(COVERBENCH_BINARY) + " run " + cfg + " --shard 1/3 --threads 1");
    if (r.exit_code == 0) {  // finished before the kill
      delay_s *= 0.6;
      continue;
    }
    ASSERT_EQ(r.exit_code, 137) << r.err;
    // Killed before its first transaction: no tables yet (the resume still takes such a file:
    // Shards.AResultsFileWithoutTablesIsTakenAsNewAndOneWithDataIsNot). Kill later next time.
    const int stored = test::storedRuns(shard1);
    if (stored < 0) {
      delay_s *= 1.5;
      continue;
    }
    caught = stored > 0 && stored < shard1_runs;
    if (!caught) delay_s *= stored == 0 ? 1.5 : 0.6;
  }
  ASSERT_TRUE(caught) << "shard 1 was never killed with part of its runs stored";
  const std::string all = db("out/shards/shard-0-of-3.sqlite") + " " + shard1 + " " + db("out/shards/shard-2-of-3.sqlite");
  test::CommandRun r = run("merge " + db("out/results.sqlite") + " " + all);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("incomplete, nothing written: shard 1/3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("resume it with `coverbench run CONFIG --shard 1/3`"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(db("out/results.sqlite"))) << "a refused merge leaves no output behind";

  std::string out;
  ASSERT_EQ(run("run " + cfg + " --shard 1/3", &out).exit_code, 0);
  EXPECT_NE(out.find("already stored"), std::string::npos) << out;
  r = run("merge " + db("out/results.sqlite") + " " + all, &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(out.find("126 runs, 126 copied"), std::string::npos) << out;

  fs::create_directories(dir_ / "single");
  std::ofstream(dir_ / "single" / "c.yaml") << kConfig;
  ASSERT_EQ(run("run " + (dir_ / "single" / "c.yaml").string() + " --no-report").exit_code, 0);
  EXPECT_EQ(test::dumpRuns(db("out/results.sqlite")), test::dumpRuns(db("single/out/results.sqlite")));
}

TEST_F(Shards, MergeRefusesWhatCannotBeMergedAndWritesNothing) {
  const std::string cfg = write("c.yaml", kConfig);
  for (int i : {0, 1}) ASSERT_EQ(run("run " + cfg + " --shard " + std::to_string(i) + "/2").exit_code, 0);
  const std::string s0 = db("out/shards/shard-0-of-2.sqlite"), s1 = db("out/shards/shard-1-of-2.sqlite");
  const std::string out_db = db("merged.sqlite");
  auto refused = [&](const std::string& shards, const std::string& expected) {
    const test::CommandRun r = run("merge " + out_db + " " + shards);
    EXPECT_EQ(r.exit_code, 2) << shards;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_FALSE(fs::exists(out_db)) << "nothing written";
  };
  refused(s0, "incomplete, nothing written: 1 of 2 shards not given (1)");
  refused(s0 + " " + s0, "1 of 2 shards not given");  // the same file twice is one shard

  // Another config (another seed: other walls) and another build.
  std::string other = kConfig;
  other.replace(other.find("seed: 4"), 7, "seed: 5");
  fs::create_directories(dir_ / "other");
  std::ofstream(dir_ / "other" / "c.yaml") << other;
  ASSERT_EQ(run("run " + (dir_ / "other" / "c.yaml").string() + " --shard 1/2").exit_code, 0);
  refused(s0 + " " + db("other/out/shards/shard-1-of-2.sqlite"), "config_hash: differs from");
  fs::copy_file(s1, db("s1-built-elsewhere.sqlite"));
  test::sqlRows(db("s1-built-elsewhere.sqlite"), "UPDATE experiments SET compiler = 'Clang 99'");
  refused(s0 + " " + db("s1-built-elsewhere.sqlite"), "build: differs from");
  // Another shard count.
  ASSERT_EQ(run("run " + cfg + " --shard 2/3").exit_code, 0);
  refused(s0 + " " + s1 + " " + db("out/shards/shard-2-of-3.sqlite"), "shard count: differs from");
  // Not a shard database: a plain run's.
  fs::create_directories(dir_ / "plain");
  std::ofstream(dir_ / "plain" / "c.yaml") << kConfig;
  ASSERT_EQ(run("run " + (dir_ / "plain" / "c.yaml").string() + " --no-report").exit_code, 0);
  refused(s0 + " " + db("plain/out/results.sqlite"), "not a shard database");
  refused(s0 + " " + db("nowhere.sqlite"), "nowhere.sqlite: (file): does not exist");
  // The same shard in two files: identical runs are kept once; a run with another result is refused.
  fs::copy_file(s1, db("s1-copy.sqlite"));
  std::string out;
  const test::CommandRun r = run("merge " + out_db + " " + s0 + " " + s1 + " " + db("s1-copy.sqlite"), &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string s1_runs = test::sqlRows(s1, "SELECT COUNT(*) FROM runs");
  EXPECT_NE(out.find("shard 1/2 given in 2 files"), std::string::npos) << out;
  EXPECT_NE(out.find(std::to_string(std::stoi(s1_runs)) + " stored twice"), std::string::npos) << out;
  fs::remove(out_db);
  fs::copy_file(s1, db("s1-tampered.sqlite"));
  test::sqlRows(db("s1-tampered.sqlite"),
                "UPDATE metrics SET value = value + 1 WHERE run_key = (SELECT MIN(run_key) FROM metrics) AND name = "
                "(SELECT MIN(name) FROM metrics)");
  refused(s0 + " " + s1 + " " + db("s1-tampered.sqlite"), "has another result than the one already merged");
}

// Inputs are never written: a shard as OUT, the same file under another name (a hard link), and a
// refused merge onto an existing output all leave every file's bytes as they were.
TEST_F(Shards, AMergeNeverWritesItsInputsAndARefusedOneLeavesTheOutputsBytes) {
  const std::string cfg = write("c.yaml", kConfig);
  for (int i : {0, 1}) ASSERT_EQ(run("run " + cfg + " --shard " + std::to_string(i) + "/2").exit_code, 0);
  const std::string s0 = db("out/shards/shard-0-of-2.sqlite"), s1 = db("out/shards/shard-1-of-2.sqlite");
  const std::string s0_bytes = slurp(s0), s1_bytes = slurp(s1);
  auto refused = [&](const std::string& args, const std::string& expected) {
    const test::CommandRun r = run("merge " + args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(slurp(s0) == s0_bytes && slurp(s1) == s1_bytes) << "a shard was written: " << args;
  };
  // A shard as the output: it would hold a merged experiment and never merge again.
  refused(s0 + " " + s1, "shard-0-of-2.sqlite: output: is a shard database");
  fs::copy_file(s0, db("shard0-copy.sqlite"));
  refused(db("shard0-copy.sqlite") + " " + s0 + " " + s1, "output: is a shard database");
  // The output is a hard link of a shard: the same file.
  fs::create_hard_link(s1, db("link.sqlite"));
  refused(db("link.sqlite") + " " + s0 + " " + s1, "is the output database itself");
  // A refused merge onto an existing merged output changes none of its bytes (SQLite's header
  // counts every write: opening it for writing used to bump it).
  std::string out;
  ASSERT_EQ(run("merge " + db("merged.sqlite") + " " + s0 + " " + s1, &out).exit_code, 0) << out;
  const std::string merged = slurp(db("merged.sqlite"));
  fs::copy_file(s1, db("s1-tampered.sqlite"));
  test::sqlRows(db("s1-tampered.sqlite"),
                "UPDATE metrics SET value = value + 1 WHERE run_key = (SELECT MIN(run_key) FROM metrics) AND name = "
                "(SELECT MIN(name) FROM metrics)");
  const test::CommandRun r = run("merge " + db("merged.sqlite") + " " + s0 + " " + db("s1-tampered.sqlite"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has another result than the one already merged"), std::string::npos) << r.err;
  EXPECT_TRUE(slurp(db("merged.sqlite")) == merged) << "a refused merge changed the output's bytes";
}

// A file that is not a results database is named for what it is, by every command that reads one.
TEST_F(Shards, AnEmptyFileIsNotAResultsDatabaseForEveryCommandThatReadsOne) {
  const std::string empty = write("empty.sqlite", "");
  for (const std::string& command :
       {"report " + empty + " --format md", "report " + empty + " --out " + db("rep"), "runs " + empty, "runs " + empty + " --list",
        "export-ompl " + empty + " --out " + db("ompl"), "redraw " + empty + " --run abcdef --svg " + db("x.svg"),
        "merge " + db("m.sqlite") + " " + empty}) {
    const test::CommandRun r = run(command);
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("empty.sqlite: (database): is not a CoverBench results database (an empty file)"), std::string::npos)
        << command << ": " << r.err;
    EXPECT_EQ(fs::file_size(empty), 0u) << command;
    EXPECT_FALSE(fs::exists(db("m.sqlite")) || fs::exists(db("rep")) || fs::exists(db("x.svg"))) << command;
  }
  // An SQLite database with no tables likewise (a reader finds nothing to read in it).
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(db("bare.sqlite").c_str(), &raw), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(raw, "PRAGMA user_version = 0; VACUUM", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(raw);
  }
  const test::CommandRun r = run("runs " + db("bare.sqlite"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is not a CoverBench results database"), std::string::npos) << r.err;
}

TEST_F(Shards, TheSlurmCommandWritesBothScriptsOrNothing) {
  const std::string cfg = write("c.yaml", kConfig);
  std::string out;
  test::CommandRun r = run("slurm " + cfg + " --shards 3 --time 30 --mem 2G", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string script = slurp(db("out/slurm/run.sbatch"));
  EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --mem=2G\n"), std::string::npos) << script;
  EXPECT_NE(script.find(" run '" + cfg + "' --shard \"${SLURM_ARRAY_TASK_ID}/3\""), std::string::npos) << script;
  EXPECT_NE(slurp(db("out/slurm/merge.sbatch")).find(" merge '" + db("out/results.sqlite") + "'"), std::string::npos);
  EXPECT_TRUE(fs::is_directory(dir_ / "out" / "slurm" / "logs"));
  EXPECT_NE(out.find("sbatch --dependency=afterany:"), std::string::npos) << out;

  fs::remove_all(dir_ / "out");
  r = run("slurm " + cfg + " --time 'an hour'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--time: time: must be in Slurm's format"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "slurm")) << "nothing written";
  // --submit without sbatch on the PATH: a clear error, the scripts kept for submitting by hand.
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", (dir_ / "no-such-folder").c_str(), 1);
  r = run("slurm " + cfg + " --submit");
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("sbatch: submit: `sbatch --parsable"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("exit 127: sbatch not found"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the scripts are written, submit them by hand"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "slurm" / "run.sbatch"));
}

TEST_F(Shards, AResultsFileWithoutTablesIsTakenAsNewAndOneWithDataIsNot) {
  // What a process killed while creating its database leaves: WAL mode set, no table.
  const std::string empty = db("empty.sqlite");
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(empty.c_str(), &raw), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(raw, "PRAGMA journal_mode = WAL", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(raw);
  }
  ASSERT_GT(fs::file_size(empty), 0u);
  EXPECT_NO_THROW(ResultsDb{empty});
  EXPECT_EQ(test::sqlRows(empty, "PRAGMA application_id"), "1131823694\n");
  // Another program's database with a table is still refused, and left as it was.
  const std::string other = db("other.sqlite");
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(other.c_str(), &raw), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(raw, "CREATE TABLE notes (text TEXT)", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(raw);
  }
  EXPECT_NE(inputError([&] { ResultsDb{other}; }).find("is not a CoverBench results database"), std::string::npos);
  EXPECT_EQ(test::sqlRows(other, "SELECT COUNT(*) FROM sqlite_master"), "1\n");
  // Another program's WAL database, refused, keeps only what it had beside it (SQLite makes -wal
  // and -shm files for any connection to it, even one that only reads).
  const std::string wal = db("wal.sqlite");
  {
    sqlite3* raw = nullptr;
    ASSERT_EQ(sqlite3_open(wal.c_str(), &raw), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(raw, "PRAGMA journal_mode = WAL; CREATE TABLE notes (text TEXT)", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(raw);
  }
  ASSERT_FALSE(fs::exists(wal + "-wal"));
  for (ResultsDb::Mode mode : {ResultsDb::Mode::ReadOnly, ResultsDb::Mode::ReadWrite}) {
    EXPECT_NE(inputError([&] { ResultsDb(wal, mode); }).find("is not a CoverBench results database"), std::string::npos);
    EXPECT_FALSE(fs::exists(wal + "-wal") || fs::exists(wal + "-shm")) << "files left beside a refused database";
  }
}

TEST(SlurmScripts, AnArrayOfShardsAndAMergeJobWithTheGivenResources) {
  ExperimentConfig config;
  config.name = "my exp";
  config.path = "/data/exp.yaml";
  config.output = "/data/results/exp";
  config.memory_limit_mb = 2048;
  SlurmOptions o;
  o.shards = 16;
  o.cpus_per_task = 2;
  o.throttle = 4;
  o.partition = "short";
  o.time = "1-00:00:00";
  o.binary = "/opt/cb/coverbench";
  o.workdir = "/data";
  const SlurmScripts s = slurmScripts(config, o);
  EXPECT_EQ(s.run_script, "/data/results/exp/slurm/run.sbatch");
  EXPECT_EQ(s.merge_script, "/data/results/exp/slurm/merge.sbatch");
  for (const char* line : {"#!/bin/bash\n", "\n#SBATCH --job-name=coverbench-my_exp\n", "\n#SBATCH --array=0-15%4\n",
                           "\n#SBATCH --cpus-per-task=2\n", "\n#SBATCH --mem=5120M\n", "\n#SBATCH --time=1-00:00:00\n",
                           "\n#SBATCH --partition=short\n", "\n#SBATCH --chdir=/data\n",
                           "\n#SBATCH --output=/data/results/exp/slurm/logs/run-%A_%a.out\n",
                           "\nexec '/opt/cb/coverbench' run '/data/exp.yaml' --shard \"${SLURM_ARRAY_TASK_ID}/16\" --threads "
                           "\"${SLURM_CPUS_PER_TASK:-2}\" --no-report --yes\n"})
    EXPECT_NE(s.run_text.find(line), std::string::npos) << line << "\nin:\n" << s.run_text;
  for (const char* line : {"\nfor i in $(seq 0 15); do shards+=('/data/results/exp/shards'/shard-$i-of-16.sqlite); done\n",
                           "\n'/opt/cb/coverbench' merge '/data/results/exp/results.sqlite' \"${shards[@]}\"\n",
                           "\n'/opt/cb/coverbench' report '/data/results/exp/results.sqlite' --format html --out "
                           "'/data/results/exp/report'\n",
                           "\n#SBATCH --output=/data/results/exp/slurm/logs/merge-%j.out\n"})
    EXPECT_NE(s.merge_text.find(line), std::string::npos) << line << "\nin:\n" << s.merge_text;
  EXPECT_EQ(s.run_text.find("--account"), std::string::npos);

  auto error = [&](SlurmOptions bad) { return inputError([&] { slurmScripts(config, bad); }); };
  SlurmOptions bad = o;
  bad.time = "1 hour";
  EXPECT_NE(error(bad).find("--time: time: must be in Slurm's format"), std::string::npos);
  bad = o;
  bad.mem = "4 GB";
  EXPECT_NE(error(bad).find("--mem: mem:"), std::string::npos);
  bad = o;
  bad.partition = "a;rm -rf /";
  EXPECT_NE(error(bad).find("--partition: partition:"), std::string::npos);
  bad = o;
  bad.shards = 0;
  EXPECT_NE(error(bad).find("--shards: shards: must be in [1, 100000]"), std::string::npos);
  ExperimentConfig spaced = config;
  spaced.output = "/data/my results";
  EXPECT_NE(inputError([&] { slurmScripts(spaced, o); }).find("has white space or %"), std::string::npos);
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
}

}  // namespace
}  // namespace coverbench
