// `coverbench serve`: a local web application over experiment databases (cpp-httplib). It serves
// only the databases named on its command line and its own page files, each by a fixed name: no
// part of a request reaches the file system. Errors are JSON: {"error": "one line"}.
#include <httplib.h>

#include <algorithm>
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
    const Loaded& l = loaded(db, id);
    auto param = [&](const char* name) { return req.has_param(name) ? req.get_param_value(name) : std::string(); };
    const std::string planner = param("planner"), dataset = param("dataset"), status = param("status"), sort = param("sort");
    const std::string order = param("order").empty() ? "asc" : param("order");
    if (order != "asc" && order != "desc") throw HttpError(400, "order: must be asc or desc, got '" + order + "'");
    const std::size_t offset = number(param("offset"), "offset", 0, 1u << 30);
    const std::size_t limit = number(param("limit"), "limit", 100, kMaxRunsPerPage);
    const auto& m = l.results.metric_order;
    const bool by_metric = std::find(m.begin(), m.end(), sort) != m.end();
    if (!sort.empty() && !by_metric && sort != "wall_name" && sort != "planner" && sort != "dataset" && sort != "status")
      throw HttpError(400, "sort: unknown column '" + sort + "' (a metric, wall_name, planner, dataset or status)");
    std::vector<const ResultRow*> rows;
    json facets = {{"planner", json::array()}, {"dataset", json::array()}, {"status", json::array()}};
    std::map<std::string, std::set<std::string>> seen;
    for (const ResultRow& r : l.results.runs) {
      const std::string st = toString(r.status);
      for (const auto& [k, v] : {std::pair<std::string, std::string>{"planner", r.planner}, {"dataset", r.dataset}, {"status", st}})
        if (seen[k].insert(v).second) facets[k].push_back(v);
      if ((planner.empty() || r.planner == planner) && (dataset.empty() || r.dataset == dataset) && (status.empty() || st == status))
        rows.push_back(&r);
    }
    auto text = [&](const ResultRow* r) -> std::string {
      return sort == "planner" ? r->planner : sort == "dataset" ? r->dataset : sort == "status" ? toString(r->status) : r->wall_name;
    };
    if (!sort.empty())
      std::stable_sort(rows.begin(), rows.end(), [&](const ResultRow* a, const ResultRow* b) {
        if (!by_metric) return order == "asc" ? text(a) < text(b) : text(b) < text(a);
        const auto va = a->metrics.find(sort), vb = b->metrics.find(sort);
        const bool ha = va != a->metrics.end() && std::isfinite(va->second), hb = vb != b->metrics.end() && std::isfinite(vb->second);
        if (ha != hb) return ha;  // runs without the metric last, in either order
        if (!ha) return false;
        return order == "asc" ? va->second < vb->second : vb->second < va->second;
      });
    json out = json::array();
    for (std::size_t i = offset; i < rows.size() && i < offset + limit; ++i) {
      const ResultRow& r = *rows[i];
      json metrics = json::object();
      for (const auto& [k, v] : r.metrics)
        if (std::isfinite(v)) metrics[k] = v;
      out.push_back({{"key", r.key}, {"planner", r.planner}, {"dataset", r.dataset}, {"wall", r.wall}, {"wall_name", r.wall_name},
                     {"status", toString(r.status)}, {"tool_width", r.tool.tool_width}, {"metrics", metrics}});
    }
    return {{"total", rows.size()}, {"offset", offset}, {"metrics", m}, {"facets", facets}, {"runs", out}};
  }

  /// The run's picture, or the script that plays it back under the experiment's time model.
  std::string drawing(std::size_t db, long long id, const std::string& key, bool playback) {
    std::lock_guard<std::mutex> lock(mutex_);
    const Loaded& l = loaded(db, id);
    if (std::none_of(l.results.runs.begin(), l.results.runs.end(), [&](const ResultRow& r) { return r.key == key; }))
      throw HttpError(404, "experiment " + std::to_string(id) + " of database " + std::to_string(db) + " has no run " + key);
    const ResultsDb::StoredRun r = dbs_[db].db->storedRun(key);
    if (playback) {
      if (r.path.segments() == 0) throw HttpError(404, "run " + key + " has no path to play");
      return playbackScript("/api/experiments/" + std::to_string(db) + "/" + std::to_string(id) + "/runs/" + key + "/playback.js",
                            r.wall, r.tool, r.vehicle, r.path, l.motion);
    }
    return pathPicture(r.wall, r.tool, r.vehicle, r.path, r.wall.name + " / " + r.planner + "  " + r.status,
                       pictureLayers(r.path, r.status).layer, kGalleryOverlapStrips);
  }

 private:
  struct Db {
    std::string file;
    std::unique_ptr<ResultsDb> db;
  };
  struct Loaded {
    ResultSet results;
    MotionLimits motion;
  };

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

  const Loaded& loaded(std::size_t db, long long id) {
    if (db >= dbs_.size()) throw HttpError(404, "no database " + std::to_string(db) + " (serving " + std::to_string(dbs_.size()) + ")");
    const auto k = std::make_pair(db, id);
    auto it = cache_.find(k);
    if (it != cache_.end()) return it->second;
    const auto ids = dbs_[db].db->experiments();
    if (std::none_of(ids.begin(), ids.end(), [&](const ResultsDb::ExperimentEntry& e) { return e.id == id; }))
      throw HttpError(404, dbs_[db].file + ": no experiment " + std::to_string(id));
    Loaded l;
    l.results = dbs_[db].db->load(id);
    const ExperimentRecord record = dbs_[db].db->record(id);
    l.motion = configMotion(record.config_text, dbs_[db].file + ": experiments.config_text");
    return cache_.emplace(k, std::move(l)).first->second;
  }

  std::vector<Db> dbs_;
  std::map<std::pair<std::size_t, long long>, Loaded> cache_;
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
