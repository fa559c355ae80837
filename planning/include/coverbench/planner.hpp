#pragma once
/// The planner plug-in interface: a problem goes in, a result value comes out.
///
/// A planner implements exactly one method, `plan(problem, budget)`. Everything else a benchmark
/// needs to know about it (name, parameters with units and ranges, promise) is declared in
/// its `PlannerInfo`, registered in algorithms/registry.cpp. See docs/ADDING_A_PLANNER.md.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "coverbench/motion.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"
#include "coverbench/transit_planners.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// A parameter value: numbers, integers, booleans or a choice among names.
using ParamValue = std::variant<double, long long, bool, std::string>;

enum class ParamType { Number, Integer, Bool, Choice };

/// A declared planner parameter: experiments list, validate and sweep these without knowing the
/// planner.
struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Number;
  ParamValue default_value;
  double min = 0.0;  ///< inclusive, for Number and Integer
  double max = 0.0;  ///< inclusive, for Number and Integer
  std::vector<std::string> choices;  ///< for Choice
  std::string unit;                  ///< "m", "deg", "" ...
  std::string description;
};

/// Resolved parameter values (every declared parameter present), by name: what experiments
/// resolve, key, store and sweep (their text and JSON: param_codec.hpp). A planner does not read them: it declares a parameter struct
/// (param_table.hpp) and receives it filled.
class Params {
 public:
  void set(const std::string& name, ParamValue value) { values_[name] = std::move(value); }
  const std::map<std::string, ParamValue>& all() const { return values_; }

 private:
  std::map<std::string, ParamValue> values_;
};

/// One planning problem: a wall, the tool, the vehicle, and the planner's resolved parameters.
struct Problem {
  const Wall* wall = nullptr;
  ToolParams tool;
  /// Under a model that lifts the tool (gantry), planners cover every free component and cross
  /// obstacles with the tool lifted (PathBuilder does it for planners built on it).
  VehicleModel vehicle;
  /// How tool-off detours are found (PathBuilder uses it for planners built on it); sampling
  /// planners are seeded from `seed`.
  TransitSpec transit;
  Params params;
  /// For planners that randomise: all randomness must come from this seed (experiments set it
  /// from the config's seed), so a run is a pure function of its inputs.
  std::uint64_t seed = 0;
  /// The time model the path will be timed by (the experiment's `motion:`), for planners that
  /// plan for the clock (`objective: time`).
  MotionLimits motion;
  /// The run's memory limit in bytes (0: none), for planners that run in a process of their own
  /// (external planners); in-tree planners are held to it by their worker.
  std::size_t memory_limit_bytes = 0;
  /// The path will be smoothed for a car (runPlanner), whose smoothing reads straight segments:
  /// planners leave F's round boundary as chords (fitBoundaryArcs does nothing).
  bool straight_segments_only = false;
};

/// Limits for one plan call. Planners poll `expired()` in their loops.
class Budget {
 public:
  using Clock = std::chrono::steady_clock;
  Budget() = default;
  /// A deadline `limit` from now. A limit of about 30 years or more (or infinite) means no
  /// deadline: the clock's range ends near 292 years, and converting more would overflow.
  explicit Budget(std::chrono::duration<double> limit) {
    if (!(limit.count() < 1e9)) return;
    deadline_ = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::max(limit, std::chrono::duration<double>::zero()));
    limited_ = true;
  }
  bool expired() const { return limited_ && Clock::now() > deadline_; }
  /// Seconds left (infinite without a deadline; 0 when expired).
  double remainingSeconds() const {
    if (!limited_) return INFINITY;
    return std::max(0.0, std::chrono::duration<double>(deadline_ - Clock::now()).count());
  }

 private:
  Clock::time_point deadline_{};
  bool limited_ = false;
};

/// Ok: everything reachable covered. Partial: a path was returned but the planner knowingly left
/// reachable parts out (other free components, parts no transit reached): see the typed fields
/// of PlanResult. The rest return no path. Crash, MemoryLimit and InvalidOutput are what a planner
/// in a process of its own (an external planner) can end in: its process died, grew past the
/// memory limit, or answered what the protocol does not allow; in-tree planners never return them.
enum class PlanStatus { Ok, Partial, NoReachableArea, InvalidInput, Timeout, Error, Crash, MemoryLimit, InvalidOutput };
std::string toString(PlanStatus status);

/// What a planner returns. A planner that cannot handle an input says so here, with a reason;
/// it never returns a wrong path silently.
struct PlanResult {
  PlanStatus status = PlanStatus::Error;
  std::string reason;
  Path path;
  std::map<std::string, double> stats;  ///< planner statistics: deterministic (counts, lengths, angles)
  /// The planner's own sub-timings in ms (e.g. "decomposition"): measured, so a rerun differs;
  /// kept apart from `stats`, which a rerun reproduces exactly.
  std::map<std::string, double> timings_ms;
  double plan_time_ms = 0.0;  ///< wall-clock time of the plan call, measured by runPlanner
  /// What the planner covered, by its own account (recordOutcome fills these; the metrics engine
  /// measures the truth independently). 0 components: not reported.
  std::size_t free_components = 0;     ///< connected components of the free region F
  std::size_t covered_components = 0;  ///< of which the path covers
  std::size_t unreachable_parts = 0;   ///< parts (rings, rows, cells) of covered components no transit reached
  /// The path was planned for the problem's car itself, and is drivable by it (checked): runPlanner
  /// does not smooth it.
  bool planned_for_car = false;
  /// The planner planned for the problem's line tool itself (its rows run to the edge), not for
  /// its circumscribed disk: runs say nothing of a disk (toolShapeNote).
  bool planned_for_shape = false;
  /// A planner outside the tree (external/): the last bytes (external::kStderrTailBytes) its
  /// processes wrote to stderr during this plan call, as valid UTF-8 (other bytes replaced by
  /// U+FFFD); empty for in-tree planners.
  std::string stderr_tail;
  /// A planner outside the tree: the user + system CPU time (s) of its processes during this plan
  /// call, and their peak memory (bytes: their cgroup's peak usage, else their summed peak resident
  /// sets); NaN for in-tree planners, whose figures are their host process's.
  double process_cpu_s = NAN;
  double process_peak_bytes = NAN;
  /// A path that knowingly leaves reachable parts out.
  bool leftPartsOut() const { return covered_components < free_components || unreachable_parts > 0; }
  bool hasPath() const { return status == PlanStatus::Ok || status == PlanStatus::Partial; }

  static PlanResult failure(PlanStatus status, std::string reason) {
    PlanResult r;
    r.status = status;
    r.reason = std::move(reason);
    return r;
  }
};

/// The plug-in interface.
class Planner {
 public:
  virtual ~Planner() = default;
  virtual PlanResult plan(const Problem& problem, const Budget& budget) = 0;
};

/// A registered planner: its name, what it does, its parameters and how to make one. In-tree
/// planners write it with designated initializers (typedPlannerInfo, param_table.hpp); the members
/// they may leave out have default initializers (GCC 12 warns of a left-out member without one).
struct PlannerInfo {
  std::string name;
  /// The planner's version: change it when the planner's results change on purpose. It is part of
  /// every run key, so stored runs of an older version are planned again.
  std::string version;
  /// Its folders under algorithms/ (its own, and shared ones it uses): their code's content hash
  /// is part of every run key (docs/run_lifecycle.md).
  std::vector<std::string> code_folders;
  /// A planner outside the tree (external): the SHA-256 of its manifest and declared files, part
  /// of every run key beside the code folders; empty for in-tree planners.
  std::string code_sha256{};
  /// A planner outside the tree: its manifest's absolute path; empty for in-tree planners.
  std::string external_manifest{};
  std::string summary;
  std::string reference;  ///< the paper or document the algorithm comes from
  std::vector<ParamSpec> params{};
  /// The planner's promise, checked by the conformance suite: with default parameters, the
  /// coverage_reachable it reaches on every conformance wall whose free region is connected.
  double min_coverage_reachable = 0.0;
  /// The planner is given the problem's car (not a holonomic tool) and may plan for it itself
  /// (PlanResult::planned_for_car); else runPlanner plans it holonomic and smooths the path.
  bool plans_for_car = false;
  /// The planner plans for a line tool's shape (ToolParams::shape); else it plans for the line's
  /// circumscribed disk (a disk-valid path is line-valid: the line lies in the disk at every
  /// heading), and every run says so in its reason.
  bool plans_line_tool = false;
  /// Given a line or rectangle tool on a gantry (which lifts it between rows) or a holonomic robot
  /// (which turns it on the wall at each row end), not a car, the planner plans for the shape
  /// itself (PlanResult::planned_for_shape): runPlanner gives it the rectangle, not its
  /// circumscribed disk.
  bool plans_shapes = false;
  std::function<std::unique_ptr<Planner>()> make{};
};

}  // namespace coverbench
