// The external planner protocol's cost per run (docs/external_planners.md): the same fixed
// 1000-waypoint path from an in-tree planner and from an external one (bench/external/fixed_path.py,
// which makes its answer's JSON once), planned through runPlanner like any run, on the living-room
// wall. The external process is started before timing (paid once per worker); each iteration is
// one run: the request (the wall as JSON), the pipe both ways, and reading and checking the answer.
//   build/bench/coverbench_external_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "coverbench/external_planner.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"

namespace {

using namespace coverbench;

Path fixedPath() {
  Path p;
  for (int i = 0; i < 1000; ++i) p.moveTo({0.1 + 0.001 * i, 0.1 + 0.0005 * (i % 2)}, true);
  return p;
}

class FixedPlanner final : public Planner {
 public:
  PlanResult plan(const Problem&, const Budget&) override {
    PlanResult r;
    r.status = PlanStatus::Ok;
    r.path = fixedPath();
    return r;
  }
};

void run(benchmark::State& state, const PlannerInfo& info) {
  static const Wall wall = loadWallFile(std::string(COVERBENCH_SOURCE_DIR) + "/datasets/canonical/living_room_north.json");
  Problem problem;
  problem.wall = &wall;
  problem.tool = ToolParams{0.1, 0.02};
  if (runPlanner(info, problem, Budget(std::chrono::seconds(60))).path.waypoints.size() != 1000)  // warm: starts the process
    state.SkipWithError("the planner did not return its 1000 waypoints");
  for (auto _ : state) {
    const PlanResult r = runPlanner(info, problem, Budget(std::chrono::seconds(60)));
    benchmark::DoNotOptimize(r.path.waypoints.data());
    if (r.path.waypoints.size() != 1000) state.SkipWithError("the planner did not return its 1000 waypoints");
  }
}

void BM_InTreeFixedPath(benchmark::State& state) {
  PlannerInfo info;
  info.name = "fixed-in-tree";
  info.version = "1";
  info.make = [] { return std::make_unique<FixedPlanner>(); };
  run(state, info);
}

void BM_ExternalFixedPath(benchmark::State& state) {
  static const PlannerInfo& info =
      external::addFromManifest(std::string(COVERBENCH_SOURCE_DIR) + "/bench/external/fixed_path.json");
  run(state, info);
}

BENCHMARK(BM_InTreeFixedPath)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExternalFixedPath)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
