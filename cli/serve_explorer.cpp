// The explorer's side of `coverbench serve` (serve_parts.hpp): each served experiment's runs as an
// index of facets (planner, dataset, status, tool) and planner parameters, read once and kept;
// each run's drawings, problem and outcome. The runs table's queries are in serve_runs.cpp.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>

#include "commands.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/wall_file.hpp"
#include "serve_parts.hpp"

namespace coverbench::cli::serve_internal {
using nlohmann::json;

Explorer::Explorer(const std::vector<std::string>& databases) {
  for (const std::string& file : databases) {
    auto db = std::make_unique<ResultsDb>(file, ResultsDb::Mode::ReadOnly);  // refuses what is not ours
    dbs_.push_back({file, std::move(db)});
  }
}

json Explorer::experiments() {
  std::lock_guard<std::mutex> lock(mutex_);
  json out = json::array();
  for (std::size_t i = 0; i < dbs_.size(); ++i)
    for (const ResultsDb::ExperimentEntry& e : dbs_[i].db->experiments())
      out.push_back({{"db", i}, {"file", dbs_[i].file}, {"id", e.id}, {"name", e.name}, {"runs", e.runs}});
  return {{"experiments", out}};
}

std::string Explorer::drawing(std::size_t db, long long id, const std::string& key, bool playback) {
  ResultsDb::StoredRun r;
  MotionLimits motion;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    r = storedRun(db, id, key);
    motion = index(db, id).motion;
  }
  if (playback) {
    if (r.path.segments() == 0) throw HttpError(404, "run " + key + " has no path to play");
    return playbackScript("/api/experiments/" + std::to_string(db) + "/" + std::to_string(id) + "/runs/" + key + "/playback.js",
                          r.wall, r.tool, r.vehicle, r.path, motion);
  }
  return pathPicture(r.wall, r.tool, r.vehicle, r.path, r.wall.name + " / " + r.planner + "  " + r.status,
                     pictureLayers(r.path, r.status).layer, kGalleryOverlapStrips, 0, true);
}

std::string Explorer::coat(std::size_t db, long long id, const std::string& key) {
  ResultsDb::StoredRun r;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    r = storedRun(db, id, key);
  }
  if (!r.tool.profile.set())
    throw HttpError(404, "run " + key + "'s tool has no flux profile (its experiment's tool: gives none): it lays no coat");
  if (!pictureLayers(r.path, r.status).scorable)
    throw HttpError(404, "run " + key + " has no scored path (" + r.status + "): no coat to draw");
  std::lock_guard<std::mutex> lock(coat_mutex_);
  try {
    return coatPicture(r.wall, r.tool, r.path, r.motion, r.vehicle, r.wall.name + " / " + r.planner + "  " + r.status + ": the coat", true);
  } catch (const InputError& e) {  // a raster over the cap: the run's metrics said so too
    throw HttpError(404, "run " + key + " has no coat picture: " + e.problem());
  }
}

ResultsDb::StoredRun Explorer::storedRun(std::size_t db, long long id, const std::string& key) {
  if (!index(db, id).position.count(key))
    throw HttpError(404, "experiment " + std::to_string(id) + " of database " + std::to_string(db) + " has no run " + key);
  return dbs_[db].db->storedRun(key);
}

json Explorer::problem(std::size_t db, long long id, const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ResultsDb::StoredRun r = storedRun(db, id, key);
  json params = json::object();
  const nlohmann::ordered_json stored = storedParamsJson(r.params_json);
  for (const auto& [k, v] : stored.items()) params[k] = paramTextOfJson(v);  // the text the workbench form shows and sends back
  return {{"wall", wallToJson(r.wall)}, {"planner", r.planner_name}, {"params", params},
          {"tool_width", r.tool.tool_width}, {"clearance", r.tool.clearance}};
}

json Explorer::outcome(std::size_t db, long long id, const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ResultsDb::StoredRun r = storedRun(db, id, key);
  return {{"status", r.status}, {"reason", r.reason}, {"stderr_tail", r.stderr_tail}, {"wall_name", r.wall.name},
          {"planner", r.planner}, {"tool_width", r.tool.tool_width}, {"clearance", r.tool.clearance}};
}

Explorer::Index& Explorer::index(std::size_t db, long long id) {
  if (db >= dbs_.size()) throw HttpError(404, "no database " + std::to_string(db) + " (serving " + std::to_string(dbs_.size()) + ")");
  const auto k = std::make_pair(db, id);
  if (const auto it = cache_.find(k); it != cache_.end()) return it->second;
  const auto ids = dbs_[db].db->experiments();
  if (std::none_of(ids.begin(), ids.end(), [&](const ResultsDb::ExperimentEntry& e) { return e.id == id; }))
    throw HttpError(404, dbs_[db].file + ": no experiment " + std::to_string(id));
  Index x;
  x.runs = dbs_[db].db->runSummaries(id);
  x.metric_names = dbs_[db].db->metricNames(id);
  std::array<std::map<std::string, std::uint32_t>, kFacets> seen;
  for (std::uint32_t i = 0; i < x.runs.size(); ++i) {
    const ResultsDb::RunSummary& r = x.runs[i];
    x.position.emplace(r.key, i);
    const std::string values[kFacets] = {r.planner, r.dataset, toString(r.status), toolAndProfileLabel(r.tool)};
    for (std::size_t f = 0; f < kFacets; ++f) {
      const auto [it, added] = seen[f].emplace(values[f], static_cast<std::uint32_t>(x.facet_values[f].size()));
      if (added) x.facet_values[f].push_back(values[f]);
      x.facet_of[f].push_back(it->second);
    }
  }
  const ExperimentRecord record = dbs_[db].db->record(id);
  // Planners and datasets in the config's order (the first dataset is the one the Plots tab opens
  // on), not in the order their runs' keys happen to sort in; a value the config does not list
  // (none should) keeps its place after those it does.
  auto configOrder = [&](std::size_t f, const std::vector<std::string>& order) {
    std::vector<std::uint32_t> by(x.facet_values[f].size());
    for (std::uint32_t v = 0; v < by.size(); ++v) by[v] = v;
    auto rank = [&](std::uint32_t v) {
      return static_cast<std::size_t>(std::find(order.begin(), order.end(), x.facet_values[f][v]) - order.begin());
    };
    std::stable_sort(by.begin(), by.end(), [&](std::uint32_t a, std::uint32_t b) { return rank(a) < rank(b); });
    std::vector<std::uint32_t> now(by.size());
    std::vector<std::string> values(by.size());
    for (std::uint32_t k = 0; k < by.size(); ++k) now[by[k]] = k, values[k] = x.facet_values[f][by[k]];
    x.facet_values[f] = std::move(values);
    for (std::uint32_t& v : x.facet_of[f]) v = now[v];
  };
  std::vector<std::string> planner_order, dataset_order;
  for (const ExperimentRecord::Config& c : record.planners) planner_order.push_back(c.label);
  for (const ExperimentRecord::Dataset& d : record.datasets) dataset_order.push_back(d.label);
  configOrder(0, planner_order);
  configOrder(1, dataset_order);
  // Each planner column's parameters, as text (the workbench's) and as stored JSON (the CSV's).
  std::map<std::string, std::set<std::string>> values;
  for (const std::string& label : x.facet_values[0]) {
    std::map<std::string, std::string> params;
    std::string stored = "{}", family = label;
    for (const ExperimentRecord::Config& c : record.planners)
      if (c.label == label) {
        family = c.planner;
        const nlohmann::ordered_json j = storedParamsJson(c.params);
        stored = j.dump();
        for (const auto& [name, v] : j.items()) values[name].insert(params[name] = paramTextOfJson(v));
      }
    x.params_of_planner.push_back(std::move(params));
    x.params_json_of_planner.push_back(std::move(stored));
    x.family_of_planner.push_back(std::move(family));
  }
  for (const auto& [name, v] : values) x.param_values[name].assign(v.begin(), v.end());
  x.motion = configMotion(record.config_text, dbs_[db].file + ": experiments.config_text");
  return cache_.emplace(k, std::move(x)).first->second;
}

}  // namespace coverbench::cli::serve_internal
