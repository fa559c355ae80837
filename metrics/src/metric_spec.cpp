#include "coverbench/metric_spec.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace coverbench {

const std::vector<MetricSpec>& metricSpecs() {
  using K = MetricKind;
  // Tie bands: coverage within 0.1 percentage point (far above the fast engine's error against the
  // exact judge, at most 1.6e-5 measured, docs/metrics.md; below what a painter could see); overlap within 0.5 percentage point (the scanline
  // method's stated error, docs/metrics.md); lengths and durations within 0.1 %; counts exactly;
  // plan time within 25 % and 0.05 ms (the same code timed three times on one wall here swung
  // by a third); memory within 5 % and 1 MiB.
  static const std::vector<MetricSpec> specs = {
      {"valid", "1", +1, K::Validity, false, 0, 0, "1 when no segment leaves F, else 0"},
      {"violations", "segments", -1, K::Validity, false, 0.5, 0, "segments whose centre line leaves F"},
      {"outside_boundary", "segments", -1, K::Validity, false, 0.5, 0, "segments whose tool disk leaves the wall"},
      {"too_close", "segments", -1, K::Validity, false, 0.5, 0, "segments whose tool disk comes closer than c to an obstacle"},
      {"min_clearance", "m", +1, K::Validity, false, 1e-6, 0, "smallest gap between the tool disk and any obstacle"},
      {"min_boundary_gap", "m", +1, K::Validity, false, 1e-6, 0, "smallest gap between the tool disk and the wall's edge"},
      {"coverage_reachable", "1", +1, K::Quality, true, 1e-3, 0, "share of the reachable area R the tool swept"},
      {"coverage_wall", "1", +1, K::Quality, true, 1e-3, 0, "share of the paintable wall P (wall minus obstacles) the tool swept"},
      {"reachable_area", "m2", 0, K::Area, false, 0, 1e-9, "|R|: the area a tool of this width can reach"},
      {"paintable_area", "m2", 0, K::Area, false, 0, 1e-9, "|P|: the wall minus its obstacles"},
      {"swept_area", "m2", 0, K::Area, false, 0, 1e-3, "|S|: the union of the tool-on sweeps"},
      {"overlap", "1", -1, K::Quality, true, 5e-3, 0, "share of the swept area passed over twice or more"},
      {"passes_1", "1", 0, K::Diagnostic, false, 5e-3, 0, "share of the swept area passed over once (1 - overlap)"},
      {"passes_2", "1", -1, K::Quality, false, 5e-3, 0, "share of the swept area passed over exactly twice"},
      {"passes_3", "1", -1, K::Quality, false, 5e-3, 0, "share of the swept area passed over exactly three times"},
      {"passes_4_or_more", "1", -1, K::Quality, false, 5e-3, 0, "share of the swept area passed over four times or more"},
      {"length_total", "m", -1, K::Quality, false, 0, 1e-3, "path length, tool on and off"},
      {"length_cover", "m", -1, K::Quality, false, 0, 1e-3, "path length with the tool on"},
      {"length_transit", "m", -1, K::Quality, false, 1e-3, 1e-3, "path length with the tool off"},
      {"length_ratio", "1", -1, K::Quality, true, 0, 1e-3, "length_total / (|R| / s): 1 is a perfect lawnmower on an open wall"},
      {"turns", "1", -1, K::Quality, false, 0.5, 0, "heading changes over 1 degree"},
      {"turns_30", "1", -1, K::Quality, true, 0.5, 0, "heading changes over 30 degrees (the robot stops)"},
      {"turning_angle", "rad", -1, K::Quality, false, 0, 1e-3, "sum of absolute heading changes"},
      {"duration_s", "s", -1, K::Quality, true, 0, 1e-3,
       "time to drive the path under the experiment's time model (default 0.3 m/s, 0.5 m/s2, stop at turns over 30 degrees)"},
      {"waypoints", "1", -1, K::Quality, false, 0.5, 0, "waypoints of the path"},
      // Only with a cost per turn in the time model (motion.turn_cost_s).
      {"turn_cost_s", "s", -1, K::Quality, false, 0, 1e-3, "turns over 1 degree times the time model's cost per turn"},
      // Only for a tool with a flux profile (deposition.hpp, docs/deposition.md): the coat over R.
      {"thickness_mean", "um", 0, K::Quality, false, 0, 1e-3, "mean thickness of the coat over the reachable area R (tool with a flux profile)"},
      {"thickness_cv", "1", -1, K::Quality, false, 1e-3, 0, "coefficient of variation of the coat's thickness over R: standard deviation / mean"},
      {"even_share", "1", +1, K::Quality, false, 5e-3, 0, "share of R whose thickness is within 10 % of the target (the mean without one)"},
      {"thin_share", "1", -1, K::Quality, false, 5e-3, 0, "share of R thinner than 0.9 times the target or the mean (unpainted R included)"},
      {"thick_share", "1", -1, K::Quality, false, 5e-3, 0, "share of R thicker than 1.1 times the target or the mean"},
      // Only with `judge: exact` in an experiment: the exact judge's verdict and certified bounds.
      {"exact_valid", "1", +1, K::Validity, false, 0, 0, "1 when the exact judge (CGAL, no tolerance) finds no violating segment"},
      {"exact_violations", "segments", -1, K::Validity, false, 0.5, 0, "segments the exact judge finds leaving F"},
      {"exact_coverage_reachable_lower", "1", 0, K::Diagnostic, false, 1e-3, 0, "certified lower bound of coverage_reachable (exact judge)"},
      {"exact_coverage_reachable_upper", "1", 0, K::Diagnostic, false, 1e-3, 0, "certified upper bound of coverage_reachable (exact judge)"},
      {"exact_coverage_wall_lower", "1", 0, K::Diagnostic, false, 1e-3, 0, "certified lower bound of coverage_wall (exact judge)"},
      {"exact_coverage_wall_upper", "1", 0, K::Diagnostic, false, 1e-3, 0, "certified upper bound of coverage_wall (exact judge)"},
      {"plan_time_ms", "ms", -1, K::Measured, true, 0.05, 0.25, "wall-clock time of the plan call (median of the repetitions)"},
      {"peak_memory_bytes", "B", -1, K::Measured, true, 1048576, 0.05, "resident memory the run added at its peak"},
  };
  return specs;
}

const MetricSpec* findMetricSpec(const std::string& name) {
  for (const MetricSpec& s : metricSpecs())
    if (s.name == name) return &s;
  return nullptr;
}

std::string toString(MetricKind kind) {
  switch (kind) {
    case MetricKind::Quality: return "quality";
    case MetricKind::Validity: return "validity";
    case MetricKind::Area: return "area";
    case MetricKind::Diagnostic: return "diagnostic";
    case MetricKind::Measured: return "measured";
  }
  throw std::logic_error("unknown MetricKind");
}

std::string displayFormat(const MetricSpec& spec) {
  const auto starts = [&](const char* prefix) { return spec.name.rfind(prefix, 0) == 0; };
  if (spec.unit == "1" && (starts("coverage") || starts("overlap") || starts("passes"))) return "percent";
  if (spec.unit == "B") return "bytes";
  if ((spec.unit == "1" || spec.unit == "segments") && spec.tie_absolute == 0.5) return "count";
  return "number";
}

bool tied(const MetricSpec& spec, double a, double b) {
  if (a == b) return true;  // also equal infinities
  return std::fabs(a - b) <= spec.tie_absolute + spec.tie_relative * std::fmax(std::fabs(a), std::fabs(b));
}

namespace {
std::string number(double v) {
  if (v == 0) return "0";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

std::string metricSpecsMarkdown() {
  std::string out = "| name | unit | better | kind | shown | equal within | description |\n|---|---|---|---|---|---|---|\n";
  for (const MetricSpec& s : metricSpecs()) {
    std::string band;
    if (s.tie_absolute > 0) band = number(s.tie_absolute) + (s.unit == "1" ? "" : " " + s.unit);
    if (s.tie_relative > 0) band += (band.empty() ? "" : " + ") + number(s.tie_relative * 100) + " %";
    if (band.empty()) band = "exactly";
    out += "| `" + s.name + "` | " + s.unit + " | " + (s.better > 0 ? "higher" : s.better < 0 ? "lower" : "-") + " | " +
           toString(s.kind) + " | " + (s.headline ? "headline" : "appendix") + " | " + band + " | " + s.description + " |\n";
  }
  return out;
}

}  // namespace coverbench
