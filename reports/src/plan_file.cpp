#include "coverbench/plan_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace coverbench {
namespace {

using nlohmann::ordered_json;

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

ordered_json paramJson(const ParamValue& value) {
  return std::visit([](const auto& v) { return ordered_json(v); }, value);
}

/// Counts print as integers, `valid` as a boolean, infinities as null.
ordered_json metricValue(const std::string& name, double v) {
  if (name == "valid") return v != 0.0;
  if (name == "violations" || name == "outside_boundary" || name == "too_close" || name == "turns" ||
      name == "turns_30" || name == "waypoints")
    return static_cast<long long>(v);
  return number(v);
}

std::string metricsObject(const PathMetrics& metrics, std::optional<double> plan_time_ms,
                          std::optional<double> peak_memory_bytes, const std::string& indent) {
  std::string text = "{";
  bool first = true;
  auto add = [&](const std::string& name, const ordered_json& value) {
    text += (first ? "\n" : ",\n") + indent + "  " + ordered_json(name).dump() + ": " + value.dump();
    first = false;
  };
  for (const NamedMetric& m : flatten(metrics)) add(m.name, metricValue(m.name, m.value));
  add("plan_time_ms", plan_time_ms ? number(*plan_time_ms) : ordered_json(nullptr));
  add("peak_memory_bytes", peak_memory_bytes ? number(*peak_memory_bytes) : ordered_json(nullptr));
  return text + "\n" + indent + "}";
}

}  // namespace

std::string metricsJson(const PathMetrics& metrics, std::optional<double> plan_time_ms,
                        std::optional<double> peak_memory_bytes) {
  return metricsObject(metrics, plan_time_ms, peak_memory_bytes, "") + "\n";
}

std::string planFileJson(const PlanFile& plan) {
  ordered_json doc;
  doc["planner"] = plan.planner;
  doc["wall"] = plan.wall;
  doc["tool_width"] = plan.tool.tool_width;
  doc["clearance"] = plan.tool.clearance;
  ordered_json params = ordered_json::object();
  for (const auto& [name, value] : plan.params.all()) params[name] = paramJson(value);
  doc["params"] = params;
  doc["status"] = toString(plan.result.status);
  doc["reason"] = plan.result.reason;
  ordered_json waypoints = ordered_json::array();
  for (const Point& p : plan.result.path.waypoints) waypoints.push_back({p.x, p.y});
  doc["waypoints"] = waypoints;
  ordered_json tool_on = ordered_json::array();
  for (bool on : plan.result.path.tool_on) tool_on.push_back(on);
  doc["tool_on"] = tool_on;
  ordered_json stats = ordered_json::object();
  for (const auto& [name, value] : plan.result.stats) stats[name] = number(value);
  doc["planner_stats"] = stats;

  // One top-level key per line, values compact: readable, diffable, and small for long paths.
  std::string text = "{\n";
  for (auto it = doc.begin(); it != doc.end(); ++it)
    text += " " + ordered_json(it.key()).dump() + ": " + it.value().dump() + ",\n";
  text += " \"metrics\": " + metricsObject(plan.metrics, plan.result.plan_time_ms, plan.peak_memory_bytes, " ");
  return text + "\n}\n";
}

LoadedPlan loadPlanFile(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "(file)", "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    std::string what = e.what();
    const auto pos = what.find("] ");
    throw InputError(file, "(document)", "malformed JSON: " + (pos == std::string::npos ? what : what.substr(pos + 2)));
  }
  if (!doc.is_object()) throw InputError(file, "(document)", "must be a JSON object");
  LoadedPlan plan;
  if (!doc.contains("waypoints")) throw InputError(file, "waypoints", "missing");
  if (!doc.contains("tool_on")) throw InputError(file, "tool_on", "missing");
  const auto& wp = doc["waypoints"];
  const auto& on = doc["tool_on"];
  if (!wp.is_array()) throw InputError(file, "waypoints", "must be an array of [x, y] points");
  if (!on.is_array()) throw InputError(file, "tool_on", "must be an array of booleans");
  for (std::size_t i = 0; i < wp.size(); ++i) {
    const std::string field = "waypoints[" + std::to_string(i) + "]";
    if (!wp[i].is_array() || wp[i].size() != 2 || !wp[i][0].is_number() || !wp[i][1].is_number())
      throw InputError(file, field, "must be an [x, y] pair of numbers");
    const Point p{wp[i][0].get<double>(), wp[i][1].get<double>()};
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw InputError(file, field, "must be finite");
    plan.path.waypoints.push_back(p);
  }
  for (std::size_t i = 0; i < on.size(); ++i) {
    if (!on[i].is_boolean()) throw InputError(file, "tool_on[" + std::to_string(i) + "]", "must be true or false");
    plan.path.tool_on.push_back(on[i].get<bool>());
  }
  const std::size_t expected = plan.path.waypoints.empty() ? 0 : plan.path.waypoints.size() - 1;
  if (plan.path.tool_on.size() != expected)
    throw InputError(file, "tool_on", "has " + std::to_string(plan.path.tool_on.size()) + " entries; " +
                                          std::to_string(plan.path.waypoints.size()) + " waypoints need " +
                                          std::to_string(expected));
  for (const char* key : {"tool_width", "clearance"}) {
    if (!doc.contains(key)) continue;
    if (!doc[key].is_number()) throw InputError(file, key, "must be a number");
    (std::string(key) == "tool_width" ? plan.tool_width : plan.clearance) = doc[key].get<double>();
  }
  return plan;
}

}  // namespace coverbench
