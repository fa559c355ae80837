// The parts of `coverbench serve` (serve_command.cpp) that answer requests, without the HTTP
// library: the explorer's index of experiment runs (serve_explorer.cpp) and the workbench's walls,
// checks and plans (serve_workbench.cpp). Internal to the server's library.
#pragma once

#include <sys/types.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "coverbench/motion.hpp"
#include "coverbench/path.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/run_record.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/walls_db.hpp"

namespace coverbench::cli::serve_internal {

/// A request that cannot be answered: its HTTP status and one line.
struct HttpError : std::runtime_error {
  int status;
  HttpError(int s, const std::string& message) : std::runtime_error(message), status(s) {}
};

/// A request body's bytes: a wall file the workbench saves or plans, its settings around it.
constexpr std::size_t kMaxBodyBytes = 1 << 20;

/// The explorer's side of the server: the experiments of the databases named on the command
/// line, their runs as a table (filtered by facet, wall, planner parameter and metric range,
/// sorted by any column, paged, or whole as CSV), and each run's picture, playback, problem and
/// outcome. The runs' query is read in serve_runs.cpp, the rest in serve_explorer.cpp.
class Explorer {
 public:
  /// A request's query parameters (httplib::Params).
  using Params = std::multimap<std::string, std::string>;
  /// The most runs a page holds (`limit`), and the rows of the CSV made at a time.
  static constexpr std::size_t kMaxRunsPerPage = 1000;

  explicit Explorer(const std::vector<std::string>& databases);

  nlohmann::json experiments();
  /// A page of the experiment's runs, as the query asks (docs/explorer.md#api): filters, sort,
  /// order, offset, limit. A parameter it does not know, one given twice, or a bad value: 400
  /// naming the parameter.
  nlohmann::json runs(std::size_t db, long long id, const Params& query);
  /// The runs a query selects, in its order, for the CSV (every one: no paging), read in pieces
  /// of at most kMaxRunsPerPage rows so the server holds one piece at a time.
  struct Selection {
    std::size_t db = 0;
    long long id = 0;
    std::vector<std::uint32_t> runs;  ///< positions in the experiment's index
  };
  Selection select(std::size_t db, long long id, const Params& query);
  /// The CSV's header line, and the rows of runs [from, from + n) of the selection.
  std::string csvHeader(const Selection& s);
  std::string csvRows(const Selection& s, std::size_t from, std::size_t n);
  /// The values of one metric (`metric`), and of a second (`versus`) when asked, of every run the
  /// filters select, for the Plots tab: each run's wall, dataset, configuration, tool, status and
  /// whether it is usable (ok or partial with a valid path), by column, with each configuration's
  /// planner and parameters. At most kMaxPlotRuns runs (400 beyond, naming the filters).
  nlohmann::json values(std::size_t db, long long id, const Params& query);
  static constexpr std::size_t kMaxPlotRuns = 200000;
  /// The metric registry as the page formats it: each metric's unit, direction, kind, description
  /// and display format (percent, count, bytes or number).
  static nlohmann::json metricSpecsJson();
  /// The run's picture, or the script that plays it back under the experiment's time model. The
  /// run is read under the lock; it is drawn outside it, so other requests do not wait for it.
  std::string drawing(std::size_t db, long long id, const std::string& key, bool playback);
  /// The coat the run lays (its experiment's flux profile and time model; coatPicture's blocks as
  /// one image), drawn outside the lock, one at a time (a raster may take 200 MB). 404 for a run
  /// whose tool has no profile, or that has no scored path.
  std::string coat(std::size_t db, long long id, const std::string& key);
  /// What the run planned, as a workbench request: its wall file, planner, parameters and tool.
  nlohmann::json problem(std::size_t db, long long id, const std::string& key);
  /// How the run ended, in words: its status, reason and the end of an external planner's stderr
  /// (kept for crash, error and invalid_output; valid UTF-8 as stored), with the wall and tool.
  nlohmann::json outcome(std::size_t db, long long id, const std::string& key);

 private:
  struct Db {
    std::string file;
    std::unique_ptr<ResultsDb> db;
  };
  static constexpr std::size_t kFacets = 4;
  static constexpr const char* kFacetNames[kFacets] = {"planner", "dataset", "status", "tool"};
  /// An experiment's runs as the table browses them: summaries in key order, each run's facet
  /// values as indices, each planner's parameters (by the planner facet's index), metric columns
  /// read when first asked for, and sort orders kept.
  struct Index {
    std::vector<ResultsDb::RunSummary> runs;
    std::map<std::string, std::uint32_t> position;
    std::vector<std::string> metric_names;
    std::array<std::vector<std::string>, kFacets> facet_values;
    std::array<std::vector<std::uint32_t>, kFacets> facet_of;
    std::vector<std::map<std::string, std::string>> params_of_planner;  ///< name -> value as text
    std::vector<std::string> params_json_of_planner;                   ///< as stored, read as JSON
    std::vector<std::string> family_of_planner;                        ///< the planner a label configures
    std::map<std::string, std::vector<std::string>> param_values;      ///< every value of each
    std::map<std::string, std::vector<double>> columns;
    std::map<std::pair<std::string, bool>, std::vector<std::uint32_t>> orders;
    MotionLimits motion;
  };
  /// A runs query read and checked against the experiment (serve_runs.cpp).
  struct Query {
    std::array<long long, kFacets> facet{};  ///< -1: any; -2: a value no run has; else its index
    std::string wall, key;                   ///< "": any
    std::vector<std::pair<std::string, std::string>> params;  ///< name, value as text
    struct Range {
      std::string metric;
      double low, high;
    };
    std::vector<Range> ranges;
    std::string sort;
    bool desc = false;
    std::size_t offset = 0, limit = 100;
  };

  /// A run of an experiment, by its key (404 when the experiment has none). Under mutex_.
  ResultsDb::StoredRun storedRun(std::size_t db, long long id, const std::string& key);
  /// The query's parameters read and checked; `paged`: offset and limit are taken.
  Query readQuery(Index& x, const Params& query, bool paged);
  /// The runs the query's filters pass, in its order. Under mutex_.
  std::vector<std::uint32_t> matching(Index& x, std::size_t db, long long id, const Query& q);
  /// A metric of every run, in key order (NaN where a run has none): read once, then kept.
  const std::vector<double>& column(Index& x, std::size_t db, long long id, const std::string& metric);
  /// The runs in the order of `column` (none: key order), runs without a value last either way;
  /// ties in key order.
  const std::vector<std::uint32_t>& sorted(Index& x, std::size_t db, long long id, const std::string& column, bool desc);
  /// The experiment's index, made when first asked for (404 for a database or experiment not served).
  Index& index(std::size_t db, long long id);

  std::vector<Db> dbs_;
  std::map<std::pair<std::size_t, long long>, Index> cache_;
  std::mutex mutex_;
  std::mutex coat_mutex_;  ///< one coat drawn at a time (coat())
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
  PlanHelper(std::string exe, double max_time_limit_s);
  ~PlanHelper();

  /// The plan's record, within `deadline`; throws HttpError 504 when the helper did not answer
  /// by then (it is restarted), 500 when it ended (restarted too), 400 for a refused request.
  RunRecord plan(const std::string& body, std::chrono::steady_clock::time_point deadline);

 private:
  void start();
  void stop();
  /// After the helper was reaped: its pipes closed (its workers end by their parent-death signal).
  void forget();

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
  Pass enter(const char* what);

 private:
  int most_;
  std::atomic<int> n_{0};
};

/// The workbench's side of the server: walls from the named folders and walls database, checks
/// and plans (docs/explorer.md#workbench). Plans run in worker processes, one at a time with one more waiting; the
/// last 32 are kept to draw and play.
class WorkbenchServer {
 public:
  WorkbenchServer(const ServeOptions& o, const std::string& helper_exe);
  ~WorkbenchServer();

  nlohmann::json walls();
  /// A listed wall file's text (by its position in the listing: no request names a file). It is
  /// opened in its folder without following a link and must still be a regular file of at most
  /// the body limit that parses as a wall: a file swapped for a link or a FIFO since the listing is
  /// refused, never followed or waited on.
  std::string folderWall(std::size_t i);
  std::string databaseWall(const std::string& name);
  /// The request checked as a plan request is: {"ok": true, ...} or {"ok": false, "error": the
  /// command line's one line}. A verdict, not a failure: answered 200 either way.
  nlohmann::json check(const std::string& body);
  nlohmann::json save(const std::string& body);
  nlohmann::json plan(const std::string& body);
  std::string drawing(long long id, bool playback);

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
  static void checkSavedName(const std::string& name);

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

}  // namespace coverbench::cli::serve_internal
