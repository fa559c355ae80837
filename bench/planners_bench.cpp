// Times every registered planner on the seeds' cases at s = 0.05 m (issue: foundation, item 4).
//   build/bench/coverbench_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"

namespace {

using namespace coverbench;

const char* const kCases[] = {"seed_1x1_empty", "seed_5x5_1obs", "seed_5x5_3obs", "seed_10x8_3obs",
                              "seed_10x10_5obs"};

void planCaseWith(benchmark::State& state, const std::string& planner_name, const std::string& case_name,
                  const std::vector<std::pair<std::string, std::string>>& settings, double tool_width, double clearance) {
  // Names with a slash are relative to bench/walls (walls for one benchmark only).
  const std::string path = case_name.find('/') == std::string::npos
                               ? std::string(COVERBENCH_WALLS_DIR) + "/" + case_name + ".json"
                               : std::string(COVERBENCH_BENCH_WALLS_DIR) + "/" + case_name.substr(case_name.find('/') + 1) + ".json";
  const Wall wall = loadWallFile(path);
  const PlannerInfo& info = findPlanner(planner_name);
  Problem problem;
  problem.wall = &wall;
  problem.tool.tool_width = tool_width;
  problem.tool.clearance = clearance;
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

/// At s = 0.05 m, c = 0.02 m.
void planCase(benchmark::State& state, const std::string& planner_name, const std::string& case_name,
              const std::vector<std::pair<std::string, std::string>>& settings) {
  planCaseWith(state, planner_name, case_name, settings, 0.05, 0.02);
}

/// A sweep planner planning for a car itself (car_plan: headland; docs/vehicles.md) on the 20 m x
/// 9 m facade with 24 windows at s = 0.1 m, c = 0.02 m, turn radius 0.3 m (issue: car-aware
/// planners, target < 50 ms), or its smoothed baseline. A forward-only car's plan may be partial
/// (rows left out): it still counts.
void planCar(benchmark::State& state, const std::string& planner, bool reverse, const std::string& car_plan) {
  const Wall wall = loadWallFile(std::string(COVERBENCH_WALLS_DIR) + "/facade_20x9_24win.json");
  const PlannerInfo& info = findPlanner(planner);
  Problem problem;
  problem.wall = &wall;
  problem.tool.tool_width = 0.1;
  problem.tool.clearance = 0.02;
  problem.vehicle.kind = VehicleModel::Kind::Car;
  problem.vehicle.turn_radius = 0.3;
  problem.vehicle.reverse = reverse;
  problem.params = resolveParams(info, {{"car_plan", car_plan}});
  for (auto _ : state) {
    PlanResult result = runPlanner(info, problem, Budget());
    if (!result.hasPath()) {
      state.SkipWithError(result.reason.c_str());
      break;
    }
    benchmark::DoNotOptimize(result);
  }
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
  // The decomposition planners (issue: decomposition planners): boustrophedon with TSP ordering
  // under 5 ms on the 10 m x 10 m wall (registered above) and under 50 ms on a 50 m x 20 m wall
  // with 200 rectangular openings; greedy ordering and trapezoidal for comparison (DFS order is
  // left out: its long transits take seconds there).
  for (const auto& [planner, order] : std::vector<std::pair<std::string, std::string>>{
           {"boustrophedon", "tsp"}, {"boustrophedon", "greedy"}, {"trapezoidal", "tsp"}})
    benchmark::RegisterBenchmark((planner + "[" + order + "]/bench_50x20_200rect").c_str(), planCase, planner,
                                 std::string("bench/bench_50x20_200rect"),
                                 std::vector<std::pair<std::string, std::string>>{{"order", order}})
        ->Unit(benchmark::kMillisecond);
  // Field scale (docs/datasets.md): a 100 m polygon with 15 buildings at s = 3 m, no clearance,
  // every planner, and boustrophedon with the direction search (targets: 20 ms and 50 ms).
  using Settings = std::vector<std::pair<std::string, std::string>>;
  for (const PlannerInfo& p : registeredPlanners())
    benchmark::RegisterBenchmark((p.name + "/field_100m_15_buildings").c_str(), planCaseWith, p.name,
                                 std::string("bench/field_100m_15_buildings"), Settings{}, 3.0, 0.0)
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("boustrophedon[direction_search]/field_100m_15_buildings", planCaseWith,
                               std::string("boustrophedon"), std::string("bench/field_100m_15_buildings"),
                               Settings{{"direction_search", "true"}}, 3.0, 0.0)
      ->Unit(benchmark::kMillisecond);
  // Planning for a car: each car-aware planner's own plan (zigzag's smoothed baseline too).
  for (const std::string planner : {"zigzag", "boustrophedon", "trapezoidal", "spiral"})
    for (const bool reverse : {false, true})
      for (const char* car_plan : {"headland", "smoothed"}) {
        if (planner != "zigzag" && std::string(car_plan) == "smoothed") continue;
        benchmark::RegisterBenchmark((planner + "[car " + (reverse ? "reeds-shepp" : "dubins") + ", " + car_plan +
                                      "]/facade_20x9_24win")
                                         .c_str(),
                                     planCar, planner, reverse, std::string(car_plan))
            ->Unit(benchmark::kMillisecond);
      }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
