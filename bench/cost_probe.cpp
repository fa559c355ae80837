// The cost gate's probe (tests/cost/README.md): one case per process, its measured call wrapped
// in callgrind's collection toggle, so `valgrind --tool=callgrind --collect-atstart=no` counts the
// instructions of that call alone (not loading the wall, not planning the path a metrics case
// scores). Run it with LD_BIND_NOW=1 (as the gate does) so that lazy symbol binding is not
// counted. Outside valgrind the toggles do nothing.
//   build/bench/coverbench_cost_probe --list       (the cases)
//   build/bench/coverbench_cost_probe --identity   (compiler, build type, flags)
//   valgrind --tool=callgrind --collect-atstart=no build/bench/coverbench_cost_probe zigzag/seed_5x5_3obs
//
// COVERBENCH_COST_SELFTEST_SLOW=PLANNER (a test switch, for the gate's own test): that planner's
// cases plan twice inside the counted region, as a planner made twice as slow would.
#include <valgrind/callgrind.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "coverbench/build_identity.hpp"
#include "coverbench/car.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/wall_file.hpp"

namespace {

using namespace coverbench;

struct WallCase {
  const char* name;  ///< as in the case name
  const char* file;  ///< under the project's source folder
  double tool_width;
};
// The seed cases at s = 0.05 m (as bench/planners_bench.cpp), a facade at 0.1 m and the
// 200-opening benchmark wall at 0.1 m.
const WallCase kWalls[] = {{"seed_1x1_empty", "datasets/canonical/seed_1x1_empty.json", 0.05},
                           {"seed_5x5_1obs", "datasets/canonical/seed_5x5_1obs.json", 0.05},
                           {"seed_5x5_3obs", "datasets/canonical/seed_5x5_3obs.json", 0.05},
                           {"seed_10x8_3obs", "datasets/canonical/seed_10x8_3obs.json", 0.05},
                           {"seed_10x10_5obs", "datasets/canonical/seed_10x10_5obs.json", 0.05},
                           {"facade_20x9_24win", "datasets/canonical/facade_20x9_24win.json", 0.1},
                           {"bench_50x20_200rect", "bench/walls/bench_50x20_200rect.json", 0.1}};
// The metrics engine: all metrics of a path planned by the named planner.
const char* const kMetricsPaths[][2] = {{"zigzag", "seed_5x5_3obs"}, {"zigzag", "facade_20x9_24win"},
                                        {"spiral", "facade_20x9_24win"}, {"spanning-tree", "seed_10x10_5obs"}};
// Planning for a car (turn radius 0.3 m, the planner's own plan) on the facade: a row sweep for a
// forward-only car and a cell decomposition for a car that reverses (issue 34's item 5).
const char* const kCarCases[][2] = {{"zigzag", "dubins"}, {"boustrophedon", "reeds-shepp"}};

std::vector<std::string> caseNames() {
  std::vector<std::string> names;
  for (const PlannerInfo& p : registeredPlanners())
    for (const WallCase& w : kWalls) names.push_back(p.name + "/" + w.name);
  for (const auto& m : kMetricsPaths) names.push_back(std::string("metrics/") + m[0] + "/" + m[1]);
  for (const auto& c : kCarCases) names.push_back(std::string("car/") + c[0] + "/" + c[1] + "/facade_20x9_24win");
  return names;
}

const WallCase& findWall(const std::string& name) {
  for (const WallCase& w : kWalls)
    if (name == w.name) return w;
  throw std::runtime_error("no wall '" + name + "' in the cost probe's cases");
}

/// A case's inputs. The problem is made where it is used, so its pointer to the wall is never
/// left pointing at a moved-from copy.
struct Input {
  Wall wall;
  ToolParams tool;
  Params params;
  Problem problem() const {
    Problem p;
    p.wall = &wall;
    p.tool = tool;
    p.params = params;
    return p;
  }
};

Input load(const std::string& planner, const std::string& wall_name) {
  const WallCase& w = findWall(wall_name);
  Input in;
  in.wall = loadWallFile(std::string(COVERBENCH_SOURCE_DIR) + "/" + w.file);
  in.tool.tool_width = w.tool_width;
  in.tool.clearance = 0.02;
  in.params = resolveParams(findPlanner(planner), {});
  return in;
}

PlanResult plan(const std::string& planner, const Problem& problem) {
  PlanResult r = findPlanner(planner).make()->plan(problem, Budget());
  if (!r.hasPath()) throw std::runtime_error(planner + ": " + toString(r.status) + ": " + r.reason);
  return r;
}

int runCase(const std::string& name) {
  const auto slash = name.find('/');
  if (slash == std::string::npos) throw std::runtime_error("no case '" + name + "' (see --list)");
  const std::string first = name.substr(0, slash), rest = name.substr(slash + 1);
  if (first == "car") {
    // car/PLANNER/dubins|reeds-shepp/WALL
    const auto s2 = rest.find('/');
    const auto s3 = s2 == std::string::npos ? s2 : rest.find('/', s2 + 1);
    if (s3 == std::string::npos) throw std::runtime_error("no case '" + name + "' (see --list)");
    const std::string planner = rest.substr(0, s2), car = rest.substr(s2 + 1, s3 - s2 - 1);
    if (car != "dubins" && car != "reeds-shepp") throw std::runtime_error("no car '" + car + "' in case '" + name + "'");
    const Input in = load(planner, rest.substr(s3 + 1));
    Problem problem = in.problem();
    problem.vehicle.kind = VehicleModel::Kind::Car;
    problem.vehicle.turn_radius = 0.3;
    problem.vehicle.reverse = car == "reeds-shepp";
    // Reeds-Shepp curves come from OMPL's plug-in, which the first curve opens (20 M instructions of
    // loading, once per process, as in an experiment's worker): opened here, outside the count.
    if (problem.vehicle.reverse) (void)reedsSheppLength({{0.0, 0.0}, 0.0}, {{1.0, 0.0}, 0.0}, problem.vehicle.turn_radius);
    CALLGRIND_TOGGLE_COLLECT;
    const PlanResult r = runPlanner(findPlanner(planner), problem, Budget());
    CALLGRIND_TOGGLE_COLLECT;
    if (!r.hasPath()) throw std::runtime_error(planner + ": " + toString(r.status) + ": " + r.reason);
    std::printf("%s: %zu waypoints\n", name.c_str(), r.path.waypoints.size());
    return 0;
  }
  if (first == "metrics") {
    const auto slash2 = rest.find('/');
    const std::string planner = rest.substr(0, slash2), wall = slash2 == std::string::npos ? "" : rest.substr(slash2 + 1);
    const Input in = load(planner, wall);
    const Path path = plan(planner, in.problem()).path;
    CALLGRIND_TOGGLE_COLLECT;
    const PathMetrics m = computeMetrics(in.wall, in.tool, path);
    CALLGRIND_TOGGLE_COLLECT;
    std::printf("%s: %zu waypoints scored, coverage_reachable %.6f\n", name.c_str(), path.waypoints.size(),
                m.coverage.coverage_reachable);
    return 0;
  }
  const Input in = load(first, rest);
  const Problem problem = in.problem();
  const char* slow = std::getenv("COVERBENCH_COST_SELFTEST_SLOW");
  const int times = slow && first == slow ? 2 : 1;
  std::size_t waypoints = 0;
  CALLGRIND_TOGGLE_COLLECT;
  for (int i = 0; i < times; ++i) waypoints += plan(first, problem).path.waypoints.size();
  CALLGRIND_TOGGLE_COLLECT;
  std::printf("%s: %zu waypoints\n", name.c_str(), waypoints / times);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 2 && std::string(argv[1]) == "--list") {
      for (const std::string& n : caseNames()) std::printf("%s\n", n.c_str());
      return 0;
    }
    if (argc == 2 && std::string(argv[1]) == "--identity") {  // what the counts depend on besides the code
      const BuildIdentity& id = buildIdentity();
      const std::string flags = id.flags.substr(std::min(id.flags.find_first_not_of(' '), id.flags.size()));
      std::printf("%s %s, flags '%s'\n", id.compiler.c_str(), id.build_type.c_str(), flags.c_str());
      return 0;
    }
    if (argc != 2) {
      std::fprintf(stderr, "usage: coverbench_cost_probe --list | --identity | CASE\n");
      return 2;
    }
    return runCase(argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "coverbench_cost_probe: %s\n", e.what());
    return 1;
  }
}
