// `coverbench serve`: a local web application over experiment databases (cpp-httplib). It serves
// only the databases named on its command line and its own page files, each by a fixed name: no
// part of a request reaches the file system. Errors are JSON: {"error": "one line"}.
#include <httplib.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <atomic>
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
#include "coverbench/walls_db.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/runner.hpp"
#include "workbench.hpp"

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
      {"/workbench.js", {COVERBENCH_WEB_DIR "/workbench.js", "text/javascript; charset=utf-8"}},
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
                       pictureLayers(r.path, r.status).layer, kGalleryOverlapStrips, 0, true);
  }

  /// What the run planned, as a workbench request: its wall file, planner, parameters and tool.
  json problem(std::size_t db, long long id, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    const Index& x = index(db, id);
    if (!x.position.count(key))
      throw HttpError(404, "experiment " + std::to_string(id) + " of database " + std::to_string(db) + " has no run " + key);
    const ResultsDb::StoredRun r = dbs_[db].db->storedRun(key);
    json params = json::object();
    const json stored = json::parse(r.params_json);
    for (const auto& [k, v] : stored.items()) params[k] = v.is_string() ? v.get<std::string>() : v.dump();
    return {{"wall", wallToJson(r.wall)}, {"planner", r.planner_name}, {"params", params},
            {"tool_width", r.tool.tool_width}, {"clearance", r.tool.clearance}};
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

/// Plans in a helper process forked when the server starts, before it has threads: a process
/// with threads must not fork workers (a lock another thread held at the fork stays locked in
/// the child forever), while the single-threaded helper forks each plan's worker safely
/// (executeInWorker). One plan at a time; the helper ends with the server.
class PlanHelper {
 public:
  explicit PlanHelper(double max_time_limit_s) {
    int to[2], from[2];
    if (::pipe2(to, O_CLOEXEC) != 0 || ::pipe2(from, O_CLOEXEC) != 0) throw std::runtime_error("pipe: cannot start the plan helper");
    std::fflush(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork: cannot start the plan helper");
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      ::close(to[1]);
      ::close(from[0]);
      for (;;) {
        std::string body;
        if (!readMessage(to[0], body)) ::_exit(0);
        std::string answer;
        try {
          answer = "R" + serializeRecord(planInWorker(readWorkbenchRequest(body, max_time_limit_s)));
        } catch (const InputError& e) {
          answer = std::string("I") + e.what();
        } catch (const std::exception& e) {
          answer = std::string("X") + e.what();
        }
        if (!writeMessage(from[1], answer)) ::_exit(0);
      }
    }
    ::close(to[0]);
    ::close(from[1]);
    to_ = to[1];
    from_ = from[0];
  }
  ~PlanHelper() {
    ::close(to_);
    ::close(from_);
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  RunRecord plan(const std::string& body) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string answer;
    if (!writeMessage(to_, body) || !readMessage(from_, answer) || answer.empty())
      throw std::runtime_error("the plan helper process ended");
    if (answer[0] == 'R') return deserializeRecord(answer.substr(1));
    if (answer[0] == 'I') throw HttpError(400, answer.substr(1));
    throw std::runtime_error(answer.substr(1));
  }

 private:
  static bool writeMessage(int fd, const std::string& text) {
    const std::uint64_t n = text.size();
    const std::string bytes = std::string(reinterpret_cast<const char*>(&n), sizeof n) + text;
    for (std::size_t off = 0; off < bytes.size();) {
      const ssize_t w = ::write(fd, bytes.data() + off, bytes.size() - off);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) return false;
      off += static_cast<std::size_t>(w);
    }
    return true;
  }
  static bool readAll(int fd, char* data, std::size_t size) {
    for (std::size_t off = 0; off < size;) {
      const ssize_t r = ::read(fd, data + off, size - off);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return false;
      off += static_cast<std::size_t>(r);
    }
    return true;
  }
  static bool readMessage(int fd, std::string& text) {
    std::uint64_t n = 0;
    if (!readAll(fd, reinterpret_cast<char*>(&n), sizeof n) || n > (std::uint64_t{1} << 32)) return false;
    text.assign(static_cast<std::size_t>(n), '\0');
    return readAll(fd, text.data(), text.size());
  }
  pid_t pid_ = -1;
  int to_ = -1, from_ = -1;
  std::mutex mutex_;
};

/// The workbench's side of the server: walls from the named folders and walls database, checks
/// and plans (docs/explorer.md#workbench). Plans run in worker processes, one at a time with one more waiting; the
/// last 32 are kept to draw and play.
class WorkbenchServer {
 public:
  explicit WorkbenchServer(const ServeOptions& o) : max_time_limit_s_(o.plan_time_limit_s), helper_(o.plan_time_limit_s) {
    validateTimeLimit(o.plan_time_limit_s, "--plan-time-limit", "plan_time_limit");
    for (const std::string& folder : o.wall_folders) {
      std::error_code ec;
      if (!fs::is_directory(folder, ec)) throw InputError(folder, "--walls", "is not a folder");
      std::vector<std::string> names;
      for (const auto& e : fs::directory_iterator(folder))
        if (e.is_regular_file() && e.path().extension() == ".json") names.push_back(e.path().filename().string());
      std::sort(names.begin(), names.end());
      for (const std::string& n : names) folder_walls_.push_back({folder, n});
    }
    if (!o.walls_db.empty()) walls_db_ = std::make_unique<WallsDb>(o.walls_db);
  }

  json walls() {
    json out = json::array();
    for (std::size_t i = 0; i < folder_walls_.size(); ++i)
      out.push_back({{"source", "folder"}, {"folder", folder_walls_[i].first}, {"name", folder_walls_[i].second},
                     {"url", "/api/walls/folder/" + std::to_string(i)}});
    if (walls_db_) {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const WallsDb::Entry& e : walls_db_->list())
        out.push_back({{"source", "database"}, {"file", walls_db_->file()}, {"name", e.name}, {"sha256", e.sha256},
                       {"saved_at", e.saved_at}});
    }
    return {{"walls", out}, {"walls_db", walls_db_ ? walls_db_->file() : ""}};
  }

  /// A listed wall file's text (by its position in the listing: no request names a file).
  std::string folderWall(std::size_t i) {
    if (i >= folder_walls_.size()) throw HttpError(404, "no wall file " + std::to_string(i) + " (serving " + std::to_string(folder_walls_.size()) + ")");
    return readFile((fs::path(folder_walls_[i].first) / folder_walls_[i].second).string());
  }
  std::string databaseWall(const std::string& name) {
    if (!walls_db_) throw HttpError(404, "no walls database is served (serve --walls-db FILE)");
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      return walls_db_->content(name);
    } catch (const InputError& e) {
      throw HttpError(404, e.what());
    }
  }

  /// The request checked as a plan request is: {"ok": true, ...} or {"ok": false, "error": the
  /// command line's one line}. A verdict, not a failure: answered 200 either way.
  json check(const std::string& body) {
    try {
      const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
      return {{"ok", true}, {"name", r.wall.wall.name}, {"wall", r.wall.json}, {"obstacles", r.wall.wall.obstacles.size()}};
    } catch (const InputError& e) {
      return {{"ok", false}, {"error", e.what()}};
    }
  }

  json save(const std::string& body) {
    if (!walls_db_) throw HttpError(400, "walls database: none is served (start coverbench serve with --walls-db FILE)");
    const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
    std::lock_guard<std::mutex> lock(mutex_);
    const WallsDb::Entry e = walls_db_->save(r.wall.wall);
    return {{"name", e.name}, {"sha256", e.sha256}, {"saved_at", e.saved_at}, {"file", walls_db_->file()}};
  }

  json plan(const std::string& body) {
    const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
    if (!r.planner) throw InputError("request body", "planner", "name a planner to plan with (see GET /api/planners)");
    struct Slot {
      std::atomic<int>& n;
      ~Slot() { --n; }
    };
    if (++running_ > kMaxPlansAtOnce) {
      --running_;
      throw HttpError(503, "plan: one plan is running and another is waiting; ask again when one has ended");
    }
    const Slot slot{running_};
    RunRecord rec = helper_.plan(body);
    if (rec.status == RunStatus::Timeout)
      throw HttpError(504, "time_limit_s: the plan did not finish within its time limit of " + shortNumber(r.time_limit_s) + " s (" +
                               rec.reason + ")");
    json metrics = json::object();
    for (const auto& [k, v] : rec.metrics)
      if (std::isfinite(v)) metrics[k] = v;
    json stats = json::object();
    for (const auto& [k, v] : rec.stats)
      if (std::isfinite(v)) stats[k] = v;
    std::lock_guard<std::mutex> lock(mutex_);
    const long long id = ++last_plan_;
    Planned& p = plans_[id];
    p.wall = r.wall.wall;
    p.tool = r.tool;
    p.path = rec.path;
    p.status = toString(rec.status);
    p.title = r.wall.wall.name + " / " + r.config.label + "  " + p.status;
    if (plans_.size() > kPlansKept) plans_.erase(plans_.begin());
    const std::string base = "/api/plans/" + std::to_string(id);
    json out = {{"id", id}, {"planner", r.config.label}, {"status", p.status}, {"reason", rec.reason}, {"valid", rec.valid},
                {"waypoints", rec.path.waypoints.size()}, {"plan_time_ms", rec.plan_time_ms}, {"metrics", metrics},
                {"stats", stats}, {"picture", base + "/picture.svg"}};
    if (rec.path.segments() > 0) out["playback"] = base + "/playback.js";
    return out;
  }

  std::string drawing(long long id, bool playback) {
    Planned p;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto it = plans_.find(id);
      if (it == plans_.end()) throw HttpError(404, "no plan " + std::to_string(id) + " (the last " + std::to_string(kPlansKept) + " are kept)");
      p = it->second;
    }
    if (playback) {
      if (p.path.segments() == 0) throw HttpError(404, "plan " + std::to_string(id) + " has no path to play");
      return playbackScript("/api/plans/" + std::to_string(id) + "/playback.js", p.wall, p.tool, VehicleModel{}, p.path, MotionLimits{});
    }
    return pathPicture(p.wall, p.tool, VehicleModel{}, p.path, p.title, pictureLayers(p.path, p.status).layer, kGalleryOverlapStrips, 0,
                       true);
  }

 private:
  static constexpr int kMaxPlansAtOnce = 2;  // the one the helper plans and one waiting for it
  static constexpr std::size_t kPlansKept = 32;
  struct Planned {
    Wall wall;
    ToolParams tool;
    Path path;
    std::string status, title;
  };
  double max_time_limit_s_;
  PlanHelper helper_;
  std::vector<std::pair<std::string, std::string>> folder_walls_;  // folder, file name
  std::unique_ptr<WallsDb> walls_db_;
  std::map<long long, Planned> plans_;
  long long last_plan_ = 0;
  std::atomic<int> running_{0};
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
  if (o.port < 0 || o.port > 65535) throw InputError("--port", "port", "must be from 0 to 65535, got " + std::to_string(o.port));
  Explorer explorer(o.databases);
  WorkbenchServer workbench(o);
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
  server.Get("/api/experiments/(\\d{1,6})/(\\d{1,12})/runs/([0-9a-f]{64})/problem", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(explorer.problem(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3]).dump() + "\n",
                    "application/json");
  }));
  server.Get("/api/planners", guarded([&](const httplib::Request&, httplib::Response& res) {
    res.set_content(plannersJson().dump() + "\n", "application/json");
  }));
  server.Get("/api/walls", guarded([&](const httplib::Request&, httplib::Response& res) {
    res.set_content(workbench.walls().dump() + "\n", "application/json");
  }));
  server.Get(R"(/api/walls/folder/(\d{1,9}))", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.folderWall(std::stoul(req.matches[1])), "application/json");
  }));
  server.Get(R"(/api/walls/db/(.{1,1000}))", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.databaseWall(req.matches[1]), "application/json");
  }));
  server.Post("/api/check", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.check(req.body).dump() + "\n", "application/json");
  }));
  server.Post("/api/walls", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.save(req.body).dump() + "\n", "application/json");
  }));
  server.Post("/api/plan", guarded([&](const httplib::Request& req, httplib::Response& res) {
    res.set_content(workbench.plan(req.body).dump() + "\n", "application/json");
  }));
  server.Get(R"(/api/plans/(\d{1,12})/(picture\.svg|playback\.js))", guarded([&](const httplib::Request& req, httplib::Response& res) {
    const bool playback = req.matches[2] == "playback.js";
    res.set_content(workbench.drawing(std::stoll(req.matches[1]), playback), playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
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
