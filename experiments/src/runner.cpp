#include "coverbench/runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <thread>

#include "coverbench/limits.hpp"
#include "coverbench/results_db.hpp"

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
  const std::vector<RunSpec> runs = expandRuns(config, walls);
  summary.walls = walls.size();
  summary.total = runs.size();

  std::error_code ec;
  fs::create_directories(config.output, ec);
  if (ec) throw InputError(config.output, "output", "cannot be created: " + ec.message());
  summary.database = resultsDatabasePath(config);
  ResultsDb db(summary.database);

  unsigned threads = options.threads ? options.threads : config.threads;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  summary.threads = threads;
  summary.experiment_id = db.beginExperiment(config, currentProvenance(threads), walls, runs);

  const std::set<std::string> finished = db.finishedRuns();
  std::vector<const RunSpec*> todo;
  for (const RunSpec& r : runs)
    if (!finished.count(r.key)) todo.push_back(&r);
  summary.skipped = runs.size() - todo.size();
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

  // Workers take runs in order; the calling thread is the single database writer.
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<std::pair<const RunSpec*, RunRecord>> results;
  std::exception_ptr failure;
  auto work = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= todo.size()) return;
      RunRecord rec;
      try {
        rec = executeRun(*todo[i], options.probe);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        next = todo.size();
        ready.notify_one();
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      results.emplace_back(todo[i], std::move(rec));
      ready.notify_one();
    }
  };
  std::vector<std::thread> pool;
  const unsigned workers = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(todo.size(), 1)));
  for (unsigned t = 0; t < workers && !todo.empty(); ++t) pool.emplace_back(work);

  double total_cost = 0.0, done_cost = 0.0;
  for (const RunSpec* r : todo) total_cost += cost(r);
  Progress progress(options.progress, todo.size(), total_cost);
  if (options.progress && summary.skipped)
    std::fprintf(options.progress, "%zu of %zu runs already in %s: skipped\n", summary.skipped, runs.size(),
                 summary.database.c_str());
  std::size_t stored = 0;
  try {
    while (stored < todo.size()) {
      std::unique_lock<std::mutex> lock(mutex);
      ready.wait(lock, [&] { return !results.empty() || failure; });
      if (failure && results.empty()) break;
      auto [spec, rec] = std::move(results.front());
      results.pop_front();
      lock.unlock();
      db.storeRun(*spec, rec);
      ++stored;
      done_cost += cost(spec);
      progress.update(stored, done_cost);
    }
  } catch (...) {
    next = todo.size();
    for (std::thread& t : pool) t.join();
    throw;
  }
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  summary.executed = stored;
  db.finishExperiment(summary.experiment_id, summary.executed, summary.skipped);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace coverbench
