#include "coverbench/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <thread>

#include "coverbench/limits.hpp"
#include "coverbench/results_db.hpp"
#include "isolation.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// done/total, rate and ETA: a redrawn bar on a terminal, a line every 5 % otherwise.
class Progress {
 public:
  /// `total_cost`: the sum of the runs' estimated costs; the ETA scales elapsed time by the cost
  /// still to go, since runs start largest first and early runs are the slow ones.
  Progress(std::FILE* out, std::size_t total, double total_cost)
      : out_(out), total_(total), total_cost_(total_cost), tty_(out && isatty(fileno(out))), start_(Clock::now()) {}
  void update(std::size_t done, double done_cost) {
    if (!out_ || total_ == 0) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = done_cost > 0.0 ? elapsed * (total_cost_ - done_cost) / done_cost : 0.0;
    if (tty_) {
      const int width = 30;
      const int filled = static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total_));
      std::fprintf(out_, "\r[%.*s%*s] %zu/%zu runs  %.1f runs/s  ETA %s ", filled, "==============================",
                   width - filled, "", done, total_, rate, clock(eta).c_str());
      if (done == total_) std::fprintf(out_, "\n");
      std::fflush(out_);
    } else {
      const std::size_t step = std::max<std::size_t>(1, total_ / 20);
      if (done % step == 0 || done == total_) {
        std::fprintf(out_, "%zu/%zu runs, %.1f runs/s, ETA %s\n", done, total_, rate, clock(eta).c_str());
        std::fflush(out_);
      }
    }
  }

 private:
  static std::string clock(double seconds) {
    const auto s = static_cast<long long>(seconds + 0.5);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
    return buf;
  }
  std::FILE* out_;
  std::size_t total_;
  double total_cost_;
  bool tty_;
  Clock::time_point start_;
};

}  // namespace

std::string resultsDatabasePath(const ExperimentConfig& config) { return (fs::path(config.output) / "results.sqlite").string(); }

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& options) {
  const auto start = Clock::now();
  RunnerSummary summary;
  if (options.progress && plannedRuns(config) >= 10000)
    std::fprintf(options.progress, "loading the walls of %zu datasets and expanding %zu runs ...\n",
                 config.datasets.size(), plannedRuns(config));
  const std::vector<WallEntry> walls = loadWalls(config);
  for (const WallEntry& w : walls)  // every (wall, tool) pair checked before any run
    for (const ToolParams& tool : config.tools) validateToolForWall(tool, w.wall, config.path);
  // With a shard, only its runs are expanded (the rest are other shards' work).
  std::function<bool(const RunSpec&)> mine;
  if (options.shard)
    mine = [shard = *options.shard](const RunSpec& r) { return shardOf(r, shard.count) == shard.index; };
  const std::vector<RunSpec> runs = expandRuns(config, walls, mine, &summary.config_runs);  // walls are distinct
  summary.walls = walls.size();
  std::optional<ShardRecord> shard;
  if (options.shard) {
    shard = ShardRecord{*options.shard, summary.config_runs, {}};
    for (const RunSpec& r : runs) shard->wall_hashes.insert(r.wall->hash);
  }
  summary.total = runs.size();

  std::error_code ec;
  fs::create_directories(config.output, ec);
  if (ec) throw InputError(config.output, "output", "cannot be created: " + ec.message());
  summary.database = options.shard ? shardDatabasePath(config, *options.shard) : resultsDatabasePath(config);
  fs::create_directories(fs::path(summary.database).parent_path(), ec);
  if (ec) throw InputError(summary.database, "output", "its folder cannot be created: " + ec.message());
  ResultsDb db(summary.database);

  // Workers: the option, else the config, else every core; never more than the cores (timings
  // would measure the contention); one in timing mode.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  unsigned threads = options.threads ? options.threads : config.threads;
  if (threads == 0 || threads > cores) threads = cores;
  if (options.timing) threads = 1;
  summary.threads = threads;

  // What to run: keys not stored yet; with retry_failed also the stored failures of the
  // environment; a stored run of the same base key but another planner version or code is run
  // again (and counted with why), unless reuse_across_builds.
  std::map<std::string, ResultsDb::StoredKey> stored_by_key;
  std::map<std::string, std::vector<ResultsDb::StoredKey>> stored_by_base;
  for (ResultsDb::StoredKey& k : db.storedKeys()) {
    stored_by_base[k.base_key].push_back(k);
    stored_by_key[k.key] = std::move(k);
  }
  std::vector<std::string> experiment_keys;
  std::vector<const RunSpec*> todo;
  std::map<std::string, std::size_t> reasons;
  for (const RunSpec& r : runs) {
    const auto same = stored_by_key.find(r.key);
    if (same != stored_by_key.end()) {
      experiment_keys.push_back(r.key);
      if (options.retry_failed && isRetryable(same->second.status)) {
        todo.push_back(&r);
        ++reasons[std::string("retrying ") + toString(same->second.status)];
      }
      continue;
    }
    const auto older = stored_by_base.find(r.base_key);
    if (older != stored_by_base.end() && options.reuse_across_builds) {
      experiment_keys.push_back(older->second.front().key);  // the stored run, from another build
      ++summary.reused;
      continue;
    }
    experiment_keys.push_back(r.key);
    todo.push_back(&r);
    if (older != stored_by_base.end()) {
      const bool version = std::none_of(older->second.begin(), older->second.end(), [&](const ResultsDb::StoredKey& k) {
        return k.planner_version == r.planner_version;
      });
      ++reasons[r.planner->planner + (version ? ": planner version changed" : ": planner code or build changed")];
    }
  }
  summary.skipped = runs.size() - todo.size() - summary.reused;
  for (const auto& [why, n] : reasons) summary.rerun_reasons += (summary.rerun_reasons.empty() ? "" : "; ") + std::to_string(n) + " " + why;
  summary.experiment_id = db.beginExperiment(config, currentProvenance(threads, options.command_line), walls, experiment_keys,
                                             shard ? &*shard : nullptr);
  if (options.progress && !summary.rerun_reasons.empty())
    std::fprintf(options.progress, "run again: %s\n", summary.rerun_reasons.c_str());
  if (options.progress && summary.reused)
    std::fprintf(options.progress, "%zu runs reused from other builds (--reuse-across-builds)\n", summary.reused);

  // Largest walls first, so the slowest runs do not end up alone at the end (results do not depend
  // on the order; the database is read back sorted).
  // Estimated cost: cells to cover times a power of the obstacle count, fitted loosely to the
  // default experiment (a 50 m wall with 300 openings takes about 2000 times a small room).
  std::vector<double> costs(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Box b = boundingBox(runs[i].wall->wall.boundary);
    costs[i] = b.width() * b.height() * std::pow(1.0 + static_cast<double>(runs[i].wall->wall.obstacles.size()), 0.75) /
               (runs[i].tool.tool_width * runs[i].tool.tool_width);
  }
  auto cost = [&](const RunSpec* r) { return costs[static_cast<std::size_t>(r - runs.data())]; };
  std::stable_sort(todo.begin(), todo.end(), [&](const RunSpec* a, const RunSpec* b) { return cost(a) > cost(b); });

  // Each run in its own child process (isolation.cpp), at most `threads` at once; this process is
  // the single database writer.
  double total_cost = 0.0, done_cost = 0.0;
  for (const RunSpec* r : todo) total_cost += cost(r);
  Progress progress(options.progress, todo.size(), total_cost);
  if (options.progress && summary.skipped)
    std::fprintf(options.progress, "%zu of %zu runs already in %s: skipped\n", summary.skipped, runs.size(),
                 summary.database.c_str());
  if (options.progress && !todo.empty())
    std::fprintf(options.progress, "%zu runs on %u worker processes (hard limits per run)\n", todo.size(), threads);
  std::size_t stored = 0;
  executeIsolated(todo, threads, [&](const RunSpec& spec, RunRecord rec) {
    ++summary.by_status[toString(rec.status)];
    db.storeRun(spec, rec);
    ++stored;
    done_cost += cost(&spec);
    progress.update(stored, done_cost);
  });
  summary.executed = stored;
  db.finishExperiment(summary.experiment_id, summary.executed, summary.skipped, summary.reused, summary.rerun_reasons);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

RunRecord executeInWorker(const RunSpec& spec) {
  RunRecord out;
  executeIsolated({&spec}, 1, [&](const RunSpec&, RunRecord r) { out = std::move(r); });
  return out;
}

}  // namespace coverbench
