// Protocols 1 and 2 of planners outside the tree (docs/external_planners.md): the request line for
// a problem, and an answer line read strictly (bounded before it is parsed).
#include <cmath>
#include <nlohmann/json.hpp>

#include "coverbench/external_planner.hpp"
#include "coverbench/files.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench::external {
namespace {

using nlohmann::json;

/// The status an answer names (`known` false, and error, when it names none this protocol has).
PlanStatus answerStatus(const std::string& s, bool& known) {
  known = true;
  for (PlanStatus p : {PlanStatus::Ok, PlanStatus::Partial, PlanStatus::NoReachableArea, PlanStatus::InvalidInput,
                       PlanStatus::Timeout, PlanStatus::Error})
    if (s == toString(p)) return p;
  known = false;
  return PlanStatus::Error;
}

/// Why an answer line is refused before it is parsed (in `why`; 1), or 0: nested deeper than
/// kMaxAnswerDepth, or more waypoints, keys or values than an answer may hold.
std::size_t answerProblem(const std::string& line, std::string& why) {
  // Before any parsing: a line of 20 MiB of '[' would cost the parser gigabytes and seconds.
  int depth = 0;
  std::size_t arrays = 0, keys = 0, values = 1;
  bool in_string = false, escaped = false;
  for (const char c : line) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxAnswerDepth) {
        why = "nested deeper than " + std::to_string(kMaxAnswerDepth) + " levels (an answer needs 3)";
        return 1;
      }
      if (c == '[' && ++arrays > kMaxAnswerWaypoints + 8) {
        why = "holds more than " + std::to_string(kMaxAnswerWaypoints) + " waypoints (the scoring limit)";
        return 1;
      }
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ':' && ++keys > kMaxAnswerKeys) {
      why = "holds more than " + std::to_string(kMaxAnswerKeys) + " keys";
      return 1;
    } else if (c == ',' && ++values > kMaxAnswerValues) {
      why = "holds more than " + std::to_string(kMaxAnswerValues) + " values (2 per waypoint, 1 per segment's tool_on and bulge)";
      return 1;
    }
  }
  return 0;
}

/// The request's `tool`: width and clearance; from protocol 2 its shape (a rectangle's depth too)
/// and flux profile (null for none), the profile as a plan file writes it (docs/file_formats.md).
json toolJson(const ToolParams& tool, int protocol) {
  // Protocol 1: the disk that holds the tool in every heading (a line's or a rectangle's
  // circumscribed one), and nothing of a profile.
  if (protocol < 2) return {{"width", circumscribedDisk(tool).tool_width}, {"clearance", tool.clearance}};
  json out = {{"width", tool.tool_width}, {"clearance", tool.clearance}};
  out["shape"] = toString(tool.shape);
  if (tool.isRectangle()) out["depth"] = tool.depth;
  out["profile"] = json::parse(profileJson(tool));
  return out;
}

}  // namespace

std::string requestJson(const Problem& problem, double time_limit_s, long long id, int protocol) {
  json p;
  p["wall"] = json::parse(wallToJson(*problem.wall));
  p["tool"] = toolJson(problem.tool, protocol);
  json vehicle = {{"model", toString(problem.vehicle.kind)}};
  if (problem.vehicle.isCar()) {
    vehicle["turn_radius"] = problem.vehicle.turn_radius;
    vehicle["reverse"] = problem.vehicle.reverse;
  } else if (!problem.vehicle.isDefault()) {
    vehicle["lift_s"] = problem.vehicle.lift_s;
    vehicle["lower_s"] = problem.vehicle.lower_s;
  }
  p["vehicle"] = vehicle;
  p["params"] = paramsJson(problem.params);
  p["seed"] = problem.seed;
  if (std::isfinite(time_limit_s)) p["time_limit_s"] = time_limit_s;
  return json{{"protocol", protocol}, {"id", id}, {"problem", p}}.dump();
}

bool readAnswer(const std::string& line, long long id, PlanResult& result, std::string& why, int protocol) {
  auto bad = [&](const std::string& text) {
    why = toValidUtf8(text);  // it may quote the planner's bytes
    return false;
  };
  if (line.size() > kMaxAnswerBytes)
    return bad("over " + std::to_string(kMaxAnswerBytes >> 20) + " MiB");
  if (answerProblem(line, why) != 0) return bad(why);
  json a;
  try {
    a = parseJsonStrict(line, "answer");  // no duplicate key: a second "status" is not read over the first
  } catch (const InputError& e) {
    if (e.field() != "(document)") return bad(e.field() + ": " + e.problem());
    return bad("not JSON (" + std::to_string(line.size()) + " bytes: " + line.substr(0, 60) + "): " + e.problem());
  }
  if (!a.is_object()) return bad("must be a JSON object");
  for (const auto& [key, value] : a.items())
    if (key != "protocol" && key != "id" && key != "status" && key != "reason" && key != "waypoints" &&
        key != "tool_on" && key != "bulge" && key != "stats")
      return bad(key + ": unknown key");
  if (!a.contains("protocol") || a["protocol"] != protocol) return bad("protocol: must be " + std::to_string(protocol));
  if (!a.contains("id") || !a["id"].is_number_integer() || a["id"].get<long long>() != id)
    return bad("id: must be the request's (" + std::to_string(id) + ")");
  if (!a.contains("status") || !a["status"].is_string()) return bad("status: missing");
  bool known = false;
  result.status = answerStatus(a["status"].get<std::string>(), known);
  if (!known)
    return bad("status: '" + toValidUtf8(a["status"].get<std::string>()).substr(0, 200) +
               "' is none of ok, partial, no_reachable_area, invalid_input, timeout, error");
  if (a.contains("reason")) {
    if (!a["reason"].is_string()) return bad("reason: must be a string");
    // A planner's own words, kept as text: bytes that are not UTF-8 and NULs become U+FFFD (a raw
    // 0xFF ended the JSON card; a NUL cut the stored reason).
    result.reason = toValidUtf8(a["reason"].get<std::string>());
  }
  if (a.contains("stats")) {
    if (!a["stats"].is_object()) return bad("stats: must be an object of numbers");
    for (const auto& [name, v] : a["stats"].items()) {
      if (!v.is_number() || !std::isfinite(v.get<double>())) return bad("stats." + name + ": must be a finite number");
      result.stats[name] = v.get<double>();
    }
  }
  if (!result.hasPath()) {
    if (a.contains("waypoints") && !a["waypoints"].empty()) return bad("waypoints: a failed plan has no path");
    if (result.reason.empty()) return bad("reason: a failed plan says why");
    return true;
  }
  if (!a.contains("waypoints") || !a["waypoints"].is_array() || a["waypoints"].empty())
    return bad("waypoints: a plan with status " + toString(result.status) + " needs a non-empty list of [x, y]");
  const json& w = a["waypoints"];
  Path& path = result.path;
  path.waypoints.reserve(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const json& p = w[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      return bad("waypoints[" + std::to_string(i) + "]: must be [x, y]");
    const Point pt{p[0].get<double>(), p[1].get<double>()};
    if (!std::isfinite(pt.x) || !std::isfinite(pt.y)) return bad("waypoints[" + std::to_string(i) + "]: must be finite");
    path.waypoints.push_back(pt);
  }
  const std::size_t segments = w.size() - 1;
  if (!a.contains("tool_on") || !a["tool_on"].is_array() || a["tool_on"].size() != segments)
    return bad("tool_on: must be a list of " + std::to_string(segments) + " booleans (one per segment)");
  for (std::size_t i = 0; i < segments; ++i) {
    if (!a["tool_on"][i].is_boolean()) return bad("tool_on[" + std::to_string(i) + "]: must be true or false");
    path.tool_on.push_back(a["tool_on"][i].get<bool>());
  }
  if (a.contains("bulge")) {
    const json& b = a["bulge"];
    if (!b.is_array() || b.size() != segments)
      return bad("bulge: must be a list of " + std::to_string(segments) + " numbers (one per segment)");
    for (std::size_t i = 0; i < segments; ++i) {
      if (!b[i].is_number() || !std::isfinite(b[i].get<double>()) || std::fabs(b[i].get<double>()) > 1.0)
        return bad("bulge[" + std::to_string(i) + "]: must be a number in [-1, 1]");
    }
    std::vector<double> bulge;
    for (std::size_t i = 0; i < segments; ++i) bulge.push_back(b[i].get<double>());
    bool arcs = false;
    for (double v : bulge) arcs = arcs || v != 0.0;
    if (arcs) path.bulge = std::move(bulge);
  }
  return true;
}

}  // namespace coverbench::external
