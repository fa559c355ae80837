// The experiment config's `tool:` section (config_reader.hpp): the tools an experiment runs.
#include <algorithm>

#include "config_reader.hpp"
#include "coverbench/limits.hpp"

namespace coverbench::config_yaml {

FluxProfile readProfile(Reader& r, const Yaml& p, const std::vector<double>& widths) {
  r.onlyKeys(p, "tool.profile", {"kind", "sigma", "beta", "rate", "depth", "target", "flow"});
  FluxProfile profile;
  const Yaml* kind = p.find("kind");
  if (!kind) r.fail(p, "tool.profile.kind", "is missing: uniform, gaussian or beta");
  const std::string name = r.text(*kind, "tool.profile.kind");
  if (!parseFluxProfileKind(name, profile.kind) || !profile.set())
    r.fail(*kind, "tool.profile.kind", "must be uniform, gaussian or beta, got '" + shownBytes(name) + "'");
  const bool gaussian = profile.kind == FluxProfile::Kind::Gaussian, beta = profile.kind == FluxProfile::Kind::Beta;
  if (!gaussian && p.find("sigma")) r.fail(*p.find("sigma"), "tool.profile.sigma", "belongs to a gaussian profile");
  if (!beta && p.find("beta")) r.fail(*p.find("beta"), "tool.profile.beta", "belongs to a beta profile");
  if (gaussian && !p.find("sigma")) r.fail(p, "tool.profile.sigma", "is missing: a gaussian profile's standard deviation, m");
  if (beta && !p.find("beta")) r.fail(p, "tool.profile.beta", "is missing: a beta profile's exponent");
  if (const Yaml* v = p.find("sigma")) profile.sigma = r.number(*v, "tool.profile.sigma", 0.0, 100.0);
  if (const Yaml* v = p.find("beta")) profile.beta = r.number(*v, "tool.profile.beta", 1.0, 100.0);
  if (const Yaml* v = p.find("rate")) profile.rate = r.number(*v, "tool.profile.rate", 0.0, 1.0, true);
  if (const Yaml* v = p.find("depth")) profile.depth = r.number(*v, "tool.profile.depth", 0.0, kMaxToolWidth);
  if (const Yaml* v = p.find("target")) profile.target = r.number(*v, "tool.profile.target", 0.0, FluxProfile::kMaxTarget, true);
  if (const Yaml* v = p.find("flow"))
    if (const std::string flow = r.text(*v, "tool.profile.flow"); !parseFlow(flow, profile.flow))
      r.fail(*v, "tool.profile.flow", "must be constant or speed, got '" + shownBytes(flow) + "'");
  for (double w : widths) {
    try {
      profile.check(w, "");
    } catch (const InputError& e) {
      r.fail(p.find(e.field()) ? *p.find(e.field()) : p, "tool.profile." + e.field(),
             e.problem() + " (tool width " + shortNumber(w) + " m)");
    }
  }
  return profile;
}

void readTools(Reader& r, const Yaml* t, ExperimentConfig& c) {
  std::vector<double> widths{0.1}, clearances{0.02}, depths;
  std::vector<ToolShape> shapes{ToolShape::Disk};
  auto distinct = [&](const char* key, auto read, auto& out) {
    const Yaml* n = t ? t->find(key) : nullptr;
    if (!n) return;
    const std::string field = std::string("tool.") + key;
    out.clear();
    for (const Yaml* v : r.values(*n, field)) {
      out.push_back(read(*v, field));
      if (std::find(out.begin(), out.end() - 1, out.back()) != out.end() - 1) r.fail(*v, field, "lists " + v->scalar + " twice");
    }
  };
  if (t) r.onlyKeys(*t, "tool", {"width", "clearance", "profile", "shape", "depth"});
  distinct("width", [&](const Yaml& v, const std::string& f) { return r.number(v, f, kMinToolWidth, kMaxToolWidth); }, widths);
  distinct("clearance", [&](const Yaml& v, const std::string& f) { return r.number(v, f, 0.0, kMaxClearance); }, clearances);
  distinct("shape", [&](const Yaml& v, const std::string& f) {
    ToolShape shape = ToolShape::Disk;
    if (!parseToolShape(r.text(v, f), shape)) r.fail(v, f, toolShapeProblem(v.scalar));
    return shape;
  }, shapes);
  // A rectangle's depth d (docs/metrics.md#tool-shapes): each rectangle is one tool per depth;
  // the other shapes have none.
  distinct("depth", [&](const Yaml& v, const std::string& f) { return r.number(v, f, kMinToolWidth, kMaxToolWidth); }, depths);
  const bool rectangle = std::find(shapes.begin(), shapes.end(), ToolShape::Rectangle) != shapes.end();
  if (rectangle && depths.empty()) r.fail(*t, "tool.depth", "is missing: a rectangle tool's depth along the heading, m");
  if (!rectangle && !depths.empty())
    r.fail(*t->find("depth"), "tool.depth", "belongs to a rectangle tool (tool.shape: rectangle)");
  const FluxProfile profile = t && t->find("profile") ? readProfile(r, *t->find("profile"), widths) : FluxProfile{};
  for (double w : widths)
    for (double cl : clearances)
      for (ToolShape shape : shapes)
        for (double d : shape == ToolShape::Rectangle ? depths : std::vector<double>{0.0}) {
          c.tools.push_back(ToolParams{w, cl, profile, shape, d});
        }
}

}  // namespace coverbench::config_yaml
