// Sub-commands for datasets, experiments and tables.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/files.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/tables.hpp"
#include "memory_meter.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

const MemoryProbe& memoryProbe() {
  static const MemoryProbe probe{[](std::size_t limit) { limitMemory(limit); }, [] { return peakMemorySinceReset(); },
                                 [] { return memoryLimitHit(); }};
  return probe;
}

/// Writes the tables of the latest experiment in `db` as report.md, report.csv and report.tex.
std::string writeTables(const std::string& database, const std::string& folder) {
  ResultsDb db(database);
  const ResultSet rs = db.load();
  const fs::path out(folder);
  writeFileAtomically((out / "report.md").string(), renderTables(rs, TableFormat::Markdown));
  writeFileAtomically((out / "report.csv").string(), renderTables(rs, TableFormat::Csv));
  writeFileAtomically((out / "report.tex").string(), renderTables(rs, TableFormat::Latex));
  return (out / "report.md").string();
}

}  // namespace

int datasetGenerateCommand(const DatasetGenerateOptions& o) {
  const FamilyInfo& info = findFamily(o.family, "--family", "family");
  if (!info.fixed_suite && o.count == 0) throw InputError("--count", "count", "must be at least 1");
  if (o.count > 1000000) throw InputError("--count", "count", "must be at most 1000000");
  const std::vector<Wall> walls = generateWalls(o.family, o.seed, o.count);
  const Dataset d = writeDataset(o.out, o.family, info.fixed_suite ? 0 : o.seed, walls);
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
  RunnerOptions options;
  options.threads = o.threads;
  options.progress = stderr;
  options.probe = &memoryProbe();
  const RunnerSummary s = runExperiment(config, options);
  const std::string report = writeTables(s.database, config.output);
  std::printf("experiment %s: %zu walls, %zu runs (%zu executed, %zu already stored) on %u threads in %.1f s",
              config.name.c_str(), s.walls, s.total, s.executed, s.skipped, s.threads, s.seconds);
  if (s.executed) std::printf(", %.1f runs/s", static_cast<double>(s.executed) / s.seconds);
  std::printf("\nresults: %s\ntables:  %s (also report.csv, report.tex)\n", s.database.c_str(), report.c_str());
  return 0;
}

int reportCommand(const ReportOptions& o) {
  const TableFormat format = parseTableFormat(o.format);
  if (!fs::is_regular_file(o.database)) throw InputError(o.database, "(file)", "does not exist");
  ResultsDb db(o.database);
  ResultSet results = db.load(o.experiment);
  if (!o.baseline.empty()) {
    if (std::find(results.planners.begin(), results.planners.end(), o.baseline) == results.planners.end())
      throw InputError("--baseline", "baseline", "'" + o.baseline + "' is not a planner configuration of this experiment");
    results.baseline = o.baseline;
  }
  const std::string text = renderTables(results, format);
  if (o.out.empty()) std::cout << text;
  else writeFileAtomically(o.out, text);
  return 0;
}

}  // namespace coverbench::cli
