#include "coverbench/ompl_export.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

#include "coverbench/experiment.hpp"
#include "coverbench/files.hpp"

namespace coverbench {
namespace {

/// The run outcomes, in the order of the log's `run_status` enum.
constexpr RunStatus kStatuses[] = {RunStatus::Ok,          RunStatus::Partial,       RunStatus::NoReachableArea,
                                   RunStatus::InvalidInput, RunStatus::Timeout,     RunStatus::MemoryLimit,
                                   RunStatus::Crash,       RunStatus::Error,          RunStatus::InvalidOutput,
                                   RunStatus::MetricsError};

/// A value on a run line, where "; " separates values and a line ends the run.
std::string value(const std::string& text) {
  std::string out;
  for (char c : text) out += c == ';' ? ',' : c == '\n' || c == '\r' ? ' ' : c;
  return out;
}
/// A value on an experiment property line ("name TYPE = value"): OMPL's parser splits the line at
/// " = ", so one inside the value would cut it short there; it is written "=".
std::string property(const std::string& text) {
  std::string out = value(text);
  for (std::size_t at; (at = out.find(" = ")) != std::string::npos;) out.replace(at, 3, "=");
  return out;
}
/// A text block between "<<<|" and "|>>>": a line of it that starts with "|>>>" would end the
/// block early in OMPL's parser, so it gets a leading space.
std::string block(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    end = end == std::string::npos ? text.size() : end + 1;
    if (text.compare(start, 4, "|>>>") == 0) out += ' ';
    out.append(text, start, end - start);
    start = end;
  }
  if (!out.empty() && out.back() != '\n') out += '\n';
  return out;
}
std::string number(double v) {
  if (!std::isfinite(v)) return "nan";  // OMPL's parser reads "nan" as NULL
  char buf[40];
  // The shortest text that reads back exactly, without an exponent for numbers from 1 to 1e17
  // ("60", not "6e+01").
  const int magnitude = v != 0.0 ? static_cast<int>(std::floor(std::log10(std::fabs(v)))) : 0;
  for (int precision = magnitude >= 0 && magnitude < 17 ? magnitude + 1 : 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}
std::string fact(const ExperimentRecord& r, const std::string& label) {
  for (const auto& [k, v] : r.facts)
    if (k == label) return v;
  return "";
}

}  // namespace

OmplLogSettings omplLogSettings(const std::string& config_text) {
  OmplLogSettings s;
  const ExperimentConfig defaults;
  s.time_limit_s = defaults.time_limit_s;
  s.memory_limit_mb = defaults.memory_limit_mb;
  s.seed = defaults.seed;
  try {
    const YAML::Node doc = YAML::Load(config_text);
    if (const YAML::Node limits = doc["limits"]) {
      if (limits["time_s"]) s.time_limit_s = limits["time_s"].as<double>();
      if (limits["memory_mb"]) s.memory_limit_mb = limits["memory_mb"].as<double>();
    }
    if (doc["seed"]) s.seed = doc["seed"].as<std::uint64_t>();
  } catch (const YAML::Exception& e) {  // the stored config was checked when it ran: this is a damaged database
    throw InputError("(experiment config)", "limits", std::string("cannot be read back: ") + e.what());
  }
  return s;
}

std::vector<OmplLog> omplBenchmarkLogs(const ResultSet& results, const ExperimentRecord& record,
                                       const OmplLogSettings& settings) {
  // Run properties: OMPL's own first (time in s, memory in MiB, solved), then every metric.
  std::vector<std::string> metrics;
  for (const std::string& m : results.metric_order)
    if (m != "plan_time_ms" && m != "peak_memory_bytes") metrics.push_back(m);
  std::string properties = "time REAL\nmemory REAL\nsolved BOOLEAN\napproximate solution BOOLEAN\nrun_status ENUM\n";
  for (const std::string& m : metrics) properties += m + (m == "valid" ? " BOOLEAN\n" : " REAL\n");
  properties += "wall STRING\nrun_key STRING\n";
  const std::size_t property_count = 7 + metrics.size();
  std::string status_enum = "run_status";
  for (RunStatus s : kStatuses) status_enum += std::string("|") + toString(s);

  std::map<std::string, std::string> params_of;  // configuration label -> "key=value, ..."
  for (const ExperimentRecord::Config& c : record.planners) params_of[c.label] = "planner=" + c.planner + (c.params.empty() ? "" : ", " + c.params);

  // The experiment and host names are the last word of their lines in OMPL's format: made one
  // word the way file names are; file names unique even where two labels map to one name.
  std::vector<std::string> datasets, names;
  for (const ExperimentRecord::Dataset& d : record.datasets) {
    datasets.push_back(d.label);
    names.push_back(record.name + "." + d.label);
  }
  const std::vector<std::string> file_names = uniqueFileNames(names);
  std::vector<OmplLog> logs;
  for (std::size_t di = 0; di < datasets.size(); ++di) {
    const std::string& dataset = datasets[di];
    // Planner entries in the tables' column order; runs in key order.
    std::map<std::string, std::vector<const ResultRow*>> by_column;
    std::set<std::string> walls;
    std::set<double> widths, clearances;
    double total_s = 0.0;
    for (const ResultRow& r : results.runs) {
      if (r.dataset != dataset) continue;
      by_column[r.planner].push_back(&r);
      walls.insert(r.wall);
      widths.insert(r.tool.tool_width);
      clearances.insert(r.tool.clearance);
      const auto t = r.metrics.find("plan_time_ms");
      if (t != r.metrics.end() && std::isfinite(t->second)) total_s += t->second / 1000.0;
    }
    if (by_column.empty()) continue;
    std::size_t runs_per_planner = by_column.begin()->second.size();
    for (const auto& [column, rows] : by_column)
      if (rows.size() != runs_per_planner) runs_per_planner = 0;  // unequal: the optional line is left out
    auto list = [](const std::set<double>& values) {
      std::string out;
      for (double v : values) out += (out.empty() ? "" : ",") + number(v);
      return out;
    };

    OmplLog log;
    log.dataset = dataset;
    log.file_name = file_names[di] + ".log";
    std::string& t = log.text;
    t += "CoverBench version " COVERBENCH_VERSION "\n";
    t += "Experiment " + safeFileName(names[di]) + "\n";
    t += "6 experiment properties\n";
    t += "dataset STRING = " + property(dataset) + "\n";
    t += "walls INTEGER = " + std::to_string(walls.size()) + "\n";
    t += "tool_widths STRING = " + list(widths) + "\n";
    t += "clearances STRING = " + list(clearances) + "\n";
    t += "config_sha256 STRING = " + record.config_hash + "\n";
    t += "coverbench_experiment STRING = " + property(record.name) + "\n";
    t += "Running on " + safeFileName(fact(record, "host")) + "\n";
    t += "Starting at " + value(fact(record, "started (UTC)")) + "\n";
    t += "<<<|\n" + block(record.config_text) + "|>>>\n";
    t += "<<<|\nCPU: " + value(fact(record, "CPU")) + "\ncores: " + value(fact(record, "cores")) + "\nOS: " +
         value(fact(record, "OS")) + "\nmemory: " + value(fact(record, "memory")) + "\n|>>>\n";
    t += std::to_string(settings.seed) + " is the random seed\n";
    t += number(settings.time_limit_s) + " seconds per run\n";
    t += number(settings.memory_limit_mb) + " MB per run\n";
    if (runs_per_planner) t += std::to_string(runs_per_planner) + " runs per planner\n";
    t += number(total_s) + " seconds spent to collect the data\n";
    t += "1 enum types\n" + status_enum + "\n";

    std::vector<std::string> columns;
    for (const std::string& c : results.planners)
      if (by_column.count(c)) columns.push_back(c);
    t += std::to_string(columns.size()) + " planners\n";
    for (const std::string& column : columns) {
      const std::vector<const ResultRow*>& rows = by_column.at(column);
      t += column + "\n";
      // Common properties: the configuration's resolved parameters and the tool.
      std::vector<std::string> settings_lines;
      const std::string params = params_of.count(rows.front()->config) ? params_of.at(rows.front()->config) : "";
      for (std::size_t start = 0; start < params.size();) {
        std::size_t end = params.find(", ", start);
        if (end == std::string::npos) end = params.size();
        const std::string kv = params.substr(start, end - start);
        const std::size_t eq = kv.find('=');
        settings_lines.push_back(eq == std::string::npos ? kv : kv.substr(0, eq) + " = " + kv.substr(eq + 1));
        start = end + 2;
      }
      settings_lines.push_back("tool_width = " + number(rows.front()->tool.tool_width));
      settings_lines.push_back("clearance = " + number(rows.front()->tool.clearance));
      t += std::to_string(settings_lines.size()) + " common properties\n";
      for (const std::string& line : settings_lines) t += value(line) + "\n";
      t += std::to_string(property_count) + " properties for each run\n" + properties;
      t += std::to_string(rows.size()) + " runs\n";
      for (const ResultRow* r : rows) {
        auto metric = [&](const std::string& name) {
          const auto it = r->metrics.find(name);
          return it == r->metrics.end() ? NAN : it->second;
        };
        const bool has_path = hasPath(r->status);
        std::size_t status_index = 0;
        while (status_index < std::size(kStatuses) && r->status != kStatuses[status_index]) ++status_index;
        t += number(metric("plan_time_ms") / 1000.0) + "; " + number(metric("peak_memory_bytes") / (1024.0 * 1024.0)) + "; ";
        t += std::string(has_path && r->valid ? "1" : "0") + "; " + (r->status == RunStatus::Partial && r->valid ? "1" : "0") + "; ";
        t += (status_index < std::size(kStatuses) ? std::to_string(status_index) : "nan") + "; ";
        for (const std::string& m : metrics) {
          const double v = metric(m);
          t += (m == "valid" && std::isfinite(v) ? std::string(v != 0.0 ? "1" : "0") : number(v)) + "; ";
        }
        t += value(r->wall_name) + "; " + r->key + "; \n";
      }
      t += ".\n";
      log.runs += rows.size();
    }
    logs.push_back(std::move(log));
  }
  return logs;
}

}  // namespace coverbench
