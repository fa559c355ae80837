// Times every registered planner on the seeds' cases at s = 0.05 m (issue: foundation, item 4).
//   build/bench/coverbench_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include "coverbench/registry.hpp"
#include "coverbench/wall.hpp"

namespace {

using namespace coverbench;

const char* const kCases[] = {"seed_1x1_empty", "seed_5x5_1obs", "seed_5x5_3obs", "seed_10x8_3obs",
                              "seed_10x10_5obs"};

void planCase(benchmark::State& state, const std::string& planner_name, const std::string& case_name,
              const std::vector<std::pair<std::string, std::string>>& settings) {
  const Wall wall = loadWallFile(std::string(COVERBENCH_WALLS_DIR) + "/" + case_name + ".json");
  const PlannerInfo& info = findPlanner(planner_name);
  Problem problem;
  problem.wall = &wall;
  problem.tool.tool_width = 0.05;
  problem.tool.clearance = 0.02;
  problem.params = resolveParams(info, settings);
  auto planner = info.make();
  std::size_t waypoints = 0;
  for (auto _ : state) {
    PlanResult result = planner->plan(problem, Budget());
    if (result.status != PlanStatus::Ok) {
      state.SkipWithError(result.reason.c_str());
      break;
    }
    waypoints = result.path.waypoints.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["waypoints"] = static_cast<double>(waypoints);
}

const bool kRegistered = [] {
  for (const PlannerInfo& p : registeredPlanners())
    for (const char* c : kCases)
      benchmark::RegisterBenchmark((p.name + "/" + c).c_str(), planCase, p.name, std::string(c),
                                   std::vector<std::pair<std::string, std::string>>{})
          ->Unit(benchmark::kMillisecond);
  // The grid planner's variants on the 10 m x 10 m wall (issue: grid planners, target < 20 ms).
  for (const char* variant : {"return", "stop", "spiral-stc"})
    benchmark::RegisterBenchmark((std::string("spanning-tree[") + variant + "]/seed_10x10_5obs").c_str(), planCase,
                                 std::string("spanning-tree"), std::string("seed_10x10_5obs"),
                                 std::vector<std::pair<std::string, std::string>>{{"variant", variant}})
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("spanning-tree[mst]/seed_10x10_5obs", planCase, std::string("spanning-tree"),
                               std::string("seed_10x10_5obs"), std::vector<std::pair<std::string, std::string>>{{"tree", "mst"}})
      ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
