// One row per run, for pandas, R or a spreadsheet; and a short list of runs.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

#include "coverbench/escape.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/records.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {
namespace {

/// Shortest text that reads back as the same double; empty for NaN and infinities.
std::string number(double v) { return std::isfinite(v) ? nlohmann::json(v).dump() : std::string(); }

/// A run field's value in a CSV cell and in JSON (NaN and infinities: empty, null).
std::string csvCell(const std::string& v) { return escapeCsv(v); }
std::string csvCell(RunStatus v) { return toString(v); }
std::string csvCell(bool v) { return v ? "true" : "false"; }
std::string csvCell(long long v) { return std::to_string(v); }
std::string csvCell(double v) { return number(v); }
nlohmann::ordered_json jsonValue(const std::string& v) { return v; }
nlohmann::ordered_json jsonValue(RunStatus v) { return toString(v); }
nlohmann::ordered_json jsonValue(bool v) { return v; }
nlohmann::ordered_json jsonValue(long long v) { return v; }
nlohmann::ordered_json jsonValue(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; }

/// The metric columns: every metric but `valid`, which is a fixed column.
std::vector<std::string> metricColumns(const ResultSet& rs) {
  std::vector<std::string> out;
  for (const std::string& m : rs.metric_order)
    if (m != "valid") out.push_back(m);
  return out;
}

/// The columns `vehicle` and `transit`, each only when some run has another than holonomic or
/// visibility, and `profile` (the tool's flux profile, FluxProfile::label; empty for a run
/// without one) only when some run has one (so tables of runs from before them keep their columns).
struct OptionColumns {
  bool vehicle = false, transit = false, profile = false, shape = false, depth = false;
  explicit OptionColumns(const ResultSet& rs) {
    for (const ResultRow& r : rs.runs) {
      vehicle = vehicle || !r.vehicle.isDefault();
      transit = transit || !r.transit.isDefault();
      profile = profile || r.tool.profile.set();
      shape = shape || r.tool.turnsWithHeading();
      depth = depth || r.tool.isRectangle();
    }
  }
};

}  // namespace

std::string renderRuns(const ResultSet& rs, bool json) {
  // The run's context, then its exported fields (kRunFields), then every metric.
  const OptionColumns options(rs);
  if (json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const ResultRow& r : rs.runs) {
      nlohmann::ordered_json row;
      row["key"] = r.key;
      row["dataset"] = r.dataset;
      row["wall"] = r.wall_name;
      row["wall_hash"] = r.wall;
      row["planner"] = r.config;
      row["params"] = storedParamsJson(r.params);
      row["planner_version"] = r.planner_version;
      row["tool_width"] = r.tool.tool_width;
      row["clearance"] = r.tool.clearance;
      if (options.shape) row["tool_shape"] = toString(r.tool.shape);
      if (options.depth) row["tool_depth"] = r.tool.depth;
      if (options.profile) row["profile"] = r.tool.profile.label();
      if (options.vehicle) row["vehicle"] = toString(r.vehicle.kind);
      if (options.transit) row["transit"] = r.transit.planner;
      forEachRunField(r, [&](const RunField& f, const auto& value) {
        if (f.exported != RunExport::No) row[f.name] = jsonValue(value);
      });
      for (const std::string& m : metricColumns(rs)) {
        const auto it = r.metrics.find(m);
        row[m] = it != r.metrics.end() && std::isfinite(it->second) ? nlohmann::ordered_json(it->second) : nullptr;
      }
      out.push_back(row);
    }
    return out.dump(1) + "\n";
  }
  std::string text = "key,dataset,wall,wall_hash,planner,params,planner_version,tool_width,clearance";
  text += options.shape ? ",tool_shape" : "";
  text += options.depth ? ",tool_depth" : "";
  text += options.profile ? ",profile" : "";
  text += std::string(options.vehicle ? ",vehicle" : "") + (options.transit ? ",transit" : "");
  for (const RunField& f : kRunFields)
    if (f.exported != RunExport::No) text += std::string(",") + f.name;
  for (const std::string& m : metricColumns(rs)) text += "," + escapeCsv(m);
  text += "\n";
  for (const ResultRow& r : rs.runs) {
    text += r.key + "," + escapeCsv(r.dataset) + "," + escapeCsv(r.wall_name) + "," + r.wall + "," + escapeCsv(r.config) +
            "," + escapeCsv(storedParamsJson(r.params).dump()) + "," + escapeCsv(r.planner_version) + "," + number(r.tool.tool_width) + "," + number(r.tool.clearance) +
            (options.shape ? "," + toString(r.tool.shape) : "") + (options.depth ? "," + number(r.tool.depth) : "") + (options.profile ? "," + escapeCsv(r.tool.profile.label()) : "") + (options.vehicle ? "," + toString(r.vehicle.kind) : "") + (options.transit ? "," + r.transit.planner : "");
    forEachRunField(r, [&](const RunField& f, const auto& value) {
      if (f.exported != RunExport::No) text += "," + csvCell(value);
    });
    for (const std::string& m : metricColumns(rs)) {
      const auto it = r.metrics.find(m);
      text += "," + (it == r.metrics.end() ? std::string() : number(it->second));
    }
    text += "\n";
  }
  return text;
}

namespace {
/// A name on one line of a terminal: control characters (a newline, a CR, an escape sequence's
/// ESC) as \n, \r, \t or \xHH, and a backslash doubled, so the line can be read back.
std::string oneLine(const std::string& name) {
  std::string out;
  for (char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\') out += "\\\\";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else out += c;
  }
  return out;
}
}  // namespace

std::string listRuns(const ResultSet& rs) {
  std::string text;
  for (const ResultRow& r : rs.runs) {
    text += r.key + "  " + toString(r.status) + "  " + oneLine(r.config) + "  " + toolAndProfileLabel(r.tool) + "  " +
            oneLine(r.dataset) + "/" +
            oneLine(r.wall_name) + "\n";
  }
  return text;
}

}  // namespace coverbench
