#include "coverbench/plan_file.hpp"

#include "coverbench/param_codec.hpp"

#include <cmath>
#include <cstdio>
#include <tuple>

#include "coverbench/json_input.hpp"
#include "coverbench/limits.hpp"

namespace coverbench {
namespace {

using nlohmann::ordered_json;

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

/// Counts print as integers, `valid` as a boolean, infinities as null.
ordered_json metricValue(const std::string& name, double v) {
  if (name == "valid") return v != 0.0;
  if (name == "violations" || name == "outside_boundary" || name == "too_close" || name == "turns" ||
      name == "turns_30" || name == "waypoints")
    return static_cast<long long>(v);
  return number(v);
}

std::string metricsObject(const PathMetrics& metrics, const std::string& indent) {
  std::string text = "{";
  bool first = true;
  for (const NamedMetric& m : flatten(metrics)) {
    text += (first ? "\n" : ",\n") + indent + "  " + ordered_json(m.name).dump() + ": " + metricValue(m.name, m.value).dump();
    first = false;
  }
  return text + "\n" + indent + "}";
}

}  // namespace

std::string metricsJson(const PathMetrics& metrics) { return metricsObject(metrics, "") + "\n"; }

std::string violationsJson(const Validity& validity) {
  ordered_json out = ordered_json::array();
  for (const Violation& v : validity.described)
    out.push_back({{"segment", v.segment},
                   {"from", {v.from.x, v.from.y}},
                   {"to", {v.to.x, v.to.y}},
                   {"outside_boundary", v.outside_boundary},
                   {"lifted", v.lifted},
                   {"too_close", v.too_close},
                   {"not_drivable", v.not_drivable},
                   {"boundary_gap", number(v.boundary_gap)},
                   {"clearance", number(v.clearance)},
                   {"obstacle", v.obstacle >= 0 ? ordered_json(v.obstacle) : ordered_json(nullptr)},
                   {"obstacle_label", v.obstacle_label}});
  return out.dump();
}

std::string profileJson(const ToolParams& tool) {
  const FluxProfile& p = tool.profile;
  if (!p.set()) return "null";
  ordered_json profile = {{"kind", toString(p.kind)}};
  if (p.kind == FluxProfile::Kind::Gaussian) profile["sigma"] = p.sigma;
  if (p.kind == FluxProfile::Kind::Beta) profile["beta"] = p.beta;
  profile["rate"] = p.rate;
  profile["depth"] = p.depthFor(tool.tool_width);
  if (p.target > 0.0) profile["target"] = p.target;  // micrometres; none: no key
  if (p.flow == FluxProfile::Flow::Speed) profile["flow"] = toString(p.flow);  // constant: no key
  return profile.dump();
}

std::string planFileJson(const PlanFile& plan) {
  ordered_json doc;
  doc["planner"] = plan.planner;
  doc["wall"] = plan.wall;
  doc["tool_width"] = plan.tool.tool_width;
  doc["clearance"] = plan.tool.clearance;
  if (plan.tool.turnsWithHeading()) doc["tool_shape"] = toString(plan.tool.shape);  // a disk: no key, as before shapes
  if (plan.tool.isRectangle()) doc["tool_depth"] = plan.tool.depth;
  if (plan.tool.profile.set()) doc["profile"] = ordered_json::parse(profileJson(plan.tool));
  if (plan.start) doc["start"] = {plan.start->x, plan.start->y};
  if (plan.end) doc["end"] = {plan.end->x, plan.end->y};
  if (!plan.vehicle.isDefault()) doc["vehicle"] = ordered_json::parse(vehicleJson(plan.vehicle));
  if (!plan.transit.isDefault())
    doc["transit"] = {{"planner", plan.transit.planner}, {"iterations", plan.transit.iterations},
                      {"time_cap_s", plan.transit.time_cap_s}, {"seed", plan.seed}};
  doc["params"] = paramsJson(plan.params);
  doc["status"] = toString(plan.result.status);
  doc["reason"] = plan.result.reason;
  ordered_json waypoints = ordered_json::array();
  for (const Point& p : plan.result.path.waypoints) waypoints.push_back({p.x, p.y});
  doc["waypoints"] = waypoints;
  ordered_json tool_on = ordered_json::array();
  for (bool on : plan.result.path.tool_on) tool_on.push_back(on);
  doc["tool_on"] = tool_on;
  if (plan.result.path.hasArcs()) {  // only paths with arcs (a car's) carry it
    ordered_json bulge = ordered_json::array();
    for (double b : plan.result.path.bulge) bulge.push_back(b);
    doc["bulge"] = bulge;
  }
  ordered_json stats = ordered_json::object();
  for (const auto& [name, value] : plan.result.stats) stats[name] = number(value);
  doc["planner_stats"] = stats;

  // One top-level key per line, values compact: readable, diffable, and small for long paths.
  std::string text = "{\n";
  for (auto it = doc.begin(); it != doc.end(); ++it)
    text += " " + ordered_json(it.key()).dump() + ": " + it.value().dump() + ",\n";
  if (plan.not_scored.empty()) text += " \"metrics\": " + metricsObject(plan.metrics, " ") + ",\n";
  else text += " \"metrics\": null,\n \"not_scored\": " + ordered_json(plan.not_scored).dump() + ",\n";
  // Last, apart from everything a rerun reproduces byte for byte: what this run measured.
  ordered_json planner_ms = ordered_json::object();
  for (const auto& [name, value] : plan.result.timings_ms) planner_ms[name] = number(value);
  text += " \"measured\": {\n  \"plan_time_ms\": " + number(plan.result.plan_time_ms).dump() +
          ",\n  \"peak_memory_bytes\": " +
          (plan.peak_memory_bytes ? number(*plan.peak_memory_bytes) : ordered_json(nullptr)).dump() +
          ",\n  \"planner_ms\": " + planner_ms.dump() + "\n }\n}\n";
  return text;
}

LoadedPlan loadPlanFile(const std::string& file) {
  const nlohmann::json doc = parseJsonStrict(readFile(file), file);
  if (!doc.is_object()) throw InputError(file, "(document)", "must be a JSON object");
  LoadedPlan plan;
  if (!doc.contains("waypoints")) throw InputError(file, "waypoints", "missing");
  if (!doc.contains("tool_on")) throw InputError(file, "tool_on", "missing");
  const auto& wp = doc["waypoints"];
  const auto& on = doc["tool_on"];
  if (!wp.is_array()) throw InputError(file, "waypoints", "must be an array of [x, y] points");
  if (!on.is_array()) throw InputError(file, "tool_on", "must be an array of booleans");
  if (wp.size() > kMaxScoredWaypoints)
    throw InputError(file, "waypoints",
                     "has " + std::to_string(wp.size()) + " waypoints; scoring is limited to " +
                         std::to_string(kMaxScoredWaypoints));
  for (std::size_t i = 0; i < wp.size(); ++i) {
    const std::string field = "waypoints[" + std::to_string(i) + "]";
    if (!wp[i].is_array() || wp[i].size() != 2 || !wp[i][0].is_number() || !wp[i][1].is_number())
      throw InputError(file, field, "must be an [x, y] pair of numbers");
    plan.path.waypoints.push_back({wp[i][0].get<double>(), wp[i][1].get<double>()});
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
  if (doc.contains("bulge")) {
    const auto& bulge = doc["bulge"];
    if (!bulge.is_array() || bulge.size() != expected)
      throw InputError(file, "bulge", "must be an array of one number per segment (" + std::to_string(expected) + ")");
    for (std::size_t i = 0; i < bulge.size(); ++i) {
      if (!bulge[i].is_number() || !std::isfinite(bulge[i].get<double>()) || std::fabs(bulge[i].get<double>()) > 1.0)
        throw InputError(file, "bulge[" + std::to_string(i) + "]",
                         "must be a number in [-1, 1] (tan of a quarter of the arc's angle: at most a half circle)");
      plan.path.bulge.push_back(effectiveBulge(plan.path.waypoints[i], plan.path.waypoints[i + 1], bulge[i].get<double>()));
    }
    if (!plan.path.hasArcs()) plan.path.bulge.clear();
  }
  checkScorable(plan.path, file);
  for (const char* key : {"tool_width", "clearance", "tool_depth"}) {
    if (!doc.contains(key)) continue;
    if (!doc[key].is_number()) throw InputError(file, key, "must be a number");
    const std::string k = key;
    (k == "tool_width" ? plan.tool_width : k == "clearance" ? plan.clearance : plan.tool_depth) = doc[key].get<double>();
  }
  if (doc.contains("tool_shape")) {
    ToolShape shape = ToolShape::Disk;
    if (!doc["tool_shape"].is_string() || !parseToolShape(doc["tool_shape"].get<std::string>(), shape))
      throw InputError(file, "tool_shape", "must be \"disk\", \"line\" or \"rectangle\"");
    plan.tool_shape = shape;
  }
  if (plan.tool_depth.has_value() != (plan.tool_shape == ToolShape::Rectangle))
    throw InputError(file, "tool_depth", plan.tool_depth ? "belongs to a rectangle tool (tool_shape \"rectangle\")"
                                                         : "missing: a rectangle tool has a depth");
  if (doc.contains("profile")) {  // as a config's tool.profile: each value belongs to its kind
    const auto& p = doc["profile"];
    FluxProfile profile;
    if (!p.is_object() || !p.contains("kind") || !p["kind"].is_string() ||
        !parseFluxProfileKind(p["kind"].get<std::string>(), profile.kind) || !profile.set())
      throw InputError(file, "profile.kind", "must be \"uniform\", \"gaussian\" or \"beta\"");
    for (const auto& [key, value] : p.items())
      if (key != "kind" && key != "sigma" && key != "beta" && key != "rate" && key != "depth" && key != "target" && key != "flow")
        throw InputError(file, "profile", "has an unknown key (known: kind, sigma, beta, rate, depth, target, flow)");
    const std::string kind = toString(profile.kind);
    for (const auto& [key, into, belongs] :
         {std::tuple<const char*, double*, bool>{"sigma", &profile.sigma, kind == "gaussian"}, {"beta", &profile.beta, kind == "beta"},
          {"rate", &profile.rate, true}, {"depth", &profile.depth, true}, {"target", &profile.target, true}}) {
      if (!p.contains(key)) {
        if (belongs && std::string(key) != "rate" && std::string(key) != "depth" && std::string(key) != "target")
          throw InputError(file, std::string("profile.") + key, "is missing for a " + kind + " profile");
        continue;
      }
      if (!belongs) throw InputError(file, std::string("profile.") + key, "does not belong to a " + kind + " profile");
      if (!p[key].is_number()) throw InputError(file, std::string("profile.") + key, "must be a number");
      *into = p[key].get<double>();
    }
    if (p.contains("target") && !(profile.target > 0.0 && profile.target <= FluxProfile::kMaxTarget))
      throw InputError(file, "profile.target", "must be in (0, 1e+06] um, got " + shortNumber(profile.target));
    if (p.contains("flow") && !(p["flow"].is_string() && parseFlow(p["flow"].get<std::string>(), profile.flow)))
      throw InputError(file, "profile.flow", "must be \"constant\" or \"speed\"");
    plan.profile = profile;  // checked against the tool's width by whoever scores it
  }
  for (const char* key : {"start", "end"}) {
    if (!doc.contains(key)) continue;
    const auto& p = doc[key];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError(file, key, "must be an [x, y] pair of numbers");
    (std::string(key) == "start" ? plan.start : plan.end) = Point{p[0].get<double>(), p[1].get<double>()};
  }
  if (doc.contains("vehicle")) {
    const auto& v = doc["vehicle"];
    if (!v.is_object()) throw InputError(file, "vehicle", "must be an object with model, lift_s and lower_s");
    VehicleModel vehicle;
    if (!v.contains("model") || !v["model"].is_string() || !parseVehicleKind(v["model"].get<std::string>(), vehicle.kind))
      throw InputError(file, "vehicle.model", "must be \"holonomic\", \"gantry\" or \"car\"");
    for (const auto& [key, value] : {std::pair<const char*, double*>{"lift_s", &vehicle.lift_s}, {"lower_s", &vehicle.lower_s},
                                     {"turn_radius", &vehicle.turn_radius}}) {
      if (!v.contains(key)) continue;
      if (!v[key].is_number()) throw InputError(file, std::string("vehicle.") + key, "must be a number");
      *value = v[key].get<double>();
    }
    if (v.contains("reverse")) {
      if (!v["reverse"].is_boolean()) throw InputError(file, "vehicle.reverse", "must be true or false");
      vehicle.reverse = v["reverse"].get<bool>();
    }
    validateVehicle(vehicle, file, "vehicle");
    plan.vehicle = vehicle;
  }
  return plan;
}

std::string vehicleJson(const VehicleModel& vehicle) {
  ordered_json v;
  v["model"] = toString(vehicle.kind);
  if (vehicle.isCar()) {
    v["turn_radius"] = vehicle.turn_radius;
    v["reverse"] = vehicle.reverse;
  } else {
    v["lift_s"] = vehicle.lift_s;
    v["lower_s"] = vehicle.lower_s;
  }
  return v.dump();
}

}  // namespace coverbench
