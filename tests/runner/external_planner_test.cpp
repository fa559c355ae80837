// Planners outside the tree (docs/external_planners.md): the manifest, protocol 1, and a planner
// process under the same limits and statuses as in-tree planners. Misbehaving planners (written in
// Python here: any language speaks the protocol) each get their named status, and the other
// planners' runs equal a run without them; the Python example planner runs in an experiment,
// is scored, stored and reported like any other, and editing its file runs it again.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <thread>

#include "coverbench/external_planner.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/wall_file.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

/// One script, one misbehaviour per argument; "fine" answers a valid straight path.
// The planners run with Debian's python3 by its path: a version manager's shim on PATH (pyenv's
// takes 0.5-0.8 s to start an interpreter here) would eat into the runs' time limit. A planner
// that must meet anything but the time limit runs under a time limit it cannot reach first: on a
// machine whose page faults are slow (4 GiB took 22 s to fill here; 300 MiB took 26 s with 4 % of
// a core) the allocating planner needs seconds to pass 300 MiB.
const char* const kMisbehave = R"py(import json, os, signal, sys, time
mode = sys.argv[1]
if mode in ("orphans", "orphans-sleep", "child-hog", "child-holds"):
    import subprocess  # only where needed: the others start as fast as they can
def orphan():
    # A child that leaves the process group (setsid), and every pid this planner knows of, recorded.
    child = subprocess.Popen(["/usr/bin/python3", "-c", "import time\ntime.sleep(3600)"], start_new_session=True)
    with open("pids.txt", "a") as f:
        f.write("%d %d %d\n" % (os.getpid(), child.pid, os.getppid()))
for line in sys.stdin:
    req = json.loads(line)
    if mode == "sleeps":
        time.sleep(3600)
    if mode == "orphans-sleep":
        orphan()
        time.sleep(3600)
    if mode == "orphans":
        orphan()
    if mode == "nested":
        os.write(1, b"[" * (2 << 20) + b"\n")
        continue
    if mode == "child-holds":  # its child touches 600 MiB and keeps it; it waits for the child
        subprocess.run(["/usr/bin/python3", "-c",
                        "import time\nb = bytearray(600 << 20)\nfor i in range(0, len(b), 4096): b[i] = 1\ntime.sleep(3600)"])
    if mode == "child-hog":
        subprocess.run(["/usr/bin/python3", "-c", "b = bytearray(600 << 20)\nfor i in range(0, len(b), 4096): b[i] = 1"])
    if mode in ("huge", "outside"):
        x = 1e300 if mode == "huge" else -5.0
        print(json.dumps({"protocol": 1, "id": req["id"], "status": "ok", "waypoints": [[x, -5.0], [x + 1.0, -5.0]],
                          "tool_on": [True]}), flush=True)
        continue
    if mode == "twice":
        # A valid answer, then (once told the host has read it) a second line that would pass for
        # the next request's answer.
        p = req["problem"]
        r = p["tool"]["width"] / 2 + p["tool"]["clearance"] + 0.01
        answer = {"protocol": 1, "id": req["id"], "status": "ok", "waypoints": [[r, r], [r + 0.05, r]], "tool_on": [True]}
        print(json.dumps(answer), flush=True)
        while not os.path.exists("go"):
            time.sleep(0.01)
        answer["id"] += 1
        print(json.dumps(answer), flush=True)
        open("written", "w").close()
        continue
    if mode == "garbage":
        print("this is not json", flush=True)
        continue
    if mode == "exits":
        sys.exit(3)
    if mode == "signal":
        os.kill(os.getpid(), signal.SIGSEGV)
    if mode == "allocates":
        hog = b"x" * (4 * 1024 ** 3)
    if mode == "floods":
        chunk = b"x" * (8 << 20)
        for _ in range(128):
            os.write(1, chunk)
        time.sleep(3600)
    if mode == "wrong-id":
        print(json.dumps({"protocol": 1, "id": req["id"] + 1, "status": "error", "reason": "x"}), flush=True)
        continue
    p = req["problem"]
    r = p["tool"]["width"] / 2 + p["tool"]["clearance"] + 0.01
    print(json.dumps({"protocol": 1, "id": req["id"], "status": "ok",
                      "waypoints": [[r, r], [r + 0.05, r]], "tool_on": [True]}), flush=True)
if mode == "orphans":  # it ignores the end of its input, and SIGTERM
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    time.sleep(3600)
)py";

constexpr const char* kModes[] = {"fine",   "sleeps", "garbage",  "exits",  "signal",        "allocates",
                                  "floods", "wrong-id", "orphans", "orphans-sleep", "nested", "child-hog", "child-holds",
                                  "huge",   "outside", "twice"};

/// A process is running (not a zombie).
bool running(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t paren = stat.rfind(')');
  return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] != 'Z' && stat[paren + 2] != 'X';
}

/// The pids a misbehaving planner recorded in pids.txt (itself, its setsid child, its host).
std::vector<pid_t> recordedPids(const fs::path& file) {
  std::vector<pid_t> pids;
  std::ifstream in(file);
  for (long p = 0; in >> p;) pids.push_back(static_cast<pid_t>(p));
  return pids;
}

/// The recorded processes still running once they have had `patience_s` to go (polled; the verdict
/// does not depend on the machine's speed, only a process that never goes fails it).
std::vector<pid_t> survivors(const std::vector<pid_t>& pids, double patience_s, double* gone_after_s = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<pid_t> alive;
  for (;;) {
    alive.clear();
    for (pid_t p : pids)
      if (running(p)) alive.push_back(p);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (alive.empty() || elapsed > patience_s) {
      if (gone_after_s) *gone_after_s = elapsed;
      for (pid_t p : alive) ::kill(p, SIGKILL);  // not left behind by the test either
      return alive;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

class External : public test::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    fs::create_directories(dir_ / "planners");
    std::ofstream(dir_ / "planners" / "misbehave.py") << kMisbehave;
    for (const char* mode : kModes)
      std::ofstream(dir_ / "planners" / (std::string(mode) + ".json"))
          << R"({"coverbench_planner": 1, "name": ")" << mode << R"(", "version": "1", "summary": "s", "reference": "r",
  "command": ["/usr/bin/python3", "misbehave.py", ")" << mode << R"("], "files": ["misbehave.py"]})";
    fs::create_directories(dir_ / "walls");
    std::ofstream(dir_ / "walls" / "a.json") << R"({"name": "a", "width": 2, "height": 1})";
    std::ofstream(dir_ / "walls" / "b.json") << R"({"name": "b", "width": 1.5, "height": 1.2})";
  }
  std::string config(const std::string& name, const std::string& planners, double time_s = 5) {
    return write(name + ".yaml", "name: " + name + "\noutput: " + name + "\ndatasets:\n  - folder: walls\nplanners:\n" +
                                     planners + "limits:\n  time_s: " + shortNumber(time_s) +
                                     "\n  memory_mb: 300\nthreads: 2\n");
  }
};

// Which status each gets must not depend on the machine's load: the planners that must meet
// something other than the time limit (the memory limit once the allocating one has touched
// 300 MiB, the 64 MiB answer limit once the flooding one has written that much, an answer, an
// exit, a signal) run under a time limit (600 s) none of them comes near on any machine, and the
// one that must meet the time limit (it sleeps) runs alone under 5 s.
TEST_F(External, EachMisbehavingPlannerGetsItsStatusAndTheOthersRunsAreUntouched) {
  std::string planners = "  - zigzag\n";
  for (const char* mode : {"fine", "garbage", "exits", "signal", "allocates", "floods", "wrong-id"})
    planners += std::string("  - external: planners/") + mode + ".json\n";
  const test::CommandRun bad = run("run " + config("bad", planners, 600) + " --no-report");
  ASSERT_EQ(bad.exit_code, 0) << bad.err;
  ResultSet rs = ResultsDb((dir_ / "bad/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 16u);
  const test::CommandRun sleepy = run("run " + config("sleepy", "  - external: planners/sleeps.json\n") + " --no-report");
  ASSERT_EQ(sleepy.exit_code, 0) << sleepy.err;
  for (ResultRow& r : ResultsDb((dir_ / "sleepy/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load().runs)
    rs.runs.push_back(std::move(r));
  ASSERT_EQ(rs.runs.size(), 18u);
  const std::map<std::string, RunStatus> expected = {
      {"zigzag", RunStatus::Ok},          {"fine", RunStatus::Ok},          {"sleeps", RunStatus::Timeout},
      {"garbage", RunStatus::InvalidOutput}, {"exits", RunStatus::Crash},   {"signal", RunStatus::Crash},
      {"allocates", RunStatus::MemoryLimit}, {"floods", RunStatus::InvalidOutput}, {"wrong-id", RunStatus::InvalidOutput}};
  const std::map<std::string, std::string> says = {
      {"sleeps", "did not answer within the time limit"}, {"garbage", "not JSON"},
      {"exits", "exited with code 3"},                    {"signal", "died of signal 11"},
      {"allocates", "past the memory limit of 300 MiB"},   {"floods", "over 64 MiB"},
      {"wrong-id", "id: must be the request's"}};
  for (const ResultRow& r : rs.runs) {
    EXPECT_EQ(r.status, expected.at(r.config)) << r.config << ": " << r.reason;
    if (says.count(r.config)) { EXPECT_NE(r.reason.find(says.at(r.config)), std::string::npos) << r.config << ": " << r.reason; }
  }
  // "fine" returned a valid path: judged like any other (valid; coverage far below 1).
  for (const ResultRow& r : rs.runs)
    if (r.config == "fine") {
      EXPECT_TRUE(r.valid);
      EXPECT_LT(r.metrics.at("coverage_reachable"), 0.2);
    }

  // zigzag's runs are the same as in an experiment without the misbehaving planners.
  ASSERT_EQ(run("run " + config("good", "  - zigzag\n", 600) + " --no-report").exit_code, 0);
  auto zigzag = [&](const std::string& db) {
    return test::sqlRows(db,
                         "SELECT r.key, r.status, r.valid, r.reason, m.name, quote(m.value) FROM runs r JOIN planner_configs p "
                         "ON p.id = r.config_id LEFT JOIN metrics m ON m.run_key = r.key WHERE p.planner = 'zigzag' "
                         "ORDER BY r.key, m.name");
  };
  EXPECT_EQ(zigzag((dir_ / "bad/results.sqlite").string()), zigzag((dir_ / "good/results.sqlite").string()));
  EXPECT_NE(zigzag((dir_ / "good/results.sqlite").string()).find("coverage_reachable"), std::string::npos);
}

TEST_F(External, TheExamplePythonPlannerRunsBesideInTreePlannersAndAChangedFileRunsItAgain) {
  fs::copy(test::sourcePath("examples/python_planner"), dir_ / "example", fs::copy_options::recursive);
  const std::string planners = "  - zigzag\n  - external: example/grid_sweep.json\n    params: {overlap: [0, 0.2]}\n";
  // The example's manifest runs `python3` from PATH (a pyenv shim here: 0.2 s to start idle, 1.4-
  // 4.2 s at a load of 20, which once made runs time out under 5 s): a limit no load comes near.
  const std::string mixed = config("mixed", planners, 600);
  std::string out;
  const test::CommandRun first = run("run " + mixed, &out);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const ResultSet rs = ResultsDb((dir_ / "mixed/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 6u);
  std::size_t python_runs = 0;
  for (const ResultRow& r : rs.runs)
    if (r.config.rfind("py-grid-sweep", 0) == 0) {
      ++python_runs;
      EXPECT_TRUE(hasPath(r.status)) << r.reason;
      EXPECT_TRUE(r.valid) << r.wall_name;
      EXPECT_GT(r.metrics.at("coverage_reachable"), 0.8) << r.wall_name;
    }
  EXPECT_EQ(python_runs, 4u);
  EXPECT_TRUE(fs::exists(dir_ / "mixed/report/index.html"));
  EXPECT_NE(slurp((dir_ / "mixed/report/index.html").string()).find("py-grid-sweep"), std::string::npos);

  // Nothing changed: nothing runs. The planner's file changed: its runs (only) run again.
  ASSERT_EQ(run("run " + mixed + " --no-report", &out).exit_code, 0);
  EXPECT_NE(out.find("(0 executed, 6 already stored)"), std::string::npos) << out;
  std::ofstream(dir_ / "example" / "grid_sweep.py", std::ios::app) << "\n# a comment changes the code's identity\n";
  ASSERT_EQ(run("run " + mixed + " --no-report", &out).exit_code, 0);
  EXPECT_NE(out.find("(4 executed, 2 already stored)"), std::string::npos) << out;
  EXPECT_NE(out.find("run again: 4 py-grid-sweep"), std::string::npos) << out;
}

// The C++ planner outside the tree (examples/cpp_planner, built with CoverBench) and the Python
// one beside two in-tree planners: the shipped experiments/external.yaml on the seed cases.
TEST_F(External, PlannersInPythonAndCppRunBesideInTreeOnesAndPassConformance) {
  fs::copy(test::sourcePath("examples"), dir_ / "examples", fs::copy_options::recursive);
  fs::remove_all(dir_ / "examples" / "cpp_planner" / "build");
  const std::string planners = "  - zigzag\n  - external: examples/python_planner/grid_sweep.json\n"
                               "  - external: examples/cpp_planner/column_sweep.json\n";
  const std::string cfg = write("mix.yaml", "name: mix\noutput: mix\ndatasets:\n  - suite: seed-cases\nplanners:\n" +
                                                planners + "tool:\n  width: 0.1\n  clearance: 0.02\n");
  std::string out;
  // run.sh finds the program CoverBench's build made (the copy here has no build of its own).
  ::setenv("COVERBENCH_BUILD_DIR", fs::path(COVERBENCH_BINARY).parent_path().string().c_str(), 1);
  const test::CommandRun r = run("run " + cfg + " --no-report", &out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ResultSet rs = ResultsDb((dir_ / "mix/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  std::map<std::string, std::size_t> with_path;
  for (const ResultRow& x : rs.runs) {
    EXPECT_NE(x.status, RunStatus::InvalidOutput) << x.config << " on " << x.wall_name << ": " << x.reason;
    EXPECT_NE(x.status, RunStatus::Crash) << x.config << ": " << x.reason;
    if (hasPath(x.status)) {
      EXPECT_TRUE(x.valid) << x.config << " on " << x.wall_name;
      ++with_path[x.config];
    }
  }
  EXPECT_EQ(with_path["cpp-column-sweep"], with_path["zigzag"]);
  EXPECT_EQ(with_path["py-grid-sweep"], with_path["zigzag"]);
  const test::CommandRun card =
      run("conformance " + (dir_ / "examples/cpp_planner/column_sweep.json").string() + " --walls " +
              test::sourcePath("datasets/conformance"),
          &out);
  EXPECT_EQ(card.exit_code, 0) << out;
  EXPECT_NE(out.find("20 of 20 passed"), std::string::npos) << out;
}

// Sharded and merged, an experiment with the Python planner equals one process, run key by run key.
TEST_F(External, AnExperimentWithThePythonPlannerShardsAndMergesLikeAnyOther) {
  fs::copy(test::sourcePath("examples/python_planner"), dir_ / "example", fs::copy_options::recursive);
  const std::string planners = "  - zigzag\n  - external: ../example/grid_sweep.json\n";
  fs::create_directories(dir_ / "single");
  fs::create_directories(dir_ / "sharded");
  const std::string text = "name: s\noutput: out\ndatasets:\n  - folder: ../walls\nplanners:\n" + planners;
  const std::string single = write("single/c.yaml", text), sharded = write("sharded/c.yaml", text);
  ASSERT_EQ(run("run " + single + " --no-report").exit_code, 0);
  std::string shards;
  for (int i = 0; i < 2; ++i) {
    const test::CommandRun r = run("run " + sharded + " --shard " + std::to_string(i) + "/2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    shards += " " + (dir_ / ("sharded/out/shards/shard-" + std::to_string(i) + "-of-2.sqlite")).string();
  }
  const test::CommandRun merged = run("merge " + (dir_ / "sharded/out/results.sqlite").string() + shards);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  const std::string a = test::dumpRuns((dir_ / "single/out/results.sqlite").string());
  EXPECT_EQ(test::dumpRuns((dir_ / "sharded/out/results.sqlite").string()), a);
  EXPECT_NE(a.find("ok"), std::string::npos);
  const ResultSet rs = ResultsDb((dir_ / "sharded/out/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  EXPECT_EQ(rs.runs.size(), 4u);
}

TEST_F(External, ManifestsAndAnswersAreCheckedWithOneLineErrors) {
  auto manifestError = [&](const std::string& text) {
    const std::string file = write("planners/m.json", text);
    try {
      external::loadManifest(file);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string head = R"({"coverbench_planner": 1, "name": "m", "version": "1", "summary": "s", "reference": "r", )";
  EXPECT_NE(manifestError(head + R"("command": ["python3"], "files": ["misbehave.py"], "extra": 1})").find("m.json: extra: unknown key"),
            std::string::npos);
  EXPECT_NE(manifestError(head + R"("command": [], "files": ["misbehave.py"]})").find("m.json: command: must be a non-empty list"),
            std::string::npos);
  EXPECT_NE(manifestError(head + R"("command": ["x"], "files": ["nope.py"]})").find("m.json: files[0]: is not a file"),
            std::string::npos);
  EXPECT_NE(manifestError(head + R"("command": ["x"], "files": ["misbehave.py"], "params": [{"name": "k", "type": "number",
      "default": 2, "min": 0, "max": 1, "description": "d"}]})")
                .find("m.json: params[0].default: is outside [min, max]"),
            std::string::npos);
  try {
    external::addFromManifest(write("planners/z.json", R"({"coverbench_planner": 1, "name": "zigzag", "version": "1",
      "summary": "s", "reference": "r", "command": ["x"], "files": ["misbehave.py"]})"));
    ADD_FAILURE() << "a registered planner's name was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("z.json: name: 'zigzag' is a registered planner's name"), std::string::npos) << e.what();
  }

  // A command that does not exist: crash, naming it.
  const PlannerInfo& missing = external::addFromManifest(write("planners/missing.json",
      R"({"coverbench_planner": 1, "name": "missing", "version": "1", "summary": "s", "reference": "r",
      "command": ["no-such-program-here"], "files": ["misbehave.py"]})"));
  const Wall wall = loadWallFile((dir_ / "walls" / "a.json").string());
  Problem problem;
  problem.wall = &wall;
  const PlanResult crashed = runPlanner(missing, problem, Budget(std::chrono::seconds(10)));
  EXPECT_EQ(crashed.status, PlanStatus::Crash);
  EXPECT_NE(crashed.reason.find("could not be started: no-such-program-here"), std::string::npos) << crashed.reason;

  // Answers: by hand, each a protocol error with its reason.
  PlanResult r;
  std::string why;
  EXPECT_TRUE(external::readAnswer(R"({"protocol":1,"id":7,"status":"ok","waypoints":[[0,0],[1,0]],"tool_on":[true],"stats":{"rows":1}})", 7, r, why)) << why;
  EXPECT_EQ(r.path.waypoints.size(), 2u);
  EXPECT_EQ(r.stats.at("rows"), 1.0);
  const std::map<std::string, std::string> bad = {
      {R"({"protocol":1,"id":7,"status":"ok","waypoints":[[0,0],[1,0]],"tool_on":[]})", "tool_on: must be a list of 1"},
      {R"({"protocol":1,"id":7,"status":"ok","waypoints":[[0,0],[1]],"tool_on":[true]})", "waypoints[1]: must be [x, y]"},
      {R"({"protocol":1,"id":7,"status":"fine"})", "status: 'fine' is none of"},
      {R"({"protocol":2,"id":7,"status":"ok"})", "protocol: must be 1"},
      {R"({"protocol":1,"id":7,"status":"error"})", "reason: a failed plan says why"},
      {R"({"protocol":1,"id":7,"status":"ok","waypoints":[[0,0],[1,0]],"tool_on":[true],"bulge":[2]})", "bulge[0]: must be a number in [-1, 1]"},
      {R"([1,2])", "must be a JSON object"}};
  for (const auto& [answer, reason] : bad) {
    PlanResult x;
    EXPECT_FALSE(external::readAnswer(answer, 7, x, why)) << answer;
    EXPECT_NE(why.find(reason), std::string::npos) << answer << " gave " << why;
  }
}

// The report card: every row passes for an in-tree planner and for the Python example; a planner
// that breaks its promise gets a failing card (exit 1) that says where.
TEST_F(External, ConformancePrintsAReportCardForAnyPlanner) {
  std::string out;
  const std::string walls = " --walls " + test::sourcePath("datasets/conformance") + " --format json";
  for (const std::string& planner : {std::string("zigzag"), test::sourcePath("examples/python_planner/grid_sweep.json")}) {
    const test::CommandRun r = run("conformance " + planner + walls, &out);
    ASSERT_EQ(r.exit_code, 0) << r.err << out;
    const nlohmann::json card = nlohmann::json::parse(out);
    EXPECT_EQ(card["checked"], 20);  // 10 walls at two tools
    EXPECT_EQ(card["passed"], 20);
    for (const auto& row : card["walls"]) {
      EXPECT_TRUE(row["contract"].get<bool>()) << row.dump();
      EXPECT_TRUE(row["deterministic"].get<bool>()) << row.dump();
      if (row["status"] == "ok" || row["status"] == "partial") { EXPECT_TRUE(row["valid"].get<bool>()) << row.dump(); }
    }
  }
  // "fine" paints 5 cm of a wall and promises 90 %: every row where the promise applies breaks it.
  std::ofstream(dir_ / "planners" / "boastful.json")
      << R"({"coverbench_planner": 1, "name": "boastful", "version": "1", "summary": "s", "reference": "r",
  "command": ["/usr/bin/python3", "misbehave.py", "fine"], "files": ["misbehave.py"], "min_coverage_reachable": 0.9})";
  const test::CommandRun r = run("conformance " + (dir_ / "planners" / "boastful.json").string() + " --walls " +
                                     test::sourcePath("datasets/conformance"),
                                 &out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(out.find("| **broken** |"), std::string::npos) << out;
  EXPECT_NE(r.err.find("boastful: "), std::string::npos) << r.err;
}

// Item 16: the protocol is strict. A duplicate key (a second "status") is refused, not read as the
// last one; nesting deeper than an answer needs is refused before the line is parsed (20 MiB of
// '[' cost the parser 1.6 GB and 30 s).
TEST_F(External, AnswersWithDuplicateKeysOrDeepNestingAreRefused) {
  PlanResult r;
  std::string why;
  EXPECT_FALSE(external::readAnswer(
      R"({"protocol":1,"id":7,"status":"error","reason":"gave up","status":"ok","waypoints":[[0,0],[1,0]],"tool_on":[true]})",
      7, r, why));
  EXPECT_NE(why.find("status: duplicate key"), std::string::npos) << why;
  PlanResult deep;
  const std::string nested = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_FALSE(external::readAnswer(nested, 7, deep, why));
  EXPECT_NE(why.find("nested deeper than 16 levels"), std::string::npos) << why;
  // Keys and values past what a path at the scoring limit needs are refused before parsing too.
  std::string stats = R"({"protocol":1,"id":7,"status":"error","reason":"x","stats":{)";
  for (int i = 0; i < 10001; ++i) stats += (i ? ",\"k" : "\"k") + std::to_string(i) + "\":1";
  PlanResult many;
  EXPECT_FALSE(external::readAnswer(stats + "}}", 7, many, why));
  EXPECT_NE(why.find("more than 10000 keys"), std::string::npos) << why;
  std::string ones = R"({"protocol":1,"id":7,"status":"ok","tool_on":[true],"waypoints":[)";
  for (int i = 0; i < 8010001; ++i) ones += "1,";
  PlanResult flat;
  EXPECT_FALSE(external::readAnswer(ones + "1]}", 7, flat, why));
  EXPECT_NE(why.find("more than 8010000 values"), std::string::npos) << why;
  // Brackets inside strings are text, not nesting.
  PlanResult quoted;
  EXPECT_TRUE(external::readAnswer(R"({"protocol":1,"id":7,"status":"error","reason":")" + std::string(100, '[') + R"("})",
                                   7, quoted, why))
      << why;
  // `plan` refuses 2 MiB of '[' as invalid_output naming the nesting, under its limits.
  std::string out;
  const test::CommandRun plan = run("plan --wall " + (dir_ / "walls/a.json").string() + " --planner " +
                                        (dir_ / "planners/nested.json").string() + " --out " + (dir_ / "p.json").string(),
                                    &out);
  EXPECT_EQ(plan.exit_code, 3) << plan.err;
  EXPECT_NE(out.find("invalid_output"), std::string::npos) << out;
  EXPECT_NE(out.find("nested deeper than 16 levels"), std::string::npos) << out;
}

// Item 16: a line written after the answer was read would be read as the next request's answer
// (here it carries the next id: it passed for it). It fails that run as invalid_output instead.
// The planner writes its second line only once the first run is over (a file says so), so the
// order of events does not depend on the machine's speed.
TEST_F(External, ALineAfterTheAnswerFailsTheNextRunInsteadOfAnsweringIt) {
  const PlannerInfo& twice = external::plannerNamed((dir_ / "planners/twice.json").string(), "test");
  const Wall a = loadWallFile((dir_ / "walls/a.json").string()), b = loadWallFile((dir_ / "walls/b.json").string());
  Problem pa, pb;
  pa.wall = &a;
  pb.wall = &b;
  const PlanResult first = runPlanner(twice, pa, Budget(std::chrono::seconds(600)));
  EXPECT_EQ(first.status, PlanStatus::Ok) << first.reason;
  std::ofstream(dir_ / "planners" / "go").close();
  for (int i = 0; i < 60000 && !fs::exists(dir_ / "planners" / "written"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(dir_ / "planners" / "written"));  // made after the line was written to the pipe
  const PlanResult second = runPlanner(twice, pb, Budget(std::chrono::seconds(600)));
  EXPECT_EQ(second.status, PlanStatus::InvalidOutput) << second.reason;
  EXPECT_NE(second.reason.find("wrote after its previous answer"), std::string::npos) << second.reason;
}

// Item 19: an answer the metrics engine cannot score (x = 1e300) fails its row of the report card,
// saying why, and the card goes on (it aborted with no card).
TEST_F(External, ConformanceGivesAnUnscorableAnswerAFailingRowAndGoesOn) {
  std::string out;
  const test::CommandRun r = run("conformance " + (dir_ / "planners/huge.json").string() + " --walls " +
                                     test::sourcePath("datasets/conformance") + " --format json",
                                 &out);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json card = nlohmann::json::parse(out);
  EXPECT_EQ(card["checked"], 20);
  EXPECT_EQ(card["passed"], 0);
  for (const auto& row : card["walls"]) {
    EXPECT_EQ(row["status"], "metrics_error") << row.dump();
    EXPECT_NE(row["reason"].get<std::string>().find("could not be scored"), std::string::npos) << row.dump();
    EXPECT_FALSE(row["passed"].get<bool>());
  }
}

// Item 14: the memory limit holds the planner's processes together: a child that touches 600 MiB
// under memory_mb 300 makes the run memory_limit (the planner's own resident set stays small). The
// time limit is one the child cannot reach first on any machine.
TEST_F(External, APlannersChildIsHeldToTheMemoryLimit) {
  const test::CommandRun r = run("run " + config("child", "  - external: planners/child-hog.json\n", 600) + " --no-report");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ResultSet rs = ResultsDb((dir_ / "child/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 2u);
  for (const ResultRow& row : rs.runs) {
    EXPECT_EQ(row.status, RunStatus::MemoryLimit) << row.reason;
    EXPECT_NE(row.reason.find("memory limit of 300 MiB"), std::string::npos) << row.reason;
  }
}

// The same where no cgroup can be made (most machines: cgroup v2, or not root): the resident sets
// of the planner's processes (found by their token) are summed. The child keeps its 600 MiB, so the
// sum passes the limit whenever it is read, however loaded the machine.
TEST_F(External, APlannersChildIsHeldToTheMemoryLimitWithoutCgroups) {
  ::setenv("COVERBENCH_PLANNER_CGROUPS", "0", 1);
  const test::CommandRun r = run("run " + config("child", "  - external: planners/child-holds.json\n", 600) + " --no-report");
  ::unsetenv("COVERBENCH_PLANNER_CGROUPS");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ResultSet rs = ResultsDb((dir_ / "child/results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
  ASSERT_EQ(rs.runs.size(), 2u);
  for (const ResultRow& row : rs.runs) {
    EXPECT_EQ(row.status, RunStatus::MemoryLimit) << row.reason;
    EXPECT_NE(row.reason.find("past the memory limit of 300 MiB"), std::string::npos) << row.reason;
  }
}

// Item 15: every process a run started is gone when the run ends: the planner that ignores the
// end of its input (and SIGTERM) and the child it started in a session of its own (setsid), after a
// normal `run` and after `plan`.
TEST_F(External, NoProcessARunStartedOutlivesIt) {
  ASSERT_EQ(run("run " + config("orphans", "  - external: planners/orphans.json\n") + " --no-report").exit_code, 0);
  std::vector<pid_t> pids = recordedPids(dir_ / "planners" / "pids.txt");
  ASSERT_GE(pids.size(), 3u);
  EXPECT_EQ(survivors(pids, 60), std::vector<pid_t>{}) << "left running after `coverbench run`";
  fs::remove(dir_ / "planners" / "pids.txt");
  const test::CommandRun plan = run("plan --wall " + (dir_ / "walls/a.json").string() + " --planner " +
                                    (dir_ / "planners/orphans.json").string() + " --out " + (dir_ / "p.json").string());
  EXPECT_EQ(plan.exit_code, 0) << plan.err;  // a valid path of 5 cm
  pids = recordedPids(dir_ / "planners" / "pids.txt");
  ASSERT_EQ(pids.size(), 3u);
  EXPECT_EQ(survivors({pids[0], pids[1]}, 60), std::vector<pid_t>{}) << "left running after `coverbench plan`";
}

// Item 15: `coverbench run` killed with kill -9 while a planner (which started a child in its own
// session) is answering: its workers, the planner and the child die too (PR_SET_PDEATHSIG for the
// workers and the planner, the run's guardian for the rest; in 5 s here, polled for up to 60 s so
// that a loaded machine gives the same verdict).
TEST_F(External, KillingTheRunnerKillsEveryProcessItStarted) {
  const std::string cfg = config("killed", "  - external: planners/orphans-sleep.json\n", 600);
  const pid_t runner = ::fork();
  ASSERT_GE(runner, 0);
  if (runner == 0) {
    ::setpgid(0, 0);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::chdir(dir_.c_str());
    ::execl(COVERBENCH_BINARY, COVERBENCH_BINARY, "run", cfg.c_str(), "--no-report", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const fs::path file = dir_ / "planners" / "pids.txt";
  // A planner has recorded itself, its child and its worker.
  for (int i = 0; i < 60000 && recordedPids(file).size() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_GE(recordedPids(file).size(), 3u);
  ASSERT_EQ(::kill(runner, SIGKILL), 0);
  ASSERT_EQ(::waitpid(runner, nullptr, 0), runner);
  const std::vector<pid_t> pids = recordedPids(file);  // a second planner may have recorded itself meanwhile
  double gone_after = 0.0;
  EXPECT_EQ(survivors(pids, 60, &gone_after), std::vector<pid_t>{}) << "left running after kill -9 of `coverbench run`";
  std::printf("[          ] every process was gone %.2f s after kill -9 of the runner\n", gone_after);
}


// Issue 61, acceptance 2: a planner that crashes on walls with holes (tests/data/crash_on_holes):
// `coverbench runs DB` shows, for those runs, the reason and the end of the planner's stderr (the
// last kStderrTailBytes, bytes that are not UTF-8 replaced), labelled by wall and tool; the runs
// it finished keep no stderr. The CSV and JSON also carry the planner's parameters and CPU time.
TEST_F(External, ACrashingPlannersReasonAndTheEndOfItsStderrAreShownByRuns) {
  fs::copy(test::sourcePath("tests/data/crash_on_holes"), dir_ / "crash", fs::copy_options::recursive);
  std::ofstream(dir_ / "walls" / "holes.json")
      << R"({"name": "holes", "width": 2, "height": 1, "obstacles": [{"type": "rect", "x": 0.8, "y": 0.3, "width": 0.4, "height": 0.4, "label": "window"}]})";
  const test::CommandRun ran = run("run " + config("crash", "  - external: crash/crash_on_holes.json\n", 600) + " --no-report");
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  const std::string db = (dir_ / "crash/results.sqlite").string();
  std::string json_text, csv;
  ASSERT_EQ(run("runs " + db + " --format json", &json_text).exit_code, 0);
  ASSERT_EQ(run("runs " + db, &csv).exit_code, 0);
  const nlohmann::json runs = nlohmann::json::parse(json_text);
  ASSERT_EQ(runs.size(), 3u);
  std::size_t crashed = 0;
  for (const auto& r : runs) {
    ASSERT_TRUE(r.contains("reason") && r.contains("stderr_tail") && r.contains("params") && r.contains("cpu_time_s")) << r.dump();
    EXPECT_TRUE(r["params"].is_object());
    EXPECT_TRUE(r["cpu_time_s"].is_number()) << r.dump();
    if (r["wall"] != "holes") {
      EXPECT_EQ(r["status"], "ok");
      EXPECT_EQ(r["stderr_tail"], "") << "an ok run keeps no stderr";
      continue;
    }
    ++crashed;
    EXPECT_EQ(r["status"], "crash");
    EXPECT_TRUE(r["tool_width"].is_number() && r["clearance"].is_number());  // labelled by wall and tool
    EXPECT_NE(r["reason"].get<std::string>().find("exited with code 1"), std::string::npos) << r["reason"];
    const std::string tail = r["stderr_tail"];
    const std::string end = "RuntimeError: holes are not supported: 1 obstacles on holes\n";
    ASSERT_GE(tail.size(), end.size());
    EXPECT_EQ(tail.substr(tail.size() - end.size()), end);
    EXPECT_NE(tail.find("Traceback (most recent call last)"), std::string::npos);
    EXPECT_NE(tail.find("not UTF-8: \xEF\xBF\xBD\xEF\xBF\xBD <- two bytes\n"), std::string::npos) << "replaced";
    EXPECT_EQ(tail.find("planning holes"), std::string::npos) << "written more than 4 KiB before the end";
    EXPECT_LE(tail.size(), external::kStderrTailBytes + 4);  // two bytes replaced by three each
    EXPECT_GT(tail.size(), external::kStderrTailBytes - 4);
  }
  EXPECT_EQ(crashed, 1u);
  // The CSV: a column each, the stderr's lines in one quoted cell.
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",params,"), std::string::npos) << header;
  EXPECT_NE(header.find(",reason,"), std::string::npos) << header;
  EXPECT_NE(header.find(",cpu_time_s,"), std::string::npos) << header;
  EXPECT_NE(header.find(",stderr_tail"), std::string::npos) << header;
  EXPECT_NE(csv.find("RuntimeError: holes are not supported: 1 obstacles on holes\n\""), std::string::npos) << csv;
  // The database keeps it as text.
  EXPECT_NE(test::sqlRows(db, "SELECT typeof(stderr_tail) FROM runs WHERE status = 'crash'").find("text"), std::string::npos);
}

// Issue 61: an external planner's CPU time and memory are its own processes', not the worker's.
// The planner burns at least 1.5 s of its own CPU time (by its own clock, however long that
// takes) and touches 200 MiB before answering; the worker meanwhile only waits.
TEST_F(External, AnExternalPlannersCpuAndMemoryAreItsOwn) {
  std::ofstream(dir_ / "planners" / "heavy.py") << R"py(import json, sys, time
for line in sys.stdin:
    req = json.loads(line)
    hog = bytearray(200 << 20)
    for i in range(0, len(hog), 4096):
        hog[i] = 1
    while time.process_time() < 1.5:
        pass
    p = req["problem"]
    r = p["tool"]["width"] / 2 + p["tool"]["clearance"] + 0.01
    print(json.dumps({"protocol": 1, "id": req["id"], "status": "ok", "waypoints": [[r, r], [r + 0.05, r]],
                      "tool_on": [True]}), flush=True)
    del hog
)py";
  std::ofstream(dir_ / "planners" / "heavy.json")
      << R"({"coverbench_planner": 1, "name": "heavy", "version": "1", "summary": "s", "reference": "r",
  "command": ["/usr/bin/python3", "heavy.py"], "files": ["heavy.py"]})";
  fs::remove(dir_ / "walls" / "b.json");  // one run: the first plan of the process
  // Measured from its cgroup where one can be made, and (COVERBENCH_PLANNER_CGROUPS=0) from /proc.
  for (const char* cgroups : {"1", "0"}) {
    ::setenv("COVERBENCH_PLANNER_CGROUPS", cgroups, 1);
    const std::string name = std::string("heavy") + cgroups;
    const test::CommandRun ran = run("run " + config(name, "  - external: planners/heavy.json\n", 600) + " --no-report");
    ::unsetenv("COVERBENCH_PLANNER_CGROUPS");
    ASSERT_EQ(ran.exit_code, 0) << ran.err;
    ResultSet rs = ResultsDb((dir_ / name / "results.sqlite").string(), ResultsDb::Mode::ReadOnly).load();
    ASSERT_EQ(rs.runs.size(), 1u);
    EXPECT_EQ(rs.runs[0].status, RunStatus::Ok) << rs.runs[0].reason;
    // /proc counts CPU time in clock ticks (1/100 s each for user and system time, truncated): at
    // least 1.4 s of the 1.5 s; the worker itself, waiting on the pipe, spends a few hundredths.
    EXPECT_GE(rs.runs[0].cpu_time_s, 1.4) << name;
    EXPECT_GE(rs.runs[0].peak_memory_bytes, 200.0 * 1024 * 1024) << name;
    EXPECT_GE(rs.runs[0].peak_rss_bytes, 200.0 * 1024 * 1024) << name;
  }
}

}  // namespace
}  // namespace coverbench
