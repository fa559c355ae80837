#pragma once
/// Comparison tables from experiment results: failures per planner, median and IQR of every
/// metric per planner and dataset, and paired win/tie/loss counts against a baseline.
/// Rendered as Markdown, CSV or LaTeX; the same results give the same bytes.
#include <map>
#include <string>
#include <vector>

#include "coverbench/planner.hpp"

namespace coverbench {

/// One finished run as the tables see it.
struct ResultRow {
  /// The column it belongs to: the planner configuration's label, and with several tool
  /// configurations in the experiment, "label @ s=... m, c=... m" (never pooled across tools).
  std::string planner;
  std::string config;   ///< the planner configuration's label alone
  std::string key;      ///< run key
  std::string wall_name;
  ToolParams tool;
  std::string dataset;
  std::string wall;     ///< wall content hash
  std::string pairing;  ///< what makes two runs comparable: wall, tool and repetition
  std::string status;
  bool valid = false;
  double uncovered_reachable_m2 = 0.0;  ///< NaN when not scored
  std::map<std::string, double> metrics;  ///< includes plan_time_ms and peak_memory_bytes if measured
};

struct ResultSet {
  std::string experiment;   ///< name
  std::string config_hash;
  std::string baseline;     ///< planner configuration label; compared with at the same tool
  std::vector<std::string> planners;       ///< labels, in config order
  std::vector<std::string> metric_order;   ///< metric names, in the order tables list them
  std::vector<ResultRow> runs;
};

enum class TableFormat { Markdown, Csv, Latex };
TableFormat parseTableFormat(const std::string& text);  ///< md, csv, latex; throws InputError

/// A metric's direction for paired comparisons: +1 higher is better, -1 lower is better, 0 not
/// compared.
int metricDirection(const std::string& metric);

/// Linear-interpolation quantile (type 7) of sorted values.
double quantile(const std::vector<double>& sorted, double q);

std::string renderTables(const ResultSet& results, TableFormat format);

/// One row per run: key, dataset, wall, planner configuration, tool, status, valid, the uncovered
/// reachable area and every metric as a column (what pandas or R load). `json`: an array of
/// objects (NaN and infinities as null); otherwise CSV. Rows in key order.
std::string renderRuns(const ResultSet& results, bool json);
/// One line per run: key, planner configuration, wall, status (for picking a run to redraw).
std::string listRuns(const ResultSet& results);

}  // namespace coverbench
