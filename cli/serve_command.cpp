// `coverbench serve`: a local web application over experiment databases (cpp-httplib). It serves
// only the databases named on its command line and its own page files, each by a fixed name: no
// part of a request reaches the file system. Errors are JSON: {"error": "one line"}.
#include <httplib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <stdexcept>

#include "commands.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/files.hpp"
#include "coverbench/report_data.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/svg.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A request that cannot be answered: its HTTP status and one line.
struct HttpError : std::runtime_error {
  int status;
  HttpError(int s, const std::string& message) : std::runtime_error(message), status(s) {}
};

constexpr std::size_t kMaxRunsPerPage = 1000;
constexpr std::size_t kMaxBodyBytes = 1 << 20;

/// The page's files, by the only names they are served under.
const std::map<std::string, std::pair<std::string, std::string>>& pageFiles() {
  static const std::map<std::string, std::pair<std::string, std::string>> files = {
      {"/", {COVERBENCH_WEB_DIR "/index.html", "text/html; charset=utf-8"}},
      {"/explorer.js", {COVERBENCH_WEB_DIR "/explorer.js", "text/javascript; charset=utf-8"}},
      {"/player.js", {COVERBENCH_REPORT_PYTHONPATH "/coverbench_report/player.js", "text/javascript; charset=utf-8"}},
  };
  return files;
}

class Explorer {
 public:
  explicit Explorer(const std::vector<std::string>& databases) {
    for (const std::string& file : databases) {
      auto db = std::make_unique<ResultsDb>(file, ResultsDb::Mode::ReadOnly);  // refuses what is not ours
      dbs_.push_back({file, std::move(db)});
    }
  }

  json experiments() {
    std::lock_guard<std::mutex> lock(mutex_);
    json out = json::array();
    for (std::size_t i = 0; i < dbs_.size(); ++i)
      for (const ResultsDb::ExperimentEntry& e : dbs_[i].db->experiments())
        out.push_back({{"db", i}, {"file", dbs_[i].file}, {"id", e.id}, {"name", e.name}, {"runs", e.runs}});
    return {{"experiments", out}};
  }

  json runs(std::size_t db, long long id, const httplib::Request& req) {
    std::lock_guard<std::mutex> lock(mutex_);
    Index& x = index(db, id);
    auto param = [&](const char* name) { return req.has_param(name) ? req.get_param_value(name) : std::string(); };
    const std::string sort = param("sort");
    const std::string order = param("order").empty() ? "asc" : param("order");
    if (order != "asc" && order != "desc") throw HttpError(400, "order: must be asc or desc, got '" + order + "'");
    const std::size_t offset = number(param("offset"), "offset", 0, 1u << 30);
    const std::size_t limit = number(param("limit"), "limit", 100, kMaxRunsPerPage);
    // A filter names a value of its facet; one that names none matches no run.
    std::array<int, kFacets> wanted;
    for (std::size_t f = 0; f < kFacets; ++f) {
      const std::string v = param(kFacetNames[f]);
      const auto& values = x.facet_values[f];
      const auto it = std::find(values.begin(), values.end(), v);
      wanted[f] = v.empty() ? -1 : it == values.end() ? -2 : static_cast<int>(it - values.begin());
    }
    const std::vector<std::uint32_t>& order_of = sorted(x, db, id, sort, order == "desc");
    std::size_t total = 0;
    std::vector<std::uint32_t> page;
    for (const std::uint32_t i : order_of) {
      bool match = true;
      for (std::size_t f = 0; f < kFacets && match; ++f) match = wanted[f] == -1 || wanted[f] == x.facet_of[f][i];
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

  /// The run's picture, or the script that plays it back under the experiment's time model. The
  /// run is read under the lock; it is drawn outside it, so other requests do not wait for it.
  std::string drawing(std::size_t db, long long id, const std::string& key, bool playback) {
    ResultsDb::StoredRun r;
    MotionLimits motion;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const Index& x = index(db, id);
      if (!x.position.count(key))
        throw HttpError(404, "experiment " + std::to_string(id) + " of database " + std::to_string(db) + " has no run " + key);
      r = dbs_[db].db->storedRun(key);
      motion = x.motion;
    }
    if (playback) {
      if (r.path.segments() == 0) throw HttpError(404, "run " + key + " has no path to play");
      return playbackScript("/api/experiments/" + std::to_string(db) + "/" + std::to_string(id) + "/runs/" + key + "/playback.js",
                            r.wall, r.tool, r.vehicle, r.path, motion);
    }
    return pathPicture(r.wall, r.tool, r.vehicle, r.path, r.wall.name + " / " + r.planner + "  " + r.status,
                       pictureLayers(r.path, r.status).layer, kGalleryOverlapStrips);
  }

 private:
  struct Db {
    std::string file;
    std::unique_ptr<ResultsDb> db;
  };
  static constexpr std::size_t kFacets = 4;
  static constexpr const char* kFacetNames[kFacets] = {"planner", "dataset", "status", "tool"};
  /// An experiment's runs as the table browses them: summaries in key order, each run's facet
  /// values as indices, metric columns read when first sorted by, and sort orders kept.
  struct Index {
    std::vector<ResultsDb::RunSummary> runs;
    std::map<std::string, std::uint32_t> position;
    std::vector<std::string> metric_names;
    std::array<std::vector<std::string>, kFacets> facet_values;
    std::array<std::vector<std::uint32_t>, kFacets> facet_of;
    std::map<std::pair<std::string, bool>, std::vector<std::uint32_t>> orders;
    MotionLimits motion;
  };

  static std::string toolText(const ToolParams& t) {
    return "s=" + shortNumber(t.tool_width) + " m, c=" + shortNumber(t.clearance) + " m";
  }

  /// The runs in the order of `column` (none: key order), runs without a value last either way.
  const std::vector<std::uint32_t>& sorted(Index& x, std::size_t db, long long id, const std::string& column, bool desc) {
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

  static std::size_t number(const std::string& text, const char* name, std::size_t fallback, std::size_t most) {
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

  Index& index(std::size_t db, long long id) {
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
      const std::string values[kFacets] = {r.planner, r.dataset, toString(r.status), toolText(r.tool)};
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

  std::vector<Db> dbs_;
  std::map<std::pair<std::size_t, long long>, Index> cache_;
  std::mutex mutex_;
};

void answerError(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json{{"error", message}}.dump() + "\n", "application/json");
}

/// Runs `handler`, answering its errors as JSON.
template <class F>
httplib::Server::Handler guarded(F handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
    } catch (const HttpError& e) {
      answerError(res, e.status, e.what());
    } catch (const InputError& e) {
      answerError(res, 400, e.what());
    } catch (const std::exception& e) {
      answerError(res, 500, std::string("internal error: ") + e.what());
    }
  };
}

}  // namespace

int serveCommand(const ServeOptions& o) {
  if (o.databases.empty()) throw InputError("serve", "database", "name at least one results.sqlite to serve");
  if (o.port < 0 || o.port > 65535) throw InputError("--port", "port", "must be from 0 to 65535, got " + std::to_string(o.port));
  Explorer explorer(o.databases);
  for (const auto& [route, file] : pageFiles())
    if (!fs::exists(file.first)) throw InputError(file.first, "serve", "the explorer's page file is missing");
  httplib::Server server;
  server.set_payload_max_length(kMaxBodyBytes);
  for (const auto& [route, file] : pageFiles()) {
    const std::string path = file.first, type = file.second;
    server.Get(route, guarded([path, type](const httplib::Request&, httplib::Response& res) { res.set_content(readFile(path), type); }));
  }
  server.Get("/api/experiments", guarded([&](const httplib::Request&, httplib::Response& res) {
    res.set_content(explorer.experiments().dump() + "\n", "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs)", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(explorer.runs(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req).dump() + "\n", "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs/([0-9a-f]{64})/(picture\.svg|playback\.js))",
             guarded([&](const httplib::Request& req, httplib::Response& res) {
               const bool playback = req.matches[4] == "playback.js";
               res.set_content(explorer.drawing(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3], playback),
                               playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
             }));
  // Anything else, and bodies over the limit: a JSON error (httplib calls this for every status
  // >= 400 left without a body).
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 413)
      answerError(res, 413, "request body: over " + std::to_string(kMaxBodyBytes) + " bytes");
    else if (res.status == 404)
      answerError(res, 404, req.path + ": no such page or API (see docs/explorer.md)");
    else
      answerError(res, res.status, req.path + ": refused (HTTP " + std::to_string(res.status) + ")");
  });
  const int port = o.port == 0 ? server.bind_to_any_port(o.host) : (server.bind_to_port(o.host, o.port) ? o.port : -1);
  if (port < 0) throw InputError("--port", "port", "cannot listen on " + o.host + ":" + std::to_string(o.port));
  std::cout << "coverbench serve: http://" << o.host << ":" << port << "/ (" << o.databases.size() << " database"
            << (o.databases.size() == 1 ? "" : "s") << "; Ctrl-C stops it)" << std::endl;
  server.listen_after_bind();
  return 0;
}

}  // namespace coverbench::cli
