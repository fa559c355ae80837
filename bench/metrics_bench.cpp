// Times the metrics engine on planned paths (issue: metrics, acceptance 3):
//   all metrics of a zigzag plan of the 5 m x 5 m wall with 3 obstacles at s = 0.05 m (< 50 ms),
//   and of the 20 m x 9 m facade with 24 windows at s = 0.1 m (< 200 ms); parts timed separately.
//   build/bench/coverbench_metrics_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"

namespace {

using namespace coverbench;

struct Case {
  const char* wall;
  const char* planner;
  double tool_width;
};
const Case kCases[] = {{"seed_5x5_3obs", "zigzag", 0.05},
                       {"facade_20x9_24win", "zigzag", 0.1},
                       {"seed_5x5_3obs", "spiral", 0.05},
                       {"facade_20x9_24win", "spiral", 0.1}};

struct Planned {
  Wall wall;
  ToolParams tool;
  Path path;
};

Planned plan(const Case& c) {
  Planned p;
  p.wall = loadWallFile(std::string(COVERBENCH_WALLS_DIR) + "/" + c.wall + ".json");
  p.tool.tool_width = c.tool_width;
  p.tool.clearance = 0.02;
  const PlannerInfo& info = findPlanner(c.planner);
  Problem problem;
  problem.wall = &p.wall;
  problem.tool = p.tool;
  problem.params = resolveParams(info, {});
  PlanResult r = runPlanner(info, problem, Budget());
  if (r.status != PlanStatus::Ok) throw std::runtime_error(c.wall + std::string(": ") + r.reason);
  p.path = std::move(r.path);
  return p;
}

template <class Part>
void measure(benchmark::State& state, const Case& c, Part part) {
  const Planned p = plan(c);
  for (auto _ : state) benchmark::DoNotOptimize(part(p));
  state.counters["waypoints"] = static_cast<double>(p.path.waypoints.size());
}

const bool kRegistered = [] {
  for (const Case& c : kCases) {
    const std::string name = std::string(c.planner) + "/" + c.wall + "/s=" + (c.tool_width == 0.05 ? "0.05" : "0.1");
    auto add = [&](const char* part, auto fn) {
      benchmark::RegisterBenchmark((name + "/" + part).c_str(), [c, fn](benchmark::State& s) { measure(s, c, fn); })
          ->Unit(benchmark::kMillisecond);
    };
    add("all", [](const Planned& p) { return computeMetrics(p.wall, p.tool, p.path).coverage.coverage_reachable; });
    add("validity", [](const Planned& p) { return checkValidity(p.wall, p.tool, p.path).violations; });
    add("coverage", [](const Planned& p) { return coverage(p.wall, p.tool, p.path).coverage_reachable; });
    add("passes", [](const Planned& p) { return passes(p.path, p.tool.radius()).overlap; });
    add("motion", [](const Planned& p) { return motion(p.path).duration_s; });
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
