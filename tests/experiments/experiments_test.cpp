// Experiment configs (errors name the line), run keys, runs as pure functions, the runner's
// resume and skip behaviour, and the tables computed from hand-made results.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>
#include <set>

#include "coverbench/build_identity.hpp"
#include "coverbench/files.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/records.hpp"
#include "test_support.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

class Experiments : public test::TempDirTest {
 protected:
  std::string config(const std::string& text, const std::string& name = "exp.yaml") {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  /// The message of the InputError that loading `text` throws ("" if none).
  std::string error(const std::string& text) {
    try {
      loadExperimentConfig(config(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

const char* const kGood = R"(name: t
output: out
datasets:
  - suite: seed-cases
  - family: residential
    count: 4
    seed: 2
planners:
  - zigzag
  - name: spiral
    params:
      overlap: [0, 0.25]
tool:
  width: 0.1
  clearance: 0.02
threads: 2
)";

TEST_F(Experiments, ConfigExpandsSweepsAndResolvesPaths) {
  const ExperimentConfig c = loadExperimentConfig(config(kGood));
  ASSERT_EQ(c.planners.size(), 3u);
  EXPECT_EQ(c.planners[0].label, "zigzag");
  EXPECT_EQ(c.planners[1].label, "spiral(overlap=0)");
  EXPECT_EQ(c.planners[2].label, "spiral(overlap=0.25)");
  EXPECT_NE(c.planners[1].id, c.planners[2].id);
  EXPECT_EQ(c.baseline, "zigzag");
  EXPECT_EQ(c.output, (dir_ / "out").string());
  ASSERT_EQ(c.datasets.size(), 2u);
  EXPECT_EQ(c.datasets[1].label, "residential");
  const std::vector<WallEntry> walls = loadWalls(c);
  EXPECT_EQ(walls.size(), 9u + 4u);
  EXPECT_EQ(expandRuns(c, walls).size(), 13u * 3u);
}

TEST_F(Experiments, ConfigErrorsNameTheLineAndTheKey) {
  auto replace = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  const std::string file = (dir_ / "exp.yaml").string();
  EXPECT_EQ(error(replace(kGood, "  - name: spiral", "  - nmae: spiral")),
            file + ":10: planners[1].nmae: unknown key (did you mean 'name'?)");
  EXPECT_EQ(error(replace(kGood, "planners:", "planers:")).substr(0, file.size() + 12), file + ":8: planers:");
  EXPECT_NE(error(replace(kGood, "overlap: [0, 0.25]", "overlap: [0, 2.5]")).find(file + ":12: planners[1].params.overlap:"),
            std::string::npos);
  EXPECT_NE(error(replace(kGood, "width: 0.1", "width: -0.1")).find(file + ":14: tool.width: must be in [0.001, 10]"),
            std::string::npos);
  EXPECT_NE(error(replace(kGood, "count: 4", "count: many")).find(":6: datasets[1].count: must be a number"),
            std::string::npos);
  EXPECT_NE(error(replace(kGood, "family: residential", "family: residental")).find(":5: datasets[1].family: unknown family"),
            std::string::npos);
  EXPECT_NE(error(replace(kGood, "  - zigzag", "  - zigzog")).find(":9: planners[0].name: unknown planner 'zigzog'"),
            std::string::npos);
  EXPECT_NE(error(replace(kGood, "      overlap:", "      sweep_angle:")).find(":12: planners[1].params.sweep_angle: unknown key"),
            std::string::npos);
  EXPECT_NE(error(std::string(kGood) + "baseline: nobody\n").find(":17: baseline: 'nobody' is not one of"), std::string::npos);
  EXPECT_NE(error(replace(kGood, "  - suite: seed-cases", "  - suite: seed-cases\n    count: 3")).find("no count or seed"),
            std::string::npos);
  EXPECT_NE(error("name: [unclosed\n").find("YAML syntax"), std::string::npos);
  EXPECT_NE(error(replace(kGood, "output: out\n", "")).find(":1: output: missing"), std::string::npos);
}

// tool.profile: one flux profile for every tool of the config, checked against each width; its
// errors name the line and the key.
TEST_F(Experiments, AToolsFluxProfileIsReadForEveryToolAndItsErrorsNameTheKey) {
  auto with = [](const std::string& profile) {
    std::string text = kGood;
    return text.replace(text.find("  width: 0.1\n"), 13, "  width: [0.1, 0.3]\n  profile:\n" + profile);
  };
  const ExperimentConfig c = loadExperimentConfig(config(with("    kind: beta\n    beta: 2.5\n    rate: 2e-6\n")));
  ASSERT_EQ(c.tools.size(), 2u);
  for (const ToolParams& t : c.tools) {
    EXPECT_EQ(t.profile.kind, FluxProfile::Kind::Beta);
    EXPECT_EQ(t.profile.beta, 2.5);
    EXPECT_EQ(t.profile.rate, 2e-6);
  }
  EXPECT_FALSE(loadExperimentConfig(config(kGood)).tools[0].profile.set());  // no profile: none
  const std::string file = (dir_ / "exp.yaml").string();
  EXPECT_EQ(error(with("    beta: 2\n")), file + ":16: tool.profile.kind: is missing: uniform, gaussian or beta");
  EXPECT_EQ(error(with("    kind: cone\n")), file + ":16: tool.profile.kind: must be uniform, gaussian or beta, got 'cone'");
  EXPECT_EQ(error(with("    kind: beta\n    sigma: 0.01\n")), file + ":17: tool.profile.sigma: belongs to a gaussian profile");
  EXPECT_EQ(error(with("    kind: gaussian\n")), file + ":16: tool.profile.sigma: is missing: a gaussian profile's standard deviation, m");
  // sigma at least s/50: 0.004 m suits the 0.1 m tool, not the 0.3 m one.
  EXPECT_EQ(error(with("    kind: gaussian\n    sigma: 0.004\n")),
            file + ":17: tool.profile.sigma: must be in [s/50, 100] m (s/50 = 0.006 m), got 0.004 (tool width 0.3 m)");
  EXPECT_EQ(error(with("    kind: uniform\n    rate: 0\n")), file + ":17: tool.profile.rate: must be in (0, 1], got 0");
  EXPECT_EQ(error(with("    kind: uniform\n    spread: 1\n")).substr(0, file.size() + 33), file + ":17: tool.profile.spread: unknown");
  // A target thickness, micrometres: optional (none: 0), and when given in (0, 1e6].
  EXPECT_EQ(c.tools[0].profile.target, 0.0);
  EXPECT_EQ(loadExperimentConfig(config(with("    kind: beta\n    beta: 2.5\n    target: 25\n"))).tools[1].profile.target, 25.0);
  EXPECT_EQ(error(with("    kind: uniform\n    target: 0\n")), file + ":17: tool.profile.target: must be in (0, 1e+06], got 0");
  EXPECT_EQ(error(with("    kind: uniform\n    target: -3\n")), file + ":17: tool.profile.target: must be in (0, 1e+06], got -3");
  EXPECT_EQ(error(with("    kind: uniform\n    target: 2e6\n")), file + ":17: tool.profile.target: must be in (0, 1e+06], got 2e6");
  EXPECT_EQ(error(with("    kind: uniform\n    target: .nan\n")), file + ":17: tool.profile.target: must be a number, got '.nan'");
  // The gun's flow: constant (the default) or speed (it follows the tool's speed).
  EXPECT_EQ(c.tools[0].profile.flow, FluxProfile::Flow::Constant);
  EXPECT_EQ(loadExperimentConfig(config(with("    kind: uniform\n    flow: speed\n"))).tools[1].profile.flow, FluxProfile::Flow::Speed);
  EXPECT_EQ(loadExperimentConfig(config(with("    kind: uniform\n    flow: constant\n"))).tools[1].profile.flow,
            FluxProfile::Flow::Constant);
  EXPECT_EQ(error(with("    kind: uniform\n    flow: fast\n")), file + ":17: tool.profile.flow: must be constant or speed, got 'fast'");
}

TEST_F(Experiments, AllMeansEveryRegisteredPlanner) {
  std::string text = kGood;
  text.replace(text.find("planners:"), text.find("tool:") - text.find("planners:"), "planners: [all]\n");
  const ExperimentConfig c = loadExperimentConfig(config(text));
  ASSERT_EQ(c.planners.size(), registeredPlanners().size());
  for (std::size_t i = 0; i < c.planners.size(); ++i) EXPECT_EQ(c.planners[i].label, registeredPlanners()[i].name);
}

TEST_F(Experiments, RunKeysChangeWithEveryInputAndNothingElse) {
  const ExperimentConfig c = loadExperimentConfig(config(kGood));
  const std::vector<WallEntry> walls = loadWalls(c);
  const std::vector<RunSpec> runs = expandRuns(c, walls);
  std::set<std::string> keys;
  for (const RunSpec& r : runs) keys.insert(r.key);
  EXPECT_EQ(keys.size(), runs.size());
  RunSpec r = runs[0];
  const std::string key = runKey(r);
  r.time_limit_s = 1.0;  // limits are not part of what a run computes
  EXPECT_EQ(runKey(r), key);
  r.tool.clearance = 0.03;
  EXPECT_NE(runKey(r), key);
  r = runs[0];
  r.repetitions = 5;  // repetitions re-time the same work
  EXPECT_EQ(runKey(r), key);
  r = runs[0];
  r.seed = 7;
  EXPECT_NE(runKey(r), key);
  r = runs[0];
  r.motion.stops = MotionLimits::Stops::Waypoints;  // another clock: other durations
  EXPECT_NE(runKey(r), key);
  // A flux profile is a different tool (other metrics, and rows a planner may space for it); each
  // of its values counts.
  r = runs[0];
  r.tool.profile.kind = FluxProfile::Kind::Beta;
  r.tool.profile.beta = 2.5;
  const std::string coat = runBaseKey(r);
  EXPECT_NE(coat, runs[0].base_key);
  r.tool.profile.beta = 3;
  EXPECT_NE(runBaseKey(r), coat);
  r.tool.profile.beta = 2.5;
  r.tool.profile.rate = 2e-6;
  EXPECT_NE(runBaseKey(r), coat);
  // A target enters the key only when there is one: a profile without one keeps its key (the
  // key's text is unchanged; tests/experiments/profile_runs_test.cpp pins a stored key).
  r.tool.profile.rate = 1e-6;
  r.tool.profile.target = 0.0;
  EXPECT_EQ(runBaseKey(r), coat);
  r.tool.profile.target = 25.0;
  const std::string targeted = runBaseKey(r);
  EXPECT_NE(targeted, coat);
  r.tool.profile.target = 30.0;
  EXPECT_NE(runBaseKey(r), targeted);
  // The planner's version and code identity change the key, not the base key.
  r = runs[0];
  r.planner_version += "-next";
  EXPECT_NE(runKey(r), key);
  EXPECT_EQ(runBaseKey(r), runs[0].base_key);
  r = runs[0];
  r.code_sha256 = std::string(64, '0');
  EXPECT_NE(runKey(r), key);
  EXPECT_EQ(runs[0].code_sha256, buildIdentity().plannerCode(findPlanner(runs[0].planner->planner).code_folders));
}

TEST_F(Experiments, ARunIsAPureFunctionOfItsInputs) {
  const ExperimentConfig c = loadExperimentConfig(config(kGood));
  const std::vector<WallEntry> walls = loadWalls(c);
  const std::vector<RunSpec> runs = expandRuns(c, walls);
  for (std::size_t i : {0ul, 5ul, runs.size() - 1}) {
    const RunRecord a = executeRun(runs[i]), b = executeRun(runs[i]);
    ASSERT_EQ(a.status, RunStatus::Ok) << a.reason;
    EXPECT_EQ(encodePath(a.path), encodePath(b.path));
    EXPECT_EQ(a.metrics, b.metrics);
  }
}

// `judge: exact`: every scored run also carries the exact judge's verdict and certified coverage
// intervals, the fast engine's coverage lies within its stated bound of them, and the keys (base
// key and code identity, which then includes the judge's code) differ from the fast-only runs'.
TEST_F(Experiments, TheExactJudgeOptionStoresItsFiguresUnderItsOwnKeys) {
  const std::string small = "name: j\noutput: out\ndatasets:\n  - family: gable\n    count: 1\n    seed: 3\n"
                            "planners:\n  - zigzag\n  - spanning-tree\ntool:\n  width: 0.2\n";
  const ExperimentConfig fast = loadExperimentConfig(config(small, "fast.yaml"));
  const ExperimentConfig exact = loadExperimentConfig(config(small + "judge: exact\n", "exact.yaml"));
  EXPECT_FALSE(fast.exact_judge);
  ASSERT_TRUE(exact.exact_judge);
  const std::vector<WallEntry> walls = loadWalls(exact);
  const std::vector<RunSpec> fast_runs = expandRuns(fast, walls), exact_runs = expandRuns(exact, walls);
  ASSERT_EQ(exact_runs.size(), 2u);
  for (std::size_t i = 0; i < exact_runs.size(); ++i) {
    EXPECT_NE(exact_runs[i].base_key, fast_runs[i].base_key);
    EXPECT_NE(exact_runs[i].code_sha256, fast_runs[i].code_sha256);
    const RunRecord rec = executeRun(exact_runs[i]);
    ASSERT_TRUE(rec.valid) << rec.reason;
    std::map<std::string, double> m;
    for (const auto& [name, value] : rec.metrics) m[name] = value;
    for (const char* name : kExactJudgeMetrics) ASSERT_TRUE(m.count(name)) << name;
    EXPECT_EQ(m["exact_valid"], 1.0);
    EXPECT_EQ(m["exact_violations"], 0.0);
    EXPECT_LT(m["exact_coverage_reachable_lower"], m["exact_coverage_reachable_upper"]);
    EXPECT_GE(m["coverage_reachable"], m["exact_coverage_reachable_lower"] - fastErrorBound(0.2));
    EXPECT_LE(m["coverage_reachable"], m["exact_coverage_reachable_upper"] + fastErrorBound(0.2));
    EXPECT_GE(m["coverage_wall"], m["exact_coverage_wall_lower"] - fastErrorBound(0.2));
    EXPECT_LE(m["coverage_wall"], m["exact_coverage_wall_upper"] + fastErrorBound(0.2));
    for (const auto& [name, value] : executeRun(fast_runs[i]).metrics) EXPECT_EQ(name.rfind("exact_", 0), std::string::npos);
  }
  EXPECT_NE(error(small + "judge: strict\n").find(":12: judge: must be fast or exact, not 'strict'"), std::string::npos);
}

// A coat past the raster cap (a gaussian of sigma s/50 on cells of sigma/5 over a field of 2.8 ha)
// loses only the coat: the run keeps its status and every other metric (as a coat that fits has
// them), the five coat metrics are stored with no value, and the reason says why.
TEST_F(Experiments, ACoatPastTheRasterCapKeepsTheOtherMetricsAndSaysWhy) {
  // A field of 2.8 ha and a 2 m tool: cells of min(s/40, spread/5), 0.05 m at sigma 1 m (4.6e7
  // samples), 0.008 m at sigma 0.04 m (2.5e9 samples, past kMaxCoatSamples).
  const std::string head = "name: c\noutput: out\ndatasets:\n  - family: field\n    count: 1\n    seed: 3\n"
                           "planners:\n  - zigzag\ntool:\n  width: 2.0\n  profile: {kind: gaussian, sigma: ";
  // (A run spec points into its config's walls: both are kept.)
  const ExperimentConfig fine_config = loadExperimentConfig(config(head + "1.0}\n", "fine.yaml"));
  const ExperimentConfig too_fine_config = loadExperimentConfig(config(head + "0.04}\n", "too_fine.yaml"));
  const std::vector<WallEntry> fine_walls = loadWalls(fine_config), too_fine_walls = loadWalls(too_fine_config);
  const std::vector<RunSpec> fine = expandRuns(fine_config, fine_walls), too_fine = expandRuns(too_fine_config, too_fine_walls);
  ASSERT_EQ(fine.size(), 1u);
  ASSERT_EQ(too_fine.size(), 1u);
  const RunRecord scored = executeRun(fine[0]), unscored = executeRun(too_fine[0]);
  ASSERT_EQ(scored.status, RunStatus::Ok) << scored.reason;
  EXPECT_EQ(scored.reason, "");
  EXPECT_EQ(unscored.status, RunStatus::Ok) << unscored.reason;
  EXPECT_TRUE(unscored.valid);
  EXPECT_EQ(unscored.reason.rfind("the coat's metrics are not scored (the others are): deposition: tool.profile: needs a "
                                  "coat raster of ", 0),
            0u)
      << unscored.reason;
  ASSERT_EQ(unscored.metrics.size(), scored.metrics.size());
  const std::set<std::string> coat = {"thickness_mean", "thickness_cv", "even_share", "thin_share", "thick_share"};
  for (std::size_t i = 0; i < scored.metrics.size(); ++i) {
    const auto& [name, value] = unscored.metrics[i];
    EXPECT_EQ(name, scored.metrics[i].first);
    if (coat.count(name)) {
      EXPECT_TRUE(std::isnan(value)) << name;
      EXPECT_TRUE(std::isfinite(scored.metrics[i].second)) << name;
    } else if (!std::isnan(value)) {
      EXPECT_EQ(value, scored.metrics[i].second) << name;
    }
  }
}

TEST(PathEncoding, RoundTripsExactly) {
  Path p;
  p.moveTo({0.1, 1.0 / 3.0}, false);
  p.moveTo({-2.5e-9, 1e300}, true);
  p.moveTo({4.0, 4.0}, false);
  p.moveTo({4.0, 4.0}, true);
  const Path q = decodePath(encodePath(p));
  ASSERT_EQ(q.waypoints.size(), p.waypoints.size());
  for (std::size_t i = 0; i < p.waypoints.size(); ++i) EXPECT_TRUE(q.waypoints[i] == p.waypoints[i]);
  EXPECT_EQ(q.tool_on, p.tool_on);
  EXPECT_TRUE(decodePath(encodePath(Path{})).waypoints.empty());
  EXPECT_THROW(decodePath(encodePath(p).substr(0, 10)), std::runtime_error);
}

TEST_F(Experiments, SecondRunDoesNoWorkAndGivesIdenticalRunsAndAGrownConfigOnlyRunsWhatIsNew) {
  std::string small = kGood;
  small.replace(small.find("count: 4"), 8, "count: 2");
  RunnerOptions options;
  const RunnerSummary first = runExperiment(loadExperimentConfig(config(small)), options);
  EXPECT_EQ(first.total, (9u + 2u) * 3u);
  EXPECT_EQ(first.executed, first.total);
  const std::string db = first.database;
  const std::string csv = renderRuns(ResultsDb(db).load(), false);
  const std::string json = renderRuns(ResultsDb(db).load(), true);

  const RunnerSummary second = runExperiment(loadExperimentConfig(config(small)), options);
  EXPECT_EQ(second.executed, 0u);
  EXPECT_EQ(second.skipped, second.total);
  EXPECT_EQ(renderRuns(ResultsDb(db).load(), false), csv);
  EXPECT_EQ(renderRuns(ResultsDb(db).load(), true), json);

  // Two more walls of the same family: walls 0 and 1 are the same, so only the new ones run (a
  // killed run resumes the same way: whatever is stored is skipped).
  const RunnerSummary grown = runExperiment(loadExperimentConfig(config(kGood)), options);
  EXPECT_EQ(grown.total, (9u + 4u) * 3u);
  EXPECT_EQ(grown.executed, 2u * 3u);

  // Every stored path can be redrawn, and the tables see every run of the latest experiment.
  ResultsDb results(db);
  const ResultSet rs = results.load();
  EXPECT_EQ(rs.runs.size(), grown.total);
  for (const ResultRow& r : rs.runs) {
    EXPECT_TRUE(hasPath(r.status)) << r.status;
    EXPECT_TRUE(r.valid);
    // A partial run says how much reachable area it left, in numbers.
    if (r.status == RunStatus::Partial) {
      EXPECT_GT(r.uncovered_reachable_m2, 0.0);
    }
  }

  // The explorer's reads (summaries, metric names, a metric by column, metrics by run) say what
  // load() says, run by run.
  const long long id = results.experiments().back().id;
  const auto summaries = results.runSummaries(id);
  EXPECT_EQ(results.metricNames(id), rs.metric_order);
  ASSERT_EQ(summaries.size(), rs.runs.size());
  std::map<std::string, const ResultRow*> by_key;
  for (const ResultRow& r : rs.runs) by_key[r.key] = &r;
  std::vector<std::string> keys;
  for (const auto& s : summaries) keys.push_back(s.key);
  const auto metrics = results.metricsOf(keys);
  for (const std::string& name : {std::string("coverage_reachable"), std::string("overlap"), std::string("min_clearance")}) {
    const std::vector<double> column = results.metricColumn(id, name);
    ASSERT_EQ(column.size(), summaries.size()) << name;
    for (std::size_t i = 0; i < summaries.size(); ++i) {
      const ResultRow& r = *by_key.at(summaries[i].key);
      const auto it = r.metrics.find(name);
      if (it == r.metrics.end()) EXPECT_TRUE(std::isnan(column[i])) << name << " " << r.key;
      else EXPECT_EQ(column[i], it->second) << name << " " << r.key;
    }
  }
  for (std::size_t i = 0; i < summaries.size(); ++i) {
    const auto& s = summaries[i];
    ASSERT_TRUE(by_key.count(s.key));
    const ResultRow& r = *by_key.at(s.key);
    if (i > 0) { EXPECT_LT(summaries[i - 1].key, s.key); }
    EXPECT_EQ(s.planner, r.planner);
    EXPECT_EQ(s.dataset, r.dataset);
    EXPECT_EQ(s.wall, r.wall);
    EXPECT_EQ(s.wall_name, r.wall_name);
    EXPECT_EQ(s.status, r.status);
    EXPECT_EQ(s.tool.tool_width, r.tool.tool_width);
    EXPECT_EQ(s.plan_time_ms, r.plan_time_ms);
    EXPECT_EQ(metrics.at(s.key), r.metrics) << s.key;
  }
}

}  // namespace
}  // namespace coverbench
