// The explorer's side of `coverbench serve` (serve_parts.hpp): each served experiment's runs as an
// index of facets (planner, dataset, status, tool) and sort orders, read once and kept.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include "commands.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/wall_file.hpp"
#include "serve_parts.hpp"

namespace coverbench::cli::serve_internal {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxRunsPerPage = 1000;

}  // namespace

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

json Explorer::runs(std::size_t db, long long id, const Params& query) {
  std::lock_guard<std::mutex> lock(mutex_);
  Index& x = index(db, id);
  // A parameter's first value, as httplib's get_param_value gives it ("" when it is not given).
  auto param = [&](const char* name) {
    const auto it = query.lower_bound(name);
    return it != query.end() && it->first == name ? it->second : std::string();
  };
  const std::string sort = param("sort");
  const std::string order = param("order").empty() ? "asc" : param("order");
  if (order != "asc" && order != "desc") throw HttpError(400, "order: must be asc or desc, got '" + order + "'");
  const std::size_t offset = number(param("offset"), "offset", 0, 1u << 30);
  const std::size_t limit = number(param("limit"), "limit", 100, kMaxRunsPerPage);
  // A filter names a value of its facet; one that names none matches no run.
  std::array<long long, kFacets> wanted;  // -1: any; -2: a value no run has; else its index
  for (std::size_t f = 0; f < kFacets; ++f) {
    const std::string v = param(kFacetNames[f]);
    const auto& values = x.facet_values[f];
    const auto it = std::find(values.begin(), values.end(), v);
    wanted[f] = v.empty() ? -1 : it == values.end() ? -2 : static_cast<long long>(it - values.begin());
  }
  const std::vector<std::uint32_t>& order_of = sorted(x, db, id, sort, order == "desc");
  std::size_t total = 0;
  std::vector<std::uint32_t> page;
  for (const std::uint32_t i : order_of) {
    bool match = true;
    for (std::size_t f = 0; f < kFacets && match; ++f) match = wanted[f] == -1 || wanted[f] == static_cast<long long>(x.facet_of[f][i]);
    if (!match) continue;
    if (total >= offset && page.size() < limit) page.push_back(i);
    ++total;
  }
  std::vector<std::string> keys;
  for (const std::uint32_t i : page) keys.push_back(x.runs[i].key);
  const auto metrics = dbs_[db].db->metricsOf(keys);
  json out = json::array();
  for (const std::uint32_t i : page) {
    const ResultsDb::RunSummary& r = x.runs[i];
    json m = json::object();
    for (const auto& [k, v] : metrics.at(r.key))
      if (std::isfinite(v)) m[k] = v;
    out.push_back({{"key", r.key}, {"planner", r.planner}, {"dataset", r.dataset}, {"wall", r.wall}, {"wall_name", r.wall_name},
                   {"status", toString(r.status)}, {"tool", x.facet_values[3][x.facet_of[3][i]]}, {"tool_width", r.tool.tool_width},
                   {"clearance", r.tool.clearance}, {"metrics", m}});
  }
  json facets = json::object();
  for (std::size_t f = 0; f < kFacets; ++f) facets[kFacetNames[f]] = x.facet_values[f];
  return {{"total", total}, {"offset", offset}, {"metrics", x.metric_names}, {"facets", facets}, {"runs", out}};
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

const std::vector<std::uint32_t>& Explorer::sorted(Index& x, std::size_t db, long long id, const std::string& column, bool desc) {
  const auto k = std::make_pair(column, desc);
  if (const auto it = x.orders.find(k); it != x.orders.end()) return it->second;
  std::vector<std::uint32_t> order(x.runs.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto& names = x.metric_names;
  if (std::find(names.begin(), names.end(), column) != names.end()) {
    std::vector<double> v;
    if (column == "plan_time_ms" || column == "peak_memory_bytes")
      for (const auto& r : x.runs) v.push_back(column == "plan_time_ms" ? r.plan_time_ms : r.peak_memory_bytes);
    else
      v = dbs_[db].db->metricColumn(id, column);
    if (v.size() != x.runs.size()) throw HttpError(500, "the runs of experiment " + std::to_string(id) + " changed while served");
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const bool ha = std::isfinite(v[a]), hb = std::isfinite(v[b]);
      if (ha != hb) return ha;
      return ha && (desc ? v[b] < v[a] : v[a] < v[b]);
    });
  } else if (!column.empty()) {
    const auto f = std::find_if(std::begin(kFacetNames), std::end(kFacetNames), [&](const char* n) { return column == n; });
    if (column != "wall_name" && f == std::end(kFacetNames))
      throw HttpError(400, "sort: unknown column '" + column + "' (a metric, wall_name, planner, dataset, status or tool)");
    auto text = [&](std::uint32_t i) -> const std::string& {
      if (f == std::end(kFacetNames)) return x.runs[i].wall_name;
      const std::size_t facet = static_cast<std::size_t>(f - std::begin(kFacetNames));
      return x.facet_values[facet][x.facet_of[facet][i]];
    };
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return desc ? text(b) < text(a) : text(a) < text(b);
    });
  }
  return x.orders.emplace(k, std::move(order)).first->second;
}

std::size_t Explorer::number(const std::string& text, const char* name, std::size_t fallback, std::size_t most) {
  if (text.empty()) return fallback;
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text[0] == '-' || v > most)
    throw HttpError(400, std::string(name) + ": must be a whole number from 0 to " + std::to_string(most) + ", got '" + text + "'");
  return static_cast<std::size_t>(v);
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
    const std::string values[kFacets] = {r.planner, r.dataset, toString(r.status), toolLabel(r.tool)};
    for (std::size_t f = 0; f < kFacets; ++f) {
      const auto [it, added] = seen[f].emplace(values[f], static_cast<std::uint32_t>(x.facet_values[f].size()));
      if (added) x.facet_values[f].push_back(values[f]);
      x.facet_of[f].push_back(it->second);
    }
  }
  const ExperimentRecord record = dbs_[db].db->record(id);
  x.motion = configMotion(record.config_text, dbs_[db].file + ": experiments.config_text");
  return cache_.emplace(k, std::move(x)).first->second;
}

}  // namespace coverbench::cli::serve_internal
