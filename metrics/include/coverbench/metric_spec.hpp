#pragma once
/// The one home of metric metadata: every figure a run can carry (the engine's metrics and the
/// two measured figures), with its unit, which direction is better, its kind, a one-line
/// description, whether reports show it as a headline or in the appendix, and the band within
/// which two values count as equal. Plan files, the results database, the report and
/// docs/metrics.md are checked against (or generated from) this list.
#include <string>
#include <vector>

namespace coverbench {

enum class MetricKind {
  Quality,     ///< what a planner is judged on (coverage, overlap, length, turns, duration)
  Validity,    ///< the exact check's counts and gaps
  Area,        ///< areas of the wall (the same for every planner on one wall) and of the sweep
  Diagnostic,  ///< describes how a figure was computed, or repeats another (passes_1 = 1 - overlap)
  Measured,    ///< measured anew by each run (time, memory): never reproduced byte for byte
};

struct MetricSpec {
  std::string name;
  std::string unit;         ///< "1" for ratios and counts without unit
  int better = 0;           ///< +1 higher is better, -1 lower is better, 0 not compared
  MetricKind kind = MetricKind::Quality;
  bool headline = false;    ///< shown first in reports; the rest go to the appendix
  double tie_absolute = 0;  ///< two values within tie_absolute + tie_relative * max(|a|,|b|) are equal
  double tie_relative = 0;
  std::string description;  ///< one line
};

/// The exact judge's figures an experiment stores with `judge: exact` (docs/metrics.md), in order.
inline constexpr const char* kExactJudgeMetrics[] = {
    "exact_valid", "exact_violations", "exact_coverage_reachable_lower", "exact_coverage_reachable_upper",
    "exact_coverage_wall_lower", "exact_coverage_wall_upper"};

/// Every metric, in the order plan files and tables list them.
const std::vector<MetricSpec>& metricSpecs();
/// The spec of `name`, or nullptr.
const MetricSpec* findMetricSpec(const std::string& name);
std::string toString(MetricKind kind);
/// How tables show a value of `spec`, as the report's tables do
/// (reports/python/coverbench_report/tables.py, `value`): "percent" (a share of unit 1 named
/// coverage..., overlap... or passes...: times 100, two decimals, " %"), "count" (a whole
/// number: unit 1 or segments, equal within 0.5), "bytes" (unit B, shown in MiB) or "number"
/// (three significant digits and the unit).
std::string displayFormat(const MetricSpec& spec);
/// Whether two values of `spec` are equal within its tie band.
bool tied(const MetricSpec& spec, double a, double b);
/// The registry as a Markdown table (docs/metrics.md holds exactly this text).
std::string metricSpecsMarkdown();

}  // namespace coverbench
