#include "coverbench/tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>

#include "coverbench/escape.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {
namespace {

/// A table independent of the output format: a title, a note, a header and rows of cells.
struct Table {
  std::string title;
  std::string note;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

std::string fmt(double v) {
  if (std::isnan(v)) return "-";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string shortHash(const std::string& h) { return h.substr(0, 12); }

/// Runs whose metrics are summarised: a valid path, everything reachable covered or (partial)
/// some reachable parts knowingly left out; the outcome table counts both apart.
bool usable(const ResultRow& r) { return (r.status == "ok" || r.status == "partial") && r.valid; }

bool tie(double a, double b) { return std::fabs(a - b) <= 1e-9 + 1e-6 * std::fmax(std::fabs(a), std::fabs(b)); }

std::vector<std::string> datasetsOf(const ResultSet& rs) {
  std::set<std::string> names;
  for (const ResultRow& r : rs.runs) names.insert(r.dataset);
  std::vector<std::string> out(names.begin(), names.end());
  if (out.size() > 1) out.push_back("all");
  return out;
}

Table failureTable(const ResultSet& rs) {
  // Statuses in a fixed order (the ones with a path first), then any others alphabetically.
  const std::vector<std::string> known = {"ok", "partial", "invalid_output", "metrics_error", "no_reachable_area",
                                          "invalid_input", "timeout", "memory_limit", "crash", "error"};
  std::set<std::string> present;
  for (const ResultRow& r : rs.runs) present.insert(r.status);
  std::vector<std::string> statuses;
  for (const std::string& s : known)
    if (s == "ok" || present.count(s)) statuses.push_back(s);
  for (const std::string& s : present)
    if (std::find(known.begin(), known.end(), s) == known.end()) statuses.push_back(s);
  Table t;
  t.title = "Run outcomes per planner";
  t.note = "ok: everything reachable covered, valid path; partial: a valid path that knowingly leaves reachable parts "
           "out (other free components; the median uncovered reachable area is given); invalid_output: the planner "
           "returned a path that fails the exact validity check; metrics_error: the path could not be scored; the "
           "other columns count runs without a path, by status. Metric tables summarise ok and partial runs.";
  t.header = {"planner", "runs"};
  for (const std::string& s : statuses) t.header.push_back(s);
  t.header.push_back("partial: uncovered reachable (m2)");
  for (const std::string& p : rs.planners) {
    std::size_t runs = 0;
    std::map<std::string, std::size_t> by_status;
    std::vector<double> uncovered;
    for (const ResultRow& r : rs.runs) {
      if (r.planner != p) continue;
      ++runs;
      ++by_status[r.status];
      if (r.status == "partial" && std::isfinite(r.uncovered_reachable_m2)) uncovered.push_back(r.uncovered_reachable_m2);
    }
    std::vector<std::string> row = {p, std::to_string(runs)};
    for (const std::string& s : statuses) row.push_back(std::to_string(by_status[s]));
    std::sort(uncovered.begin(), uncovered.end());
    row.push_back(uncovered.empty() ? "-" : fmt(quantile(uncovered, 0.5)));
    t.rows.push_back(row);
  }
  return t;
}

struct Summary {
  std::size_t n = 0;
  double median = NAN, q1 = NAN, q3 = NAN;
};

Summary summarise(std::vector<double> v) {
  Summary s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.median = quantile(v, 0.5);
  s.q1 = quantile(v, 0.25);
  s.q3 = quantile(v, 0.75);
  return s;
}

/// Figures a rerun measures anew (time, memory): shown apart from the deterministic metrics,
/// and never counted as wins or losses (one noisy sample per run says nothing about a winner).
bool measured(const std::string& m) { return m == "plan_time_ms" || m == "peak_memory_bytes"; }

/// Every metric shown, deterministic ones first, then the measured ones.
std::vector<std::string> shownMetrics(const ResultSet& rs) {
  std::vector<std::string> out;
  for (const std::string& m : rs.metric_order)
    if (m != "valid" && !measured(m)) out.push_back(m);
  for (const std::string& m : rs.metric_order)
    if (measured(m)) out.push_back(m);
  return out;
}

/// summaries[dataset][planner][metric]
std::map<std::string, std::map<std::string, std::map<std::string, Summary>>> summaries(const ResultSet& rs) {
  // Values of every metric per (dataset, planner), over valid runs, gathered in one pass.
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::vector<double>>> values;
  for (const ResultRow& r : rs.runs) {
    if (!usable(r)) continue;
    for (const auto& [name, v] : r.metrics) {
      if (!std::isfinite(v)) continue;
      values[{r.dataset, r.planner}][name].push_back(v);
      values[{"all", r.planner}][name].push_back(v);
    }
  }
  std::map<std::string, std::map<std::string, std::map<std::string, Summary>>> out;
  for (const std::string& d : datasetsOf(rs))
    for (const std::string& p : rs.planners)
      for (const std::string& m : shownMetrics(rs)) {
        const auto group = values.find({d, p});
        std::vector<double> v;
        if (group != values.end() && group->second.count(m)) v = group->second.at(m);
        out[d][p][m] = summarise(std::move(v));
      }
  return out;
}

/// Whether a row is the baseline's (at its own tool: pairings include the tool).
bool isBaseline(const ResultSet& rs, const ResultRow& r) { return (r.config.empty() ? r.planner : r.config) == rs.baseline; }

/// Whether a column is one of the baseline's.
bool baselineColumn(const ResultSet& rs, const std::string& column) {
  for (const ResultRow& r : rs.runs)
    if (r.planner == column) return isBaseline(rs, r);
  return column == rs.baseline;
}

struct Paired {
  std::size_t pairs = 0;
  std::map<std::string, std::array<std::size_t, 3>> wtl;  // metric -> wins, ties, losses
};

std::vector<std::string> comparedMetrics(const ResultSet& rs) {
  std::vector<std::string> out;
  for (const std::string& m : rs.metric_order)
    if (metricDirection(m) != 0 && !measured(m)) out.push_back(m);
  return out;
}

Paired paired(const ResultSet& rs, const std::string& planner, const std::string& dataset) {
  std::map<std::string, const ResultRow*> base;
  for (const ResultRow& r : rs.runs)
    if (isBaseline(rs, r) && (dataset == "all" || r.dataset == dataset) && usable(r)) base[r.pairing] = &r;
  Paired out;
  for (const std::string& m : comparedMetrics(rs)) out.wtl[m] = {0, 0, 0};
  for (const ResultRow& r : rs.runs) {
    if (r.planner != planner || (dataset != "all" && r.dataset != dataset) || !usable(r)) continue;
    const auto it = base.find(r.pairing);
    if (it == base.end()) continue;
    ++out.pairs;
    for (const std::string& m : comparedMetrics(rs)) {
      const auto a = r.metrics.find(m), b = it->second->metrics.find(m);
      if (a == r.metrics.end() || b == it->second->metrics.end()) continue;
      const int dir = metricDirection(m);
      if (tie(a->second, b->second)) ++out.wtl[m][1];
      else if ((a->second - b->second) * dir > 0) ++out.wtl[m][0];
      else ++out.wtl[m][2];
    }
  }
  return out;
}

/// One table row: the metric's name, then median (IQR) per planner.
std::vector<std::string> summaryRow(const std::string& metric,
                                    const std::map<std::string, std::map<std::string, Summary>>& per_planner,
                                    const std::vector<std::string>& planners) {
  std::vector<std::string> row = {metric};
  for (const std::string& p : planners) {
    const Summary& s = per_planner.at(p).at(metric);
    // An IQR below 1e-9 of the values is rounding noise, shown as 0.
    double iqr = s.q3 - s.q1;
    if (std::fabs(iqr) <= 1e-9 * std::fmax(std::fabs(s.q1), std::fabs(s.q3))) iqr = 0.0;
    row.push_back(s.n ? fmt(s.median) + " (" + fmt(iqr) + ")" : "-");
  }
  return row;
}

// --- rendering ---------------------------------------------------------------------------------

std::string markdown(const Table& t) {
  std::string out = "## " + escapeMarkdown(t.title) + "\n\n";
  if (!t.note.empty()) out += t.note + "\n\n";
  out += "|";
  for (const std::string& h : t.header) out += " " + escapeMarkdown(h) + " |";
  out += "\n|";
  for (std::size_t i = 0; i < t.header.size(); ++i) out += i == 0 ? "---|" : "---:|";
  out += "\n";
  for (const auto& row : t.rows) {
    out += "|";
    for (const std::string& c : row) out += " " + escapeMarkdown(c) + " |";
    out += "\n";
  }
  return out + "\n";
}

std::string latex(const Table& t) {
  std::string out = "% " + escapeLatex(t.title) + "\n\\begin{table}[htbp]\n\\centering\n\\small\n\\begin{tabular}{l";
  for (std::size_t i = 1; i < t.header.size(); ++i) out += "r";
  out += "}\n\\toprule\n";
  for (std::size_t i = 0; i < t.header.size(); ++i) out += (i ? " & " : "") + escapeLatex(t.header[i]);
  out += " \\\\\n\\midrule\n";
  for (const auto& row : t.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out += (i ? " & " : "") + escapeLatex(row[i]);
    out += " \\\\\n";
  }
  out += "\\bottomrule\n\\end{tabular}\n\\caption{" + escapeLatex(t.title) + "}\n\\end{table}\n\n";
  return out;
}

}  // namespace

TableFormat parseTableFormat(const std::string& text) {
  if (text == "md" || text == "markdown") return TableFormat::Markdown;
  if (text == "csv") return TableFormat::Csv;
  if (text == "latex" || text == "tex") return TableFormat::Latex;
  throw InputError("--format", "format", "must be md, csv or latex, got '" + text + "'");
}

int metricDirection(const std::string& m) {
  static const std::map<std::string, int> d = {
      {"coverage_reachable", +1}, {"coverage_wall", +1}, {"overlap", -1},      {"length_total", -1},
      {"length_transit", -1},     {"length_ratio", -1},  {"turns", -1},        {"turning_angle", -1},
      {"duration_s", -1},         {"plan_time_ms", -1},  {"peak_memory_bytes", -1}};
  const auto it = d.find(m);
  return it == d.end() ? 0 : it->second;
}

double quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return NAN;
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

std::string renderTables(const ResultSet& rs, TableFormat format) {
  const auto sums = summaries(rs);
  const std::vector<std::string> datasets = datasetsOf(rs);

  if (format == TableFormat::Csv) {
    // One long table: every number with its context, for scripts and spreadsheets.
    std::string out = "table,dataset,planner,metric,n,median,q1,q3,wins,ties,losses\n";
    const Table f = failureTable(rs);
    for (const auto& row : f.rows)
      for (std::size_t i = 1; i < f.header.size(); ++i)
        out += "outcomes,all," + escapeCsv(row[0]) + "," + escapeCsv(f.header[i]) + "," + row[i] + ",,,,,,\n";
    for (const std::string& d : datasets)
      for (const std::string& p : rs.planners)
        for (const std::string& m : shownMetrics(rs)) {
          const Summary& s = sums.at(d).at(p).at(m);
          char buf[160];
          std::snprintf(buf, sizeof buf, "%zu,%.10g,%.10g,%.10g,,,", s.n, s.median, s.q1, s.q3);
          out += std::string(measured(m) ? "measured," : "metrics,") + escapeCsv(d) + "," + escapeCsv(p) + "," + m + "," + buf + "\n";
        }
    for (const std::string& p : rs.planners) {
      if (baselineColumn(rs, p)) continue;
      for (const std::string& d : datasets) {
        const Paired pr = paired(rs, p, d);
        for (const auto& [m, w] : pr.wtl)
          out += escapeCsv("paired_vs_" + rs.baseline) + "," + escapeCsv(d) + "," + escapeCsv(p) + "," + m + "," +
                 std::to_string(pr.pairs) + ",,,," + std::to_string(w[0]) + "," + std::to_string(w[1]) + "," +
                 std::to_string(w[2]) + "\n";
      }
    }
    return out;
  }

  std::vector<Table> tables;
  tables.push_back(failureTable(rs));
  for (const std::string& d : datasets) {
    Table t;
    t.title = "Dataset " + d + ": median (IQR) over valid runs";
    t.note = "IQR = q3 - q1 (linear-interpolation quantiles); n = valid runs. Definitions: docs/metrics.md.";
    t.header = {"metric"};
    for (const std::string& p : rs.planners) t.header.push_back(p);
    std::vector<std::string> n_row = {"n"};
    for (const std::string& p : rs.planners) {
      const auto& per_metric = sums.at(d).at(p);
      n_row.push_back(per_metric.empty() ? "0" : std::to_string(per_metric.begin()->second.n));
    }
    t.rows.push_back(n_row);
    for (const std::string& m : shownMetrics(rs))
      if (!measured(m)) t.rows.push_back(summaryRow(m, sums.at(d), rs.planners));
    tables.push_back(t);
  }
  if (rs.planners.size() > 1) {
    Table t;
    t.title = "Paired comparison against " + rs.baseline + ": wins/ties/losses";
    t.note = "Over the walls (same tool and seed) where both runs are valid. A win is better than the baseline "
             "(higher coverage; lower everything else); a tie is within 1e-6 relative. Measured figures (time, memory) are "
             "not compared.";
    t.header = {"planner", "dataset", "pairs"};
    const std::vector<std::string> compared = comparedMetrics(rs);
    for (const std::string& m : compared) t.header.push_back(m);
    for (const std::string& p : rs.planners) {
      if (baselineColumn(rs, p)) continue;
      for (const std::string& d : datasets) {
        const Paired pr = paired(rs, p, d);
        std::vector<std::string> row = {p, d, std::to_string(pr.pairs)};
        for (const std::string& m : compared) {
          const auto& w = pr.wtl.at(m);
          row.push_back(std::to_string(w[0]) + "/" + std::to_string(w[1]) + "/" + std::to_string(w[2]));
        }
        t.rows.push_back(row);
      }
    }
    tables.push_back(t);
  }

  {
    Table t;
    t.title = "Measured on this machine: median (IQR) over valid runs";
    t.note = "Plan time and peak heap of the plan call, one sample per run: a rerun measures them anew, so they differ "
             "from run to run and from machine to machine. Everything above is reproduced byte for byte.";
    t.header = {"dataset", "measure"};
    for (const std::string& p : rs.planners) t.header.push_back(p);
    for (const std::string& d : datasets)
      for (const std::string& m : shownMetrics(rs))
        if (measured(m)) {
          std::vector<std::string> row = summaryRow(m, sums.at(d), rs.planners);
          row.insert(row.begin(), d);
          t.rows.push_back(row);
        }
    tables.push_back(t);
  }

  std::size_t runs = rs.runs.size();
  std::string out;
  if (format == TableFormat::Markdown) {
    out = "# Experiment " + escapeMarkdown(rs.experiment) + "\n\nConfig " + shortHash(rs.config_hash) + ", " + std::to_string(runs) +
          " runs, " + std::to_string(rs.planners.size()) + " planner configurations, baseline " + escapeMarkdown(rs.baseline) + ".\n\n";
    for (const Table& t : tables) out += markdown(t);
  } else {
    out = "% Experiment " + escapeLatex(rs.experiment) + ", config " + shortHash(rs.config_hash) + ", " + std::to_string(runs) +
          " runs. Needs \\usepackage{booktabs}.\n\n";
    for (const Table& t : tables) out += latex(t);
  }
  return out;
}

}  // namespace coverbench
