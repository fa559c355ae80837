#include "coverbench/plan_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

namespace coverbench {
namespace {

using nlohmann::ordered_json;

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

ordered_json paramJson(const ParamValue& value) {
  return std::visit([](const auto& v) { return ordered_json(v); }, value);
}

}  // namespace

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

  const Lengths lengths = pathLengths(plan.result.path);
  ordered_json metrics;
  metrics["valid"] = plan.validity.valid;
  metrics["violations"] = plan.validity.violations;
  metrics["outside_boundary"] = plan.validity.outside_boundary;
  metrics["too_close"] = plan.validity.too_close;
  metrics["min_clearance"] = number(plan.validity.min_clearance);
  metrics["min_boundary_gap"] = number(plan.validity.min_boundary_gap);
  metrics["waypoints"] = plan.result.path.waypoints.size();
  metrics["length_total"] = lengths.total;
  metrics["length_cover"] = lengths.cover;
  metrics["length_transit"] = lengths.transit;
  doc["metrics"] = metrics;
  ordered_json stats = ordered_json::object();
  for (const auto& [name, value] : plan.result.stats) stats[name] = number(value);
  doc["planner_stats"] = stats;
  doc["timing"] = {{"plan_time_ms", plan.result.plan_time_ms}};
  // One top-level key per line, values compact: readable, diffable, and small for long paths.
  std::string text = "{\n";
  bool first = true;
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    text += (first ? " " : ",\n ") + ordered_json(it.key()).dump() + ": " + it.value().dump();
    first = false;
  }
  return text + "\n}\n";
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "(file)", "cannot be written");
    out << text;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw InputError(path, "(file)", "write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, "(file)", "cannot be written");
  }
}

}  // namespace coverbench
