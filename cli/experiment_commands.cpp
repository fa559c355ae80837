// Sub-commands for datasets, experiments and tables.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/files.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

}  // namespace

int datasetGenerateCommand(const DatasetGenerateOptions& o) {
  const FamilyInfo& info = findFamily(o.family, "--family", "family");
  if (info.fixed_suite ? o.count < 0 : o.count < 1) throw InputError("--count", "count", info.fixed_suite ? "must not be negative, got " + std::to_string(o.count) : "must be at least 1, got " + std::to_string(o.count));
  if (o.count > 1000000) throw InputError("--count", "count", "must be at most 1000000, got " + std::to_string(o.count));
  if (o.seed < 0 || o.seed > (1LL << 53))
    throw InputError("--seed", "seed", "must be in [0, 2^53], got " + std::to_string(o.seed));
  const auto count = static_cast<std::size_t>(o.count);
  const auto seed = static_cast<std::uint64_t>(o.seed);
  if (count >= 10000) std::cerr << "generating " << count << " walls of " << o.family << " ...\n";
  const std::vector<Wall> walls = generateWalls(o.family, seed, count);
  const Dataset d = writeDataset(o.out, o.family, info.fixed_suite ? 0 : seed, walls);
  std::cout << "wrote " << d.entries.size() << " walls and manifest.json to " << o.out << "\n" << describeDataset(d);
  return 0;
}

int datasetShowCommand(const std::string& dir) {
  std::cout << describeDataset(readDataset(dir));
  return 0;
}

int datasetFamiliesCommand() {
  for (const FamilyInfo& f : wallFamilies())
    std::cout << f.name << (f.fixed_suite ? " (suite of " + std::to_string(suiteSize(f.name)) + " walls)" : "") << ": "
              << f.summary << "\n";
  return 0;
}

int runCommand(const RunOptions& o) {
  const ExperimentConfig config = loadExperimentConfig(o.config);  // every check before any run
  const std::size_t planned = plannedRuns(config);
  if (planned > kLargeExperimentRuns && !config.allow_large && !o.yes)
    throw InputError(o.config, "allow_large",
                     "the experiment asks for " + std::to_string(planned) + " runs (more than " +
                         std::to_string(kLargeExperimentRuns) +
                         "; hours to days of work): confirm with --yes or `allow_large: true`");
  RunnerOptions options;
  options.threads = o.threads;
  options.progress = stderr;
  options.timing = o.timing;
  options.retry_failed = o.retry_failed;
  options.reuse_across_builds = o.reuse_across_builds;
  options.command_line = o.command_line;
  const RunnerSummary s = runExperiment(config, options);
  std::printf("experiment %s: %zu walls, %zu runs (%zu executed, %zu already stored", config.name.c_str(), s.walls,
              s.total, s.executed, s.skipped);
  if (s.reused) std::printf(", %zu reused from other builds", s.reused);
  std::printf(") on %u worker processes in %.1f s", s.threads, s.seconds);
  if (s.executed) std::printf(", %.1f runs/s", static_cast<double>(s.executed) / s.seconds);
  if (!s.rerun_reasons.empty()) std::printf("\nrun again: %s", s.rerun_reasons.c_str());
  if (!s.by_status.empty()) {
    std::printf("\noutcomes of the executed runs:");
    for (const auto& [status, n] : s.by_status) std::printf(" %s %zu;", status.c_str(), n);
  }
  std::printf("\nresults: %s\n", s.database.c_str());
  std::fflush(stdout);
  if (!o.no_report) {
    ReportOptions report;
    report.database = s.database;
    report.out = (fs::path(config.output) / "report").string();
    std::printf("report:  %s (tables: report.md, report.csv, report.tex)\n", writeReport(report).c_str());
  }
  return 0;
}

int runsCommand(const RunsOptions& o) {
  if (o.format != "csv" && o.format != "json") throw InputError("--format", "format", "must be csv or json, got '" + o.format + "'");
  ResultsDb db(o.database, ResultsDb::Mode::ReadOnly);
  const ResultSet rs = db.load(o.experiment);
  std::cout << (o.list ? listRuns(rs) : renderRuns(rs, o.format == "json"));
  return 0;
}

}  // namespace coverbench::cli
