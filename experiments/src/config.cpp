// The experiment config: YAML (yaml-cpp), checked completely before any run, errors with lines.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "coverbench/datasets.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/registry.hpp"

namespace coverbench {
namespace {

namespace fs = std::filesystem;

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// Reads one config file; every error names FILE:LINE and the key path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& field, const std::string& problem) const {
    const int line = at.IsDefined() && at.Mark().line >= 0 ? at.Mark().line + 1 : 1;
    throw InputError(file_ + ":" + std::to_string(line), field, problem);
  }

  void onlyKeys(const YAML::Node& map, const std::string& where, const std::vector<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, where.empty() ? "(document)" : where, "must be a mapping of keys to values");
    for (const auto& item : map) {
      const std::string key = item.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string hint;
      std::size_t best = 3;
      for (const std::string& a : allowed)
        if (editDistance(key, a) < best) best = editDistance(key, a), hint = a;
      std::string known;
      for (const std::string& a : allowed) known += (known.empty() ? "" : ", ") + a;
      fail(item.first, where.empty() ? key : where + "." + key,
           "unknown key" + (hint.empty() ? " (allowed: " + known + ")" : " (did you mean '" + hint + "'?)"));
    }
  }

  std::string text(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(n, field, "must be a single value");
    return n.Scalar();
  }
  double number(const YAML::Node& n, const std::string& field, double lo, double hi, bool open_lo = false) const {
    const std::string t = text(n, field);
    double v = 0.0;
    std::size_t used = 0;
    try {
      v = std::stod(t, &used);
    } catch (...) {
      used = 0;
    }
    if (used != t.size() || t.empty() || !std::isfinite(v)) fail(n, field, "must be a number, got '" + t + "'");
    if (v < lo || v > hi || (open_lo && v == lo))
      fail(n, field, "must be in " + std::string(open_lo ? "(" : "[") + toString(lo) + ", " + toString(hi) + "], got " + t);
    return v;
  }
  long long integer(const YAML::Node& n, const std::string& field, long long lo, long long hi) const {
    const double v = number(n, field, static_cast<double>(lo), static_cast<double>(hi));
    if (v != std::floor(v)) fail(n, field, "must be a whole number, got " + text(n, field));
    return static_cast<long long>(v);
  }
  /// A scalar or a list of scalars, as a list.
  std::vector<YAML::Node> values(const YAML::Node& n, const std::string& field) const {
    std::vector<YAML::Node> out;
    if (n.IsSequence()) {
      if (n.size() == 0) fail(n, field, "must not be an empty list");
      for (const auto& item : n) out.push_back(item);
    } else {
      out.push_back(n);
    }
    return out;
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

std::string join(const std::vector<std::pair<std::string, std::string>>& settings) {
  std::string out;
  for (const auto& [k, v] : settings) out += (out.empty() ? "" : ", ") + k + "=" + v;
  return out;
}

/// One planner configuration: resolved parameters, its label, and its content hash.
PlannerConfig makeConfig(const PlannerInfo& info, std::vector<std::pair<std::string, std::string>> settings,
                         const std::string& where) {
  PlannerConfig pc;
  pc.planner = info.name;
  pc.params = resolveParams(info, settings, where);
  pc.label = settings.empty() ? info.name : info.name + "(" + join(settings) + ")";
  pc.settings = std::move(settings);
  std::string canonical = "planner=" + info.name;
  for (const auto& [k, v] : pc.params.all()) canonical += "\n" + k + "=" + toString(v);
  pc.id = sha256Hex(canonical);
  return pc;
}

}  // namespace

ExperimentConfig loadExperimentConfig(const std::string& path) {
  ExperimentConfig c;
  c.path = path;
  c.text = readFile(path);
  c.hash = sha256Hex(c.text);
  const Reader r(path);
  YAML::Node doc;
  try {
    doc = YAML::Load(c.text);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1), "(document)", "YAML syntax: " + e.msg);
  }
  if (!doc.IsMap()) throw InputError(path + ":1", "(document)", "must be a mapping (name, datasets, planners, ...)");
  r.onlyKeys(doc, "", {"name", "output", "datasets", "planners", "tool", "repetitions", "limits", "baseline", "threads", "seed"});
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (base / p).lexically_normal().string(); };

  for (const char* required : {"name", "output", "datasets", "planners"})
    if (!doc[required]) throw InputError(path + ":1", required, "missing");
  c.name = r.text(doc["name"], "name");
  c.output = resolve(r.text(doc["output"], "output"));

  // Datasets.
  const YAML::Node datasets = doc["datasets"];
  if (!datasets.IsSequence() || datasets.size() == 0) r.fail(datasets, "datasets", "must be a non-empty list");
  for (std::size_t i = 0; i < datasets.size(); ++i) {
    const YAML::Node d = datasets[i];
    const std::string where = "datasets[" + std::to_string(i) + "]";
    r.onlyKeys(d, where, {"family", "count", "seed", "suite", "folder", "label"});
    DatasetSpec spec;
    spec.line = d.Mark().line + 1;
    const int kinds = (d["family"] ? 1 : 0) + (d["suite"] ? 1 : 0) + (d["folder"] ? 1 : 0);
    if (kinds != 1) r.fail(d, where, "needs exactly one of family (with count and seed), suite, or folder");
    if (d["family"]) {
      spec.kind = DatasetSpec::Kind::Family;
      spec.family = r.text(d["family"], where + ".family");
      try {
        if (findFamily(spec.family, "", "").fixed_suite) r.fail(d["family"], where + ".family", "'" + spec.family + "' is a suite: write suite: " + spec.family);
      } catch (const InputError& e) {
        if (e.source().empty()) r.fail(d["family"], where + ".family", e.problem());
        throw;
      }
      if (!d["count"]) r.fail(d, where + ".count", "missing (how many walls to generate)");
      spec.count = static_cast<std::size_t>(r.integer(d["count"], where + ".count", 1, 1000000));
      spec.seed = d["seed"] ? static_cast<std::uint64_t>(r.integer(d["seed"], where + ".seed", 0, 1LL << 53)) : 0;
    } else if (d["suite"]) {
      spec.kind = DatasetSpec::Kind::Suite;
      spec.family = r.text(d["suite"], where + ".suite");
      try {
        if (!findFamily(spec.family, "", "").fixed_suite) r.fail(d["suite"], where + ".suite", "'" + spec.family + "' is a generator family: write family, count and seed");
      } catch (const InputError& e) {
        if (e.source().empty()) r.fail(d["suite"], where + ".suite", e.problem());
        throw;
      }
      if (d["count"] || d["seed"]) r.fail(d, where, "a suite has a fixed set of walls: no count or seed");
    } else {
      spec.kind = DatasetSpec::Kind::Folder;
      spec.folder = resolve(r.text(d["folder"], where + ".folder"));
      if (d["count"] || d["seed"]) r.fail(d, where, "a folder has a fixed set of walls: no count or seed");
      if (!fs::is_directory(spec.folder)) r.fail(d["folder"], where + ".folder", "'" + spec.folder + "' is not a folder");
    }
    spec.label = d["label"] ? r.text(d["label"], where + ".label")
                 : spec.kind == DatasetSpec::Kind::Folder ? fs::path(spec.folder).filename().string()
                                                          : spec.family;
    c.datasets.push_back(spec);
  }

  // Planners, with sweeps expanded (lists give the product of their values, in key order).
  const YAML::Node planners = doc["planners"];
  if (!planners.IsSequence() || planners.size() == 0) r.fail(planners, "planners", "must be a non-empty list");
  std::set<std::string> labels;
  for (std::size_t i = 0; i < planners.size(); ++i) {
    const std::string where = "planners[" + std::to_string(i) + "]";
    YAML::Node p = planners[i];
    if (p.IsScalar() && p.Scalar() == "all") {  // every registered planner, default parameters
      for (const PlannerInfo& info : registeredPlanners()) {
        PlannerConfig pc = makeConfig(info, {}, where);
        if (!labels.insert(pc.label).second) r.fail(p, where, "configuration '" + pc.label + "' is listed twice");
        c.planners.push_back(std::move(pc));
      }
      continue;
    }
    if (p.IsScalar()) {  // "- zigzag" is short for "- name: zigzag"
      YAML::Node m;
      m["name"] = p;
      p = m;
      p.SetStyle(YAML::EmitterStyle::Block);
    }
    r.onlyKeys(p, where, {"name", "params"});
    if (!p["name"]) r.fail(p, where + ".name", "missing");
    const std::string name = r.text(p["name"], where + ".name");
    const PlannerInfo* info = nullptr;
    for (const PlannerInfo& candidate : registeredPlanners())
      if (candidate.name == name) info = &candidate;
    if (!info) {
      std::string known;
      for (const PlannerInfo& candidate : registeredPlanners()) known += (known.empty() ? "" : ", ") + candidate.name;
      r.fail(planners[i].IsScalar() ? planners[i] : p["name"], where + ".name", "unknown planner '" + name + "' (registered: " + known + ")");
    }
    std::vector<std::vector<std::pair<std::string, std::string>>> combos{{}};
    if (p["params"]) {
      const YAML::Node params = p["params"];
      std::vector<std::string> declared;
      for (const ParamSpec& s : info->params) declared.push_back(s.name);
      r.onlyKeys(params, where + ".params", declared);
      std::vector<std::pair<std::string, YAML::Node>> sorted;
      for (const auto& item : params) sorted.push_back({item.first.as<std::string>(), item.second});
      std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [key, node] : sorted) {
        const std::string field = where + ".params." + key;
        std::vector<std::vector<std::pair<std::string, std::string>>> next;
        for (const YAML::Node& v : r.values(node, field)) {
          const std::string value = r.text(v, field);
          try {
            resolveParams(*info, {{key, value}}, "");
          } catch (const InputError& e) {
            r.fail(v, field, e.problem());
          }
          for (auto combo : combos) {
            combo.push_back({key, value});
            next.push_back(std::move(combo));
          }
        }
        combos = std::move(next);
      }
    }
    for (auto& settings : combos) {
      PlannerConfig pc = makeConfig(*info, std::move(settings), where);
      if (!labels.insert(pc.label).second) r.fail(planners[i], where, "configuration '" + pc.label + "' is listed twice");
      c.planners.push_back(std::move(pc));
    }
  }

  // Tool: width and clearance, each a value or a list.
  std::vector<double> widths{0.1}, clearances{0.02};
  if (doc["tool"]) {
    const YAML::Node t = doc["tool"];
    r.onlyKeys(t, "tool", {"width", "clearance"});
    if (t["width"]) {
      widths.clear();
      for (const YAML::Node& v : r.values(t["width"], "tool.width")) widths.push_back(r.number(v, "tool.width", 0.0, 10.0, true));
    }
    if (t["clearance"]) {
      clearances.clear();
      for (const YAML::Node& v : r.values(t["clearance"], "tool.clearance"))
        clearances.push_back(r.number(v, "tool.clearance", 0.0, 10.0));
    }
  }
  for (double w : widths)
    for (double cl : clearances) c.tools.push_back(ToolParams{w, cl});

  if (doc["repetitions"]) c.repetitions = static_cast<int>(r.integer(doc["repetitions"], "repetitions", 1, 1000));
  if (doc["limits"]) {
    const YAML::Node l = doc["limits"];
    r.onlyKeys(l, "limits", {"time_s", "memory_mb"});
    if (l["time_s"]) c.time_limit_s = r.number(l["time_s"], "limits.time_s", 0.0, 86400.0, true);
    if (l["memory_mb"]) c.memory_limit_mb = r.number(l["memory_mb"], "limits.memory_mb", 0.0, 1048576.0, true);
  }
  if (doc["threads"]) c.threads = static_cast<unsigned>(r.integer(doc["threads"], "threads", 0, 1024));
  if (doc["seed"]) c.seed = static_cast<std::uint64_t>(r.integer(doc["seed"], "seed", 0, 1LL << 53));
  c.baseline = c.planners.front().label;
  if (doc["baseline"]) {
    c.baseline = r.text(doc["baseline"], "baseline");
    if (!labels.count(c.baseline)) {
      std::string known;
      for (const PlannerConfig& pc : c.planners) known += (known.empty() ? "" : ", ") + pc.label;
      r.fail(doc["baseline"], "baseline", "'" + c.baseline + "' is not one of the planner configurations (" + known + ")");
    }
  }
  return c;
}

}  // namespace coverbench
