#pragma once
/// The results layer: what an experiment produced, as value types (one row per run, and the
/// experiment's record: its config, datasets, planner configurations and walls), and the exports
/// of every run (CSV, JSON). The runner and the results database write and read these; the
/// report reads them. Below both: it depends on the geometry layer alone.
#include <cstddef>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "coverbench/path.hpp"
#include "coverbench/run_record.hpp"

namespace coverbench {

/// One repair of a run's path after surprise obstacles (docs/replanning.md; table replans).
struct ReplanRow {
  double fraction = 0.0;
  std::string repair;  ///< replan or detour
  std::size_t obstacles = 0, requested = 0;
  std::string status;  ///< ok, partial, failed, invalid_output
  bool valid = false;
  double repair_ms = 0.0;  ///< measured; NaN when not
  std::map<std::string, double> figures;  ///< kReplanFigures (experiment.hpp) that were measured
};

/// One finished run as the tables see it: its fields (RunFields, run_record.hpp) in the context
/// of its experiment.
struct ResultRow : RunFields {
  /// The column it belongs to: the planner configuration's label, and with several tool
  /// configurations in the experiment, "label @ s=... m, c=... m" (never pooled across tools).
  std::string planner;
  std::string config;   ///< the planner configuration's label alone
  std::string params;   ///< its resolved parameters as stored (storedParamsJson reads them)
  std::string planner_version;  ///< the planner's declared version when the run was executed
  std::string wall_name;
  ToolParams tool;
  VehicleModel vehicle;
  TransitSpec transit;
  std::string dataset;
  std::string wall;     ///< wall content hash
  std::string pairing;  ///< what makes two runs comparable: wall, tool and repetition
  /// The metrics engine's values by name, and the measured fields the metric registry lists
  /// (plan_time_ms, and peak_memory_bytes when measured), for tables that show every metric.
  std::map<std::string, double> metrics;
  /// A sampling transit planner's statistics (transit_queries, transit_failures, transit_length_m,
  /// transit_shortest_m, transit_length_ratio) and its measured time (transit_ms); empty otherwise.
  std::map<std::string, double> transit_figures;
  /// With replanning: one per fraction and repair, in that order; empty otherwise.
  std::vector<ReplanRow> replans;
};

struct ResultSet {
  std::string experiment;   ///< name
  std::string config_hash;
  std::string baseline;     ///< planner configuration label; compared with at the same tool
  std::vector<std::string> planners;       ///< labels, in config order
  std::vector<std::string> metric_order;   ///< metric names, in the order tables list them
  std::vector<ResultRow> runs;
};

/// What was run, besides the runs: the config, provenance, datasets, planner configurations, walls.
struct ExperimentRecord {
  long long id = 0;
  std::string name, config_path, config_text, config_hash, baseline;
  std::string motion;  ///< the time model of every duration_s, described (MotionLimits::describe)
  /// Provenance and run counts as (label, value), in display order.
  std::vector<std::pair<std::string, std::string>> facts;
  struct Dataset {
    std::string label, source, sha256;
    long long walls = 0;
  };
  std::vector<Dataset> datasets;
  struct Config {
    std::string label, planner;
    std::string params;  ///< resolved, defaults included, as stored (storedParamsJson reads it)
  };
  std::vector<Config> planners;
  struct WallInfo {
    std::string hash, name;
    std::size_t obstacles = 0;
    double area = 0.0;  ///< m2 inside the boundary (obstacles not subtracted)
  };
  std::vector<WallInfo> walls;  ///< in hash order
};

/// One row per run: key, dataset, wall, planner configuration, its parameters (a JSON object; in
/// CSV its text) and version, tool, the exported run fields (status, reason, valid, the uncovered
/// reachable area, CPU time, the end of an external planner's stderr) and every metric as a column
/// (what pandas or R load). `json`: an array of
/// objects (NaN and infinities as null); otherwise CSV. Rows in key order.
std::string renderRuns(const ResultSet& results, bool json);

/// One line per run: key, planner configuration, wall, status (for picking a run to redraw).
std::string listRuns(const ResultSet& results);

}  // namespace coverbench
