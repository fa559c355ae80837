// Sub-commands for datasets, experiments and tables.
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "coverbench/datasets.hpp"
#include "coverbench/files.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/ompl_export.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/shards.hpp"
#include "coverbench/slurm.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

/// The config's run count; more than kLargeExperimentRuns needs --yes or `allow_large: true`.
std::size_t requireConfirmedSize(const ExperimentConfig& config, bool yes) {
  const std::size_t planned = plannedRuns(config);
  if (planned > kLargeExperimentRuns && !config.allow_large && !yes)
    throw InputError(config.path, "allow_large",
                     "the experiment asks for " + std::to_string(planned) + " runs (more than " +
                         std::to_string(kLargeExperimentRuns) +
                         "; hours to days of work): confirm with --yes or `allow_large: true`");
  return planned;
}

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

int datasetImportCommand(DatasetImportOptions o) {
  o.options.transform = parseTransform(o.transform, "--transform", "(value)");
  o.options.split_multipolygons = !o.refuse_multipolygons;
  const ImportResult result = importWalls(o.sources, o.options);
  std::vector<Wall> walls;
  std::size_t dropped = 0;
  double dropped_area = 0.0;
  for (const ImportedWall& w : result.walls) {
    walls.push_back(w.wall);
    dropped += w.dropped_holes;
    dropped_area += w.dropped_hole_area;
  }
  const Dataset d = writeDataset(o.out, "import", 0, walls, importRecordJson(result, o.options));
  std::cout << "imported " << d.entries.size() << " walls from " << result.sources.size() << " files into " << o.out;
  if (dropped) std::cout << " (" << dropped << " holes under --min-hole-area dropped, " << shortNumber(dropped_area) << " m^2)";
  std::size_t components = 0;
  double component_area = 0.0;
  for (const ImportedWall& w : result.walls) components += w.dropped_components, component_area += w.dropped_component_area;
  if (components) std::cout << " (" << components << " free map components left out, " << shortNumber(component_area) << " m^2)";
  std::cout << "\n";
  for (const RoomsReport& rooms : result.rooms) std::cout << describeRooms(rooms);
  std::cout << describeDataset(d);
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
  requireConfirmedSize(config, o.yes);
  RunnerOptions options;
  options.threads = o.threads;
  options.progress = stderr;
  options.timing = o.timing;
  options.retry_failed = o.retry_failed;
  options.reuse_across_builds = o.reuse_across_builds;
  options.command_line = o.command_line;
  if (!o.shard.empty()) options.shard = parseShard(o.shard);
  const RunnerSummary s = runExperiment(config, options);
  // The name as the terminal shows it: as written when it is one printable line, else escaped.
  const std::string name = isValidUtf8(config.name) && isPrintableLine(config.name) ? config.name : shownBytes(config.name);
  if (options.shard)
    std::printf("experiment %s, shard %s: %zu of the config's %zu runs", name.c_str(), toString(*options.shard).c_str(),
                s.total, s.config_runs);
  else
    std::printf("experiment %s: %zu walls, %zu runs", name.c_str(), s.walls, s.total);
  std::printf(" (%zu executed, %zu already stored", s.executed, s.skipped);
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
  if (options.shard) {  // a shard's runs alone make no report: merge them first
    std::printf("merge every shard's database: coverbench merge %s %s/shard-*-of-%u.sqlite\n",
                resultsDatabasePath(config).c_str(), (fs::path(config.output) / "shards").string().c_str(),
                options.shard->count);
    return 0;
  }
  if (!o.no_report) {
    ReportOptions report;
    report.database = s.database;
    report.out = (fs::path(config.output) / "report").string();
    std::printf("report:  %s (tables: report.md, report.csv, report.tex)\n", writeReport(report).c_str());
  }
  return 0;
}

int mergeCommand(const MergeCommandOptions& o) {
  MergeOptions options;
  options.out = o.out;
  options.shards = o.shards;
  options.command_line = o.command_line;
  const auto start = std::chrono::steady_clock::now();
  const MergeSummary s = mergeShards(options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const std::string& note : s.notes) std::printf("note: %s\n", note.c_str());
  if (s.unchanged) {
    std::printf("%s already holds this merge of %u shards (%zu runs; experiment %lld): nothing changed\n", o.out.c_str(),
                s.shard_count, s.runs, s.experiment_id);
    return 0;
  }
  std::printf("merged %zu shard files (all %u shards, run on %s) into %s in %.2f s: %zu runs, %zu copied, %zu already "
              "there, %zu stored twice (identical, kept once); experiment %lld\n",
              s.shard_files, s.shard_count, s.hosts.c_str(), o.out.c_str(), seconds, s.runs,
              s.copied, s.already_stored, s.duplicates, s.experiment_id);
  return 0;
}

int slurmCommand(const SlurmCommandOptions& o) {
  const ExperimentConfig config = loadExperimentConfig(o.config);
  const std::size_t planned = requireConfirmedSize(config, o.yes);
  SlurmOptions options;
  options.shards = o.shards;
  options.cpus_per_task = o.cpus_per_task;
  options.throttle = o.throttle;
  options.partition = o.partition;
  options.time = o.time;
  options.mem = o.mem;
  options.account = o.account;
  options.report = !o.no_report;
  std::error_code ec;
  options.binary = fs::canonical("/proc/self/exe", ec).string();
  options.workdir = fs::current_path().string();
  const SlurmScripts scripts = slurmScripts(config, options);
  {  // both scripts and the log folder, or nothing
    OutputFiles out;
    out.folder((fs::path(scripts.folder) / "logs").string());
    out.add(scripts.run_script, scripts.run_text);
    out.add(scripts.merge_script, scripts.merge_text);
    out.commit();
  }
  std::printf("wrote %s (%u array tasks, %zu runs in all) and %s\n", scripts.run_script.c_str(), o.shards, planned,
              scripts.merge_script.c_str());
  if (!o.submit) {  // quoted for the shell: paste it as it is, whatever the folder's name
    std::printf("submit with:\n  job=$(sbatch --parsable %s)\n  sbatch --dependency=afterany:\"${job%%%%;*}\" %s\n",
                shellQuote(scripts.run_script).c_str(), shellQuote(scripts.merge_script).c_str());
    return 0;
  }
  auto sbatch = [](const std::string& args) {
    const std::string command = "sbatch --parsable " + args;
    std::FILE* p = ::popen(command.c_str(), "r");
    if (!p) throw InputError("sbatch", "submit", "cannot run sbatch");
    std::string out;
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    const int status = ::pclose(p);
    const int rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    const std::string id = out.substr(0, out.find(';'));  // "id" or "id;cluster"
    if (rc != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("sbatch", "submit",
                       "`" + command + "` failed (exit " + std::to_string(rc) + (rc == 127 ? ": sbatch not found" : "") +
                           "): " + out + "; the scripts are written, submit them by hand");
    return id;
  };
  const std::string array = sbatch(shellQuote(scripts.run_script));
  const std::string merge = sbatch("--dependency=afterany:" + array + " " + shellQuote(scripts.merge_script));
  std::printf("submitted: array job %s (%u tasks), merge job %s after it\n", array.c_str(), o.shards, merge.c_str());
  std::printf("array %s\nmerge %s\n", array.c_str(), merge.c_str());
  return 0;
}

int exportOmplCommand(const ExportOmplOptions& o) {
  ResultsDb db(o.database, ResultsDb::Mode::ReadOnly);
  const ResultSet rs = db.load(o.experiment);
  const ExperimentRecord record = db.record(o.experiment);
  const std::vector<OmplLog> logs = omplBenchmarkLogs(rs, record, omplLogSettings(record.config_text));
  OutputFiles out;  // all logs or none
  out.folder(o.out);
  std::size_t runs = 0;
  for (const OmplLog& log : logs) {
    out.add((fs::path(o.out) / log.file_name).string(), log.text);
    runs += log.runs;
  }
  out.commit();
  std::printf("wrote %zu OMPL benchmark logs (one per dataset, %zu runs) to %s\n"
              "load them into OMPL's benchmark database (Planner Arena reads it) with:\n"
              "  ompl_benchmark_statistics %s/*.log -d benchmark.db\n",
              logs.size(), runs, o.out.c_str(), o.out.c_str());
  return 0;
}

int runsCommand(const RunsOptions& o) {
  if (o.format != "csv" && o.format != "json") throw InputError("--format", "format", "must be csv or json, got '" + shownBytes(o.format) + "'");
  ResultsDb db(o.database, ResultsDb::Mode::ReadOnly);
  const ResultSet rs = db.load(o.experiment);
  std::cout << (o.list ? listRuns(rs) : renderRuns(rs, o.format == "json"));
  return 0;
}

}  // namespace coverbench::cli
