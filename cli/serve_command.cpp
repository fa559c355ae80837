// `coverbench serve`: a local web application over experiment databases (cpp-httplib). Built into
// the plug-in libcoverbench_serve.so (serve_plugin.cpp), so only `serve` loads httplib and OpenSSL.
// It serves
// only the databases named on its command line and its own page files, each by a fixed name: no
// part of a request reaches the file system. Errors are JSON: {"error": "one line"}.
#include <httplib.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

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
#include "serve.hpp"
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
/// A request body's bytes: a wall file the workbench saves or plans, its settings around it.
constexpr std::size_t kMaxBodyBytes = 1 << 20;
/// POST /api/check's body may be larger: a wall of 10^6 vertices is about 30 MB of JSON and its
/// check takes seconds (docs/explorer.md has the figures). At most kLargeBodiesAtOnce such bodies
/// are read at once (each is held whole, and parsed), so memory stays bounded (measured: 1.4 GB
/// for two 50 MB bodies at once).
constexpr std::size_t kMaxCheckBodyBytes = 64u << 20;
constexpr int kLargeBodiesAtOnce = 2;
constexpr std::size_t kMaxSavedNameBytes = 1000;  // what GET /api/walls/db/NAME takes
/// A request's line, headers and body must all arrive within this many seconds of its first
/// byte; then the connection is answered 408 and closed (a slow client holds no thread longer).
constexpr int kRequestReadSeconds = 10;
/// Connections served at once (threads); more wait for one of them.
constexpr std::size_t kConnectionThreads = 64;
/// A request's line and headers together, and the room a chunked body's framing may take beyond
/// its body limit: what is read past these is refused, however the body is framed.
constexpr std::size_t kMaxHeadBytes = 256 << 10;

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

  /// A run of an experiment, by its key (404 when the experiment has none). Under mutex_.
  ResultsDb::StoredRun storedRun(std::size_t db, long long id, const std::string& key) {
    if (!index(db, id).position.count(key))
      throw HttpError(404, "experiment " + std::to_string(id) + " of database " + std::to_string(db) + " has no run " + key);
    return dbs_[db].db->storedRun(key);
  }

  /// What the run planned, as a workbench request: its wall file, planner, parameters and tool.
  json problem(std::size_t db, long long id, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ResultsDb::StoredRun r = storedRun(db, id, key);
    json params = json::object();
    const json stored = json::parse(r.params_json);
    for (const auto& [k, v] : stored.items()) params[k] = v.is_string() ? v.get<std::string>() : v.dump();
    return {{"wall", wallToJson(r.wall)}, {"planner", r.planner_name}, {"params", params},
            {"tool_width", r.tool.tool_width}, {"clearance", r.tool.clearance}};
  }

  /// How the run ended, in words: its status, reason and the end of an external planner's stderr
  /// (kept for crash, error and invalid_output; valid UTF-8 as stored), with the wall and tool.
  json outcome(std::size_t db, long long id, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ResultsDb::StoredRun r = storedRun(db, id, key);
    return {{"status", r.status}, {"reason", r.reason}, {"stderr_tail", r.stderr_tail}, {"wall_name", r.wall.name},
            {"planner", r.planner}, {"tool_width", r.tool.tool_width}, {"clearance", r.tool.clearance}};
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

  std::vector<Db> dbs_;
  std::map<std::pair<std::size_t, long long>, Index> cache_;
  std::mutex mutex_;
};

/// Plans in a helper process of its own: the server has threads, and a process with threads must
/// not fork workers (a lock another thread held at the fork stays locked in the child forever),
/// so the helper is a fresh process (this executable run with kPlanHelperArgument), which forks
/// each plan's worker safely (executeInWorker). One plan at a time. A helper that ends, or that
/// does not answer by its plan's deadline, is killed with everything it started and started
/// again for the next plan; the helper ends with the server (its parent-death signal, and the
/// end of its input).
class PlanHelper {
 public:
  PlanHelper(std::string exe, double max_time_limit_s) : exe_(std::move(exe)), max_time_limit_s_(max_time_limit_s) { start(); }
  ~PlanHelper() { stop(); }

  /// The plan's record, within `deadline`; throws HttpError 504 when the helper did not answer
  /// by then (it is restarted), 500 when it ended (restarted too), 400 for a refused request.
  RunRecord plan(const std::string& body, std::chrono::steady_clock::time_point deadline) {
    std::unique_lock<std::timed_mutex> lock(mutex_, std::defer_lock);
    if (!lock.try_lock_until(deadline))
      throw HttpError(503, "plan: another plan held the planner past this one's deadline; ask again");
    // A helper that has ended (killed, or a crash) since the last plan is started again first.
    if (pid_ >= 0 && ::waitpid(pid_, nullptr, WNOHANG) == pid_) forget();
    if (pid_ < 0) start();
    std::string answer;
    bool timed_out = false;
    if (!writeMessage(to_, body) || !readMessage(from_, answer, &deadline, &timed_out) || answer.empty()) {
      stop();  // the next plan starts a new helper
      if (timed_out) throw HttpError(504, "plan: no answer by the plan's deadline; its process was ended");
      throw std::runtime_error("the plan helper process ended while planning (it is started again for the next plan)");
    }
    if (answer[0] == 'R') return deserializeRecord(answer.substr(1));
    if (answer[0] == 'I') throw HttpError(400, answer.substr(1));
    throw std::runtime_error(answer.substr(1));
  }

 private:
  void start() {
    int to[2], from[2];
    if (::pipe2(to, O_CLOEXEC) != 0) throw std::runtime_error("pipe: cannot start the plan helper");
    if (::pipe2(from, O_CLOEXEC) != 0) {
      ::close(to[0]), ::close(to[1]);
      throw std::runtime_error("pipe: cannot start the plan helper");
    }
    const std::string limit = shortNumber(max_time_limit_s_);
    const char* argv[] = {exe_.c_str(), kPlanHelperArgument, limit.c_str(), nullptr};
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
      // Only async-signal-safe calls between fork and exec (the server has threads).
      ::setpgid(0, 0);  // its own group: a helper that misses its deadline is ended with its workers
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(127);
      // Onto fds 3 and 4 by way of fds above them, so neither dup2 is onto itself (which would
      // keep close-on-exec) or onto the other's source.
      const int in = ::fcntl(to[0], F_DUPFD, 10), out = ::fcntl(from[1], F_DUPFD, 10);
      if (in < 0 || out < 0 || ::dup2(in, 3) < 0 || ::dup2(out, 4) < 0) ::_exit(127);
      ::execv(argv[0], const_cast<char* const*>(argv));
      ::_exit(127);
    }
    ::close(to[0]);
    ::close(from[1]);
    if (pid < 0) {
      ::close(to[1]), ::close(from[0]);
      throw std::runtime_error("fork: cannot start the plan helper");
    }
    ::setpgid(pid, pid);  // also here: whichever runs first
    pid_ = pid, to_ = to[1], from_ = from[0];
  }
  void stop() {
    if (pid_ < 0) return;
    ::kill(-pid_, SIGKILL);  // the helper and the workers it forked
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    forget();
  }
  /// After the helper was reaped: its pipes closed (its workers end by their parent-death signal).
  void forget() {
    ::close(to_);
    ::close(from_);
    pid_ = -1, to_ = -1, from_ = -1;
  }

  std::string exe_;
  double max_time_limit_s_;
  pid_t pid_ = -1;
  int to_ = -1, from_ = -1;
  std::timed_mutex mutex_;
};

/// At most `most` holders at once; the rest are refused (503), not queued: a check or save of a
/// large wall is CPU work, and the machine's cores are the bound.
class Gate {
 public:
  explicit Gate(int most) : most_(most) {}
  struct Pass {
    std::atomic<int>* n;
    ~Pass() { --*n; }
  };
  Pass enter(const char* what) {
    if (++n_ > most_) {
      --n_;
      throw HttpError(503, std::string(what) + ": " + std::to_string(most_) + " are being worked on; ask again when one has ended");
    }
    return Pass{&n_};
  }

 private:
  int most_;
  std::atomic<int> n_{0};
};

/// A walls database's own failure (locked, unwritable, corrupt) is the server's, not the
/// request's: 503 with the reason. Other refusals keep `status`.
[[noreturn]] void rethrowWallsDbError(const InputError& e, int status) {
  if (e.field() == "(database)") throw HttpError(503, std::string("walls database: ") + e.what());
  throw HttpError(status, e.what());
}

/// The workbench's side of the server: walls from the named folders and walls database, checks
/// and plans (docs/explorer.md#workbench). Plans run in worker processes, one at a time with one more waiting; the
/// last 32 are kept to draw and play.
class WorkbenchServer {
 public:
  WorkbenchServer(const ServeOptions& o, const std::string& helper_exe)
      : max_time_limit_s_(o.plan_time_limit_s), helper_((validateTimeLimit(o.plan_time_limit_s, "--plan-time-limit", "plan_time_limit"),
                                                         helper_exe),
                                                        o.plan_time_limit_s) {
    for (const std::string& folder : o.wall_folders) {
      std::error_code ec;
      if (!fs::is_directory(folder, ec)) throw InputError(folder, "--walls", "is not a folder");
      // The folder is held open: each file is opened in it by name, without following links.
      const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (dir < 0) throw InputError(folder, "--walls", std::string("cannot be opened: ") + std::strerror(errno));
      folders_.push_back({folder, dir});
      std::vector<std::string> names;
      for (const auto& e : fs::directory_iterator(folder, ec)) {
        std::error_code sec;
        // Regular files only: a link (to /etc/passwd, or out of the folder), a FIFO or a device is not listed.
        if (e.symlink_status(sec).type() == fs::file_type::regular && e.path().extension() == ".json")
          names.push_back(e.path().filename().string());
      }
      if (ec) throw InputError(folder, "--walls", "cannot be listed: " + ec.message());
      std::sort(names.begin(), names.end());
      for (const std::string& n : names) folder_walls_.push_back({folders_.size() - 1, n});
    }
    if (!o.walls_db.empty()) walls_db_ = std::make_unique<WallsDb>(o.walls_db);
  }
  ~WorkbenchServer() {
    for (const auto& f : folders_) ::close(f.second);
  }

  json walls() {
    json out = json::array();
    for (std::size_t i = 0; i < folder_walls_.size(); ++i)
      out.push_back({{"source", "folder"}, {"folder", folders_[folder_walls_[i].first].first}, {"name", folder_walls_[i].second},
                     {"url", "/api/walls/folder/" + std::to_string(i)}});
    if (walls_db_) {
      std::lock_guard<std::mutex> lock(mutex_);
      try {
        for (const WallsDb::Entry& e : walls_db_->list())
          out.push_back({{"source", "database"}, {"file", walls_db_->file()}, {"name", e.name}, {"sha256", e.sha256},
                         {"saved_at", e.saved_at}});
      } catch (const InputError& e) {
        rethrowWallsDbError(e, 500);
      }
    }
    return {{"walls", out}, {"walls_db", walls_db_ ? walls_db_->file() : ""}};
  }

  /// A listed wall file's text (by its position in the listing: no request names a file). It is
  /// opened in its folder without following a link and must still be a regular file of at most
  /// the body limit that parses as a wall: a file swapped for a link or a FIFO since the listing is
  /// refused, never followed or waited on.
  std::string folderWall(std::size_t i) {
    if (i >= folder_walls_.size()) throw HttpError(404, "no wall file " + std::to_string(i) + " (serving " + std::to_string(folder_walls_.size()) + ")");
    const auto& [folder, name] = folder_walls_[i];
    const std::string shown = (fs::path(folders_[folder].first) / name).string();
    const int fd = ::openat(folders_[folder].second, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0)
      throw HttpError(404, shown + ": cannot be opened as a regular file of the folder (" +
                               (errno == ELOOP ? std::string("it is now a link") : std::string(std::strerror(errno))) + ")");
    struct Closer {
      int fd;
      ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) throw HttpError(404, shown + ": is no longer a regular file");
    if (static_cast<std::uint64_t>(st.st_size) > kMaxBodyBytes)
      throw HttpError(413, shown + ": over " + std::to_string(kMaxBodyBytes) + " bytes, the most a wall the workbench opens may have");
    std::string text(static_cast<std::size_t>(st.st_size) + 1, '\0');  // one more: a file that grew is seen
    std::size_t got = 0;
    while (got < text.size()) {
      const ssize_t r = ::read(fd, text.data() + got, text.size() - got);
      if (r < 0 && errno == EINTR) continue;
      if (r < 0) throw HttpError(500, shown + ": read error: " + std::strerror(errno));
      if (r == 0) break;
      got += static_cast<std::size_t>(r);
    }
    if (got > static_cast<std::size_t>(st.st_size)) throw HttpError(409, shown + ": changed while read; ask again");
    text.resize(got);
    try {
      const Gate::Pass pass = checks_.enter("wall checks");
      parseWallJson(text, shown);
    } catch (const InputError& e) {
      throw HttpError(422, e.what());
    }
    return text;
  }
  std::string databaseWall(const std::string& name) {
    if (!walls_db_) throw HttpError(404, "no walls database is served (serve --walls-db FILE)");
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      return walls_db_->content(name);
    } catch (const InputError& e) {
      rethrowWallsDbError(e, 404);
    }
  }

  /// The request checked as a plan request is: {"ok": true, ...} or {"ok": false, "error": the
  /// command line's one line}. A verdict, not a failure: answered 200 either way.
  json check(const std::string& body) {
    const Gate::Pass pass = checks_.enter("wall checks");
    try {
      const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
      return {{"ok", true}, {"name", r.wall.wall.name}, {"wall", r.wall.json}, {"obstacles", r.wall.wall.obstacles.size()}};
    } catch (const InputError& e) {
      return {{"ok", false}, {"error", e.what()}};
    }
  }

  json save(const std::string& body) {
    if (!walls_db_) throw HttpError(400, "walls database: none is served (start coverbench serve with --walls-db FILE)");
    const Gate::Pass pass = checks_.enter("wall checks");
    const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
    checkSavedName(r.wall.wall.name);
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      const WallsDb::Entry e = walls_db_->save(r.wall.wall);
      return {{"name", e.name}, {"sha256", e.sha256}, {"saved_at", e.saved_at}, {"file", walls_db_->file()}};
    } catch (const InputError& e) {
      rethrowWallsDbError(e, 400);
    }
  }

  json plan(const std::string& body) {
    const auto received = std::chrono::steady_clock::now();
    WorkbenchRequest r;
    {
      const Gate::Pass pass = checks_.enter("wall checks");
      r = readWorkbenchRequest(body, max_time_limit_s_);
    }
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
    // The answer's deadline (docs/explorer.md): the worker's hard deadline (twice the limit plus
    // 5 s) and 5 s for the helper to read the request and score the path.
    const auto deadline = received + std::chrono::milliseconds(static_cast<long long>((2 * r.time_limit_s + 10) * 1000));
    if (std::chrono::steady_clock::now() >= deadline)
      throw HttpError(504, "plan: reading the request's wall took past the plan's deadline (twice its time limit plus 10 s)");
    RunRecord rec = helper_.plan(body, deadline);
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

  /// A name the walls database can give back through GET /api/walls/db/NAME: 1 to 1000 bytes,
  /// no control characters (a newline, a NUL), so a saved wall can always be read back.
  static void checkSavedName(const std::string& name) {
    if (name.empty()) throw InputError("request body", "wall.name", "a saved wall needs a name (it is how it is opened again)");
    if (name.size() > kMaxSavedNameBytes)
      throw InputError("request body", "wall.name",
                       "is " + std::to_string(name.size()) + " bytes; a saved wall's name has at most " + std::to_string(kMaxSavedNameBytes));
    for (const unsigned char c : name)
      if (c < 0x20 || c == 0x7f) throw InputError("request body", "wall.name", "has a control character (a newline, a tab, a NUL); a saved wall's name may not");
  }

  double max_time_limit_s_;
  PlanHelper helper_;
  std::vector<std::pair<std::string, int>> folders_;                 // --walls folder, its open descriptor
  std::vector<std::pair<std::size_t, std::string>> folder_walls_;  // folder's index, file name
  std::unique_ptr<WallsDb> walls_db_;
  std::map<long long, Planned> plans_;
  long long last_plan_ = 0;
  std::atomic<int> running_{0};
  Gate checks_{2};
  std::mutex mutex_;
};

/// JSON text whatever the strings hold: bytes that are not UTF-8 (a path, a file name, a wall's
/// name) become U+FFFD instead of ending the process with nlohmann's type_error.
std::string jsonText(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace) + "\n"; }

void answerError(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(jsonText(json{{"error", message}}), "application/json");
}

/// What a request's headers say of its body, refused before any of it is read: a length that is
/// no number, two lengths, a length and chunks, a body of no stated length (httplib would read it
/// to the connection's end) or one over its route's limit. `status` 0: nothing refused.
struct Refusal {
  int status = 0;
  std::string message;
};

/// Bodies over kMaxBodyBytes being read now (POST /api/check only), at most kLargeBodiesAtOnce.
std::atomic<int> large_bodies{0};

/// One request's bytes from its socket: each read waits at most until the request's deadline,
/// so a client that sends a header line every few seconds cannot hold its thread past it.
class DeadlineStream final : public httplib::Stream {
 public:
  explicit DeadlineStream(int sock) : sock_(sock) {}
  ~DeadlineStream() override { endRequest(); }
  void startRequest() {
    deadline_ = std::chrono::steady_clock::now() + std::chrono::seconds(kRequestReadSeconds);
    timed_out_ = false;
    readTimedOut() = false;
    malformed() = false;
    tooLarge() = false;
    refusal() = Refusal{};
    bodyLimit() = kMaxBodyBytes;
    written_ = 0;
    read_ = 0;
    cap_ = kMaxHeadBytes;
    framed_ = folded_ = false;
    line_start_ = false;
  }
  /// Gives back the large body's place, if this request had one.
  void endRequest() {
    if (large_) large_bodies.fetch_sub(1);
    large_ = false;
  }
  /// Reads the request's headers for its body's framing and limit (called once they are read,
  /// before the body is): the bytes it may still read are its body limit and the framing's room.
  void frameBody(const httplib::Request& req) {
    framed_ = true;
    const bool check = req.method == "POST" && req.path == "/api/check";
    const std::size_t limit = check ? kMaxCheckBodyBytes : kMaxBodyBytes;
    bodyLimit() = limit;
    cap_ = read_ + limit + kMaxHeadBytes;
    const bool has_body = req.method == "POST" || req.method == "PUT" || req.method == "PATCH" || req.method == "DELETE" ||
                          req.method == "PRI";  // the methods whose body httplib reads
    // Headers a proxy in front could read otherwise: a folded line (httplib drops it), a name
    // with white space or a control byte ("Transfer-Encoding : chunked"), two Hosts, two
    // Transfer-Encodings.
    if (folded_) return refuse(400, "a header line starts with white space (a folded header line)");
    for (const auto& [name, value] : req.headers)
      if (name.empty() || name.find_first_of(" \t\r\n\v\f:") != std::string::npos ||
          std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        return refuse(400, "a header's name holds white space or a control byte");
    if (req.headers.count("Host") > 1) return refuse(400, "Host: given twice");
    if (req.headers.count("Transfer-Encoding") > 1) return refuse(400, "Transfer-Encoding: given twice");
    std::string length;
    const auto [first, last] = req.headers.equal_range("Content-Length");
    for (auto it = first; it != last; ++it) {
      const std::string& v = it->second;
      if (v.empty() || v.size() > 18 || v.find_first_not_of("0123456789") != std::string::npos)
        return refuse(400, "Content-Length: must be a whole number of bytes, got '" + v.substr(0, 40) + "'");
      if (!length.empty() && v != length) return refuse(400, "Content-Length: given twice, as " + length + " and " + v);
      length = v;
    }
    const bool chunked = req.has_header("Transfer-Encoding");
    if (chunked && req.get_header_value("Transfer-Encoding") != "chunked")
      return refuse(400, "Transfer-Encoding: only chunked is read, got '" + req.get_header_value("Transfer-Encoding").substr(0, 40) + "'");
    if (chunked && !length.empty()) return refuse(400, "Transfer-Encoding and Content-Length: a request gives one or the other");
    if (!has_body) {
      if (chunked || (!length.empty() && std::stoull(length) > 0))
        return refuse(400, req.method.substr(0, 10) + ": takes no body");
      return;
    }
    if (!chunked && length.empty()) return refuse(411, "Content-Length: a request with a body must give its length (or be chunked)");
    const std::uint64_t n = chunked ? 0 : std::stoull(length);
    if (n > limit) return refuse(413, tooLargeMessage(n));
    if (n > kMaxBodyBytes || (chunked && limit > kMaxBodyBytes)) {
      if (large_bodies.fetch_add(1) >= kLargeBodiesAtOnce) {
        large_bodies.fetch_sub(1);
        return refuse(503, "request body: " + std::to_string(kLargeBodiesAtOnce) +
                               " bodies over " + std::to_string(kMaxBodyBytes) + " bytes are being read; try again");
      }
      large_ = true;
    }
  }
  /// The answer to a body over this request's limit, of `n` bytes (0: not known).
  static std::string tooLargeMessage(std::uint64_t n) {
    return "request body: " + (n > 0 ? std::to_string(n) + " bytes, " : std::string()) + "over the " + std::to_string(bodyLimit()) +
           " bytes this request takes" + (bodyLimit() == kMaxBodyBytes ? " (POST /api/check takes " + std::to_string(kMaxCheckBodyBytes) + ")" : "");
  }
  /// This thread's request refused by its headers (status 0: not refused).
  static Refusal& refusal() {
    thread_local Refusal r;
    return r;
  }
  /// The body limit of this thread's request.
  static std::size_t& bodyLimit() {
    thread_local std::size_t limit = kMaxBodyBytes;
    return limit;
  }
  std::size_t written() const { return written_; }
  bool timedOut() const { return timed_out_; }

  bool is_readable() const override { return wait(POLLIN, remainingMs()); }
  /// Whether this thread's request just passed its read deadline (the error handler answers 408).
  static bool& readTimedOut() {
    thread_local bool timed_out = false;
    return timed_out;
  }
  /// Whether this thread's request went past the bytes a request may have (a chunked body, which
  /// httplib 0.11 reads without its payload limit): the error handler answers 413.
  static bool& tooLarge() {
    thread_local bool too_large = false;
    return too_large;
  }
  /// Whether httplib refused this thread's request before any route saw it (a malformed request
  /// line or header): what follows on the connection cannot be trusted to start a request, so
  /// the connection is closed after the answer.
  static bool& malformed() {
    thread_local bool refused = false;
    return refused;
  }
  bool is_writable() const override { return wait(POLLOUT, kWriteMs); }
  /// Bytes from a buffer of 64 KiB filled by one recv at a time: httplib reads a request's line
  /// and headers a byte at a time (a 200 KB request line was 400,000 system calls).
  ssize_t read(char* ptr, size_t size) override {
    if (read_ >= cap_) {
      if (refusal().status == 0) tooLarge() = true;
      return -1;
    }
    size = std::min(size, cap_ - read_);
    if (begin_ == end_) {
      if (!wait(POLLIN, remainingMs())) {
        if (remainingMs() <= 0) timed_out_ = readTimedOut() = true;
        return -1;
      }
      ssize_t r;
      do r = ::recv(sock_, buffer_.data(), buffer_.size(), 0);
      while (r < 0 && errno == EINTR);
      if (r <= 0) return r;
      begin_ = 0, end_ = static_cast<std::size_t>(r);
    }
    const std::size_t n = std::min(size, end_ - begin_);
    std::memcpy(ptr, buffer_.data() + begin_, n);
    if (!framed_)  // the line and headers (httplib reads them a byte at a time): a folded line?
      for (std::size_t i = 0; i < n; ++i) {
        const char c = ptr[i];
        if (line_start_ && (c == ' ' || c == '\t')) folded_ = true;
        line_start_ = c == '\n';
      }
    begin_ += n;
    read_ += n;
    return static_cast<ssize_t>(n);
  }
  /// Bytes received and not yet read (the start of a pipelined next request).
  bool buffered() const { return begin_ != end_; }
  ssize_t write(const char* ptr, size_t size) override {
    if (!wait(POLLOUT, kWriteMs)) return -1;
    for (;;) {
      const ssize_t w = ::send(sock_, ptr, size, MSG_NOSIGNAL);
      if (w < 0 && errno == EINTR) continue;
      if (w > 0) written_ += static_cast<std::size_t>(w);
      return w;
    }
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(::getpeername, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(::getsockname, ip, port); }
  socket_t socket() const override { return sock_; }

 private:
  static constexpr int kWriteMs = 5000;
  /// Refuses the request: no byte of its body is read (httplib's read fails at once) and the
  /// answer is the refusal's; the connection is closed after it.
  void refuse(int status, std::string message) {
    refusal() = Refusal{status, std::move(message)};
    cap_ = read_;
  }
  long long remainingMs() const {
    return std::chrono::duration_cast<std::chrono::milliseconds>(deadline_ - std::chrono::steady_clock::now()).count();
  }
  bool wait(short events, long long ms) const {
    for (;;) {
      if (ms <= 0) return false;
      pollfd p{sock_, events, 0};
      const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(ms, 60000)));
      if (r < 0 && errno == EINTR) {
        ms = events == POLLIN ? remainingMs() : ms;
        continue;
      }
      return r > 0;
    }
  }
  template <class F>
  void address(F get, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t n = sizeof a;
    ip.clear();
    port = 0;
    if (get(sock_, reinterpret_cast<sockaddr*>(&a), &n) != 0) return;
    char text[INET6_ADDRSTRLEN] = {};
    if (a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
      port = ntohs(v4->sin_port);
    } else if (a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
      port = ntohs(v6->sin6_port);
    }
    ip = text;
  }

  int sock_;
  std::chrono::steady_clock::time_point deadline_{};
  mutable bool timed_out_ = false;
  std::size_t written_ = 0;
  std::size_t read_ = 0;
  std::size_t cap_ = kMaxHeadBytes;  ///< the bytes this request may read in all
  bool large_ = false;               ///< it holds one of the large bodies' places
  bool framed_ = false;              ///< its headers are read (frameBody was called)
  bool folded_ = false;              ///< a header line started with white space
  bool line_start_ = false;          ///< the last byte read ended a line
  std::array<char, 65536> buffer_{};
  std::size_t begin_ = 0, end_ = 0;
};

std::string readDeadlineMessage() {
  return "request: not read whole within " + std::to_string(kRequestReadSeconds) + " s of its first byte; the connection is closed";
}

/// httplib's server with each request's reading bounded in time (DeadlineStream) and keep-alive
/// connections served the same way (httplib's SSLServer overrides the same function).
class DeadlineServer final : public httplib::Server {
 private:
  /// A lingering close after a refusal: what the client still sends is read and dropped for up
  /// to 1 s (and 8 MiB), so the answer is not lost to a reset.
  static void linger(int sock) {
    ::shutdown(sock, SHUT_WR);
    char scratch[65536];
    std::size_t dropped = 0;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (dropped < (8u << 20)) {
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now()).count();
      pollfd q{sock, POLLIN, 0};
      if (ms <= 0 || ::poll(&q, 1, static_cast<int>(ms)) <= 0) break;
      const ssize_t r = ::recv(sock, scratch, sizeof scratch, 0);
      if (r <= 0) break;
      dropped += static_cast<std::size_t>(r);
    }
  }

  bool process_and_close_socket(socket_t sock) override {
    DeadlineStream stream(sock);
    bool ok = false;
    for (std::size_t left = keep_alive_max_count_; left > 0 && svr_sock_ != INVALID_SOCKET; --left) {
      // Between requests: wait for the next one's first byte up to the keep-alive timeout
      // (unless it is here already, read with the last one).
      if (!stream.buffered()) {
        pollfd p{sock, POLLIN, 0};
        int ready = 0;
        do ready = ::poll(&p, 1, static_cast<int>(keep_alive_timeout_sec_ * 1000));
        while (ready < 0 && errno == EINTR);
        if (ready <= 0) break;
        char probe;
        if (::recv(sock, &probe, 1, MSG_PEEK | MSG_DONTWAIT) <= 0) break;  // closed by the client
      }
      stream.startRequest();
      bool closed = false;
      // No Range: answers are whole (httplib cut JSON answers at a Range header, and answered an
      // unsatisfiable one with an empty 416).
      ok = process_request(stream, left == 1, closed, [&stream](httplib::Request& req) {
        req.ranges.clear();
        req.headers.erase("Range");
        stream.frameBody(req);
      });
      stream.endRequest();
      if (stream.timedOut()) {
        // httplib answers a request cut off in its headers or body itself (through the error
        // handler, as 408); one cut off in its first line gets no answer from it: this one.
        if (stream.written() == 0) {
          const std::string body = jsonText(json{{"error", readDeadlineMessage()}});
          const std::string head = "HTTP/1.1 408 Request Timeout\r\nContent-Type: application/json\r\nContent-Length: " +
                                   std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n";
          stream.write((head + body).data(), head.size() + body.size());
        }
        linger(sock);
        break;
      }
      if (DeadlineStream::malformed() || DeadlineStream::tooLarge() || DeadlineStream::refusal().status != 0) {
        linger(sock);
        break;
      }
      if (!ok || closed) break;
    }
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
    return ok;
  }
};

/// The names a request's Host header may give for this server (DNS rebinding: a page on another
/// name that resolves to this address is refused), and the request checks that go with them.
class HostCheck {
 public:
  HostCheck(const std::string& host, int port) : port_(port) {
    const std::string p = ":" + std::to_string(port);
    auto add = [&](const std::string& name) {
      names_.insert(name + p);
      if (port == 80) names_.insert(name);
    };
    any_ = host == "0.0.0.0" || host == "::" || host.empty();
    add(host.find(':') != std::string::npos ? "[" + host + "]" : host);
    if (any_ || isLoopback(host)) {
      add("localhost"), add("127.0.0.1"), add("[::1]");
    }
    char name[256] = {};
    if (any_ && ::gethostname(name, sizeof name - 1) == 0) add(name);
  }

  static bool isLoopback(const std::string& host) {
    return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
  }

  /// Throws HttpError 403 for a request this server must not answer: a Host it is not, or a
  /// state-changing request from another origin (a page elsewhere posting through the user's
  /// browser) or in a form a page elsewhere may send without asking (not application/json).
  void check(const httplib::Request& req) const {
    const std::string host = req.get_header_value("Host");
    if (!allowedHost(host))
      throw HttpError(403, "Host: '" + host + "' is not a name this server answers to (it serves " + *names_.begin() + " and the like)");
    if (req.method == "GET" || req.method == "HEAD") return;
    const std::string origin = req.get_header_value("Origin");
    if (req.has_header("Origin") && origin != "http://" + host)
      throw HttpError(403, "Origin: '" + origin + "' may not change anything here (only pages of http://" + host + " may)");
    if (req.get_header_value("Sec-Fetch-Site") == "cross-site")
      throw HttpError(403, "Sec-Fetch-Site: a cross-site request may not change anything here");
    const std::string type = req.get_header_value("Content-Type");
    if (type.substr(0, type.find(';')) != "application/json")
      throw HttpError(415, "Content-Type: must be application/json, got '" + type + "'");
  }

 private:
  bool allowedHost(const std::string& host) const {
    if (names_.count(host)) return true;
    if (!any_) return false;
    // Bound to every address: any IP literal with this port (a name could be rebound; a literal cannot).
    const std::string p = ":" + std::to_string(port_);
    if (host.size() <= p.size() || host.compare(host.size() - p.size(), p.size(), p) != 0) return false;
    std::string ip = host.substr(0, host.size() - p.size());
    if (ip.size() > 2 && ip.front() == '[' && ip.back() == ']') ip = ip.substr(1, ip.size() - 2);
    unsigned char buf[sizeof(in6_addr)];
    return ::inet_pton(AF_INET, ip.c_str(), buf) == 1 || ::inet_pton(AF_INET6, ip.c_str(), buf) == 1;
  }

  int port_;
  bool any_ = false;
  std::set<std::string> names_;
};

}  // namespace

struct ServeApp::Impl {
  Impl(const ServeOptions& o, const std::string& helper_exe) : explorer(o.databases), workbench(o, helper_exe), hosts(o.host, 0) {}

  /// Runs `handler` after the request checks, answering its errors as JSON.
  template <class F>
  httplib::Server::Handler guarded(F handler) {
    return [this, handler](const httplib::Request& req, httplib::Response& res) {
      try {
        if (const Refusal& r = DeadlineStream::refusal(); r.status != 0) {
          res.set_header("Connection", "close");  // it is closed after the answer
          throw HttpError(r.status, r.message);
        }
        hosts.check(req);
        // A chunked body is counted as it is read (DeadlineStream), with its framing's room.
        if (req.body.size() > DeadlineStream::bodyLimit()) throw HttpError(413, DeadlineStream::tooLargeMessage(req.body.size()));
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

  Explorer explorer;
  WorkbenchServer workbench;
  HostCheck hosts;
  DeadlineServer server;
  int port = -1;
};

ServeApp::ServeApp(const ServeOptions& o, const std::string& helper_exe) {
  if (o.port < 0 || o.port > 65535) throw InputError("--port", "port", "must be from 0 to 65535, got " + std::to_string(o.port));
  ::signal(SIGPIPE, SIG_IGN);  // a client or the plan helper gone mid-answer is an error, not the server's end
  for (const auto& [route, file] : pageFiles())
    if (!fs::exists(file.first)) throw InputError(file.first, "serve", "the explorer's page file is missing");
  impl_ = std::make_unique<Impl>(o, helper_exe);
  Impl& x = *impl_;
  httplib::Server& server = x.server;
  server.new_task_queue = [] { return new httplib::ThreadPool(kConnectionThreads); };
  // Each route's own limit is held as its body is read (DeadlineStream::frameBody): httplib's is
  // the largest of them.
  server.set_payload_max_length(kMaxCheckBodyBytes);
  // Address reuse lets a restarted server bind at once, but not port reuse: a second server on a
  // busy port must fail at start, not share the port and split the saves between two databases.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  for (const auto& [route, file] : pageFiles()) {
    const std::string path = file.first, type = file.second;
    server.Get(route, x.guarded([path, type](const httplib::Request&, httplib::Response& res) { res.set_content(readFile(path), type); }));
  }
  server.Get("/api/experiments", x.guarded([&x](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(x.explorer.experiments()), "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs)", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(x.explorer.runs(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req)), "application/json");
  }));
  server.Get(R"(/api/experiments/(\d{1,6})/(\d{1,12})/runs/([0-9a-f]{64})/(picture\.svg|playback\.js))",
             x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
               const bool playback = req.matches[4] == "playback.js";
               res.set_content(x.explorer.drawing(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3], playback),
                               playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
             }));
  server.Get("/api/experiments/(\\d{1,6})/(\\d{1,12})/runs/([0-9a-f]{64})/problem",
             x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
               res.set_content(jsonText(x.explorer.problem(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3])),
                               "application/json");
             }));
  server.Get("/api/experiments/(\\d{1,6})/(\\d{1,12})/runs/([0-9a-f]{64})/outcome",
             x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
               res.set_content(jsonText(x.explorer.outcome(std::stoul(req.matches[1]), std::stoll(req.matches[2]), req.matches[3])),
                               "application/json");
             }));
  server.Get("/api/planners", x.guarded([](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(plannersJson()), "application/json");
  }));
  server.Get("/api/walls", x.guarded([&x](const httplib::Request&, httplib::Response& res) {
    res.set_content(jsonText(x.workbench.walls()), "application/json");
  }));
  server.Get(R"(/api/walls/folder/(\d{1,9}))", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(x.workbench.folderWall(std::stoul(req.matches[1])), "application/json");
  }));
  server.Get(R"(/api/walls/db/(.{1,1000}))", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(x.workbench.databaseWall(req.matches[1]), "application/json");
  }));
  server.Post("/api/check", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(x.workbench.check(req.body)), "application/json");
  }));
  server.Post("/api/walls", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(x.workbench.save(req.body)), "application/json");
  }));
  server.Post("/api/plan", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    res.set_content(jsonText(x.workbench.plan(req.body)), "application/json");
  }));
  server.Get(R"(/api/plans/(\d{1,12})/(picture\.svg|playback\.js))", x.guarded([&x](const httplib::Request& req, httplib::Response& res) {
    const bool playback = req.matches[2] == "playback.js";
    res.set_content(x.workbench.drawing(std::stoll(req.matches[1]), playback), playback ? "text/javascript; charset=utf-8" : "image/svg+xml");
  }));
  // A client that asks before sending its body (Expect: 100-continue) hears the refusal before
  // sending it, or 100 Continue once its headers hold (and a large body has its place).
  server.set_expect_100_continue_handler([&x](const httplib::Request& req, httplib::Response& res) {
    const Refusal& r = DeadlineStream::refusal();
    if (r.status != 0) {
      answerError(res, r.status, r.message);
      res.set_header("Connection", "close");
      return r.status;
    }
    try {
      x.hosts.check(req);  // another Host or Origin, or not JSON: refused before the body is sent
    } catch (const HttpError& e) {
      DeadlineStream::refusal() = Refusal{e.status, e.what()};
      answerError(res, e.status, e.what());
      res.set_header("Connection", "close");
      return e.status;
    }
    return 100;
  });
  // An exception outside a route's own handling (httplib's, or a bug): 500 as JSON, never the
  // process's end.
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "unknown";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    answerError(res, 500, "internal error: " + what);
  });
  // Anything else, and bodies over the limit: a JSON error (httplib calls this for every status
  // >= 400 left without a body).
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 400) DeadlineStream::malformed() = true;  // every route's own 400 has a body
    try {
      if (const Refusal& r = DeadlineStream::refusal(); r.status != 0) {
        answerError(res, r.status, r.message);
        res.set_header("Connection", "close");  // it is closed after the answer
      }
      else if (DeadlineStream::readTimedOut())
        answerError(res, 408, readDeadlineMessage());
      else if (res.status == 413 || DeadlineStream::tooLarge())
        answerError(res, 413, DeadlineStream::tooLargeMessage(0));
      else if (res.status == 404)
        answerError(res, 404, req.path + ": no such page or API (see docs/explorer.md)");
      else
        answerError(res, res.status, req.path + ": refused (HTTP " + std::to_string(res.status) + ")");
    } catch (...) {
      res.set_content("{\"error\": \"refused\"}\n", "application/json");
    }
  });
  x.port = o.port == 0 ? server.bind_to_any_port(o.host) : (server.bind_to_port(o.host, o.port) ? o.port : -1);
  if (x.port < 0)
    throw InputError("--port", "port", "cannot listen on " + o.host + ":" + std::to_string(o.port) + " (is another server on it?)");
  x.hosts = HostCheck(o.host, x.port);
}

ServeApp::~ServeApp() = default;
int ServeApp::port() const { return impl_->port; }
bool ServeApp::listen() { return impl_->server.listen_after_bind(); }
void ServeApp::stop() { impl_->server.stop(); }

int serveHere(const ServeOptions& o) {
  ServeApp app(o, "/proc/self/exe");
  if (!HostCheck::isLoopback(o.host))
    std::cerr << "coverbench serve: warning: listening on " << o.host
              << ", not a loopback address: anyone who can reach it on that network can read the served results, "
                 "save walls and start plans\n";
  std::cout << "coverbench serve: http://" << o.host << ":" << app.port() << "/ (" << o.databases.size() << " database"
            << (o.databases.size() == 1 ? "" : "s") << "; Ctrl-C stops it)" << std::endl;
  app.listen();
  return 0;
}

}  // namespace coverbench::cli
