// Times every transit planner on the conformance walls' detour queries (issue 16, item 2), and
// reports each sampling planner's route length against the visibility route's as counters:
//   build/bench/coverbench_transit_bench --benchmark_min_time=0.5
// One iteration answers every query of every conformance wall (64 at s = 0.1 m, c = 0.02 m), each
// in a fresh workspace with seed 7 (the sampling planners' routes repeat exactly; the time does not).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>

#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"

namespace {

using namespace coverbench;

struct Query {
  const Wall* wall;
  DetourQuery q;
};

std::vector<Wall> conformanceWalls() {
  std::vector<std::string> files;
  for (const char* dir : {"datasets/canonical", "datasets/conformance"})
    for (const auto& e : std::filesystem::directory_iterator(std::string(COVERBENCH_SOURCE_DIR) + "/" + dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Wall> walls;
  for (const std::string& f : files) walls.push_back(loadWallFile(f));
  return walls;
}

const ToolParams kTool{0.1, 0.02};

void transits(benchmark::State& state, const std::string& planner) {
  static const std::vector<Wall> walls = conformanceWalls();
  std::vector<Query> queries;
  for (const Wall& w : walls) {
    Workspace ws(w, kTool);
    for (const DetourQuery& q : detourQueries(ws, 4)) queries.push_back({&w, q});
  }
  TransitSpec spec;
  spec.planner = planner;
  std::vector<double> ratios;
  std::size_t failures = 0;
  for (auto _ : state) {
    ratios.clear();
    failures = 0;
    for (const Query& q : queries) {
      state.PauseTiming();  // the workspace (F, the exact checks) is not the transit planner's work
      Workspace ws(*q.wall, kTool, {}, spec, 7);
      state.ResumeTiming();
      const auto route = ws.route(q.q.a, q.q.b);
      if (!route) {
        ++failures;
        continue;
      }
      ratios.push_back(polylineLength(*route) / q.q.shortest);
    }
  }
  std::sort(ratios.begin(), ratios.end());
  state.counters["queries"] = static_cast<double>(queries.size());
  state.counters["failures"] = static_cast<double>(failures);
  if (!ratios.empty()) {
    state.counters["ratio_min"] = ratios.front();
    state.counters["ratio_median"] = ratios[ratios.size() / 2];
    state.counters["ratio_max"] = ratios.back();
  }
  state.counters["per_query"] = benchmark::Counter(static_cast<double>(queries.size()),
                                                      benchmark::Counter::kIsIterationInvariantRate |
                                                          benchmark::Counter::kInvert);
}

const bool kRegistered = [] {
  for (const TransitPlannerInfo& t : transitPlanners())
    benchmark::RegisterBenchmark(("transits/" + t.name).c_str(), [name = t.name](benchmark::State& s) { transits(s, name); })
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
