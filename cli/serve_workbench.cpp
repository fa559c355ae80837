// The workbench's side of `coverbench serve` (serve_parts.hpp): the wall files and walls database
// it opens and saves, checks, and plans in a helper process of their own.
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "coverbench/limits.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/wall_file.hpp"
#include "serve.hpp"
#include "serve_parts.hpp"
#include "workbench.hpp"

namespace coverbench::cli::serve_internal {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::size_t kMaxSavedNameBytes = 1000;  // what GET /api/walls/db/NAME takes

/// Whether a name (valid UTF-8) is empty or only white space: the page's `!/\S/.test(name)`, so
/// that both refuse the same names (ASCII space, no-break and typographic spaces, the line and
/// paragraph separators, the ideographic space and the byte order mark; the control characters
/// among JavaScript's white space are refused on their own).
bool isBlank(const std::string& name) {
  static const std::string_view kBlanks[] = {" ",      "\u00a0", "\u1680", "\u2000", "\u2001", "\u2002", "\u2003",
                                             "\u2004", "\u2005", "\u2006", "\u2007", "\u2008", "\u2009", "\u200a",
                                             "\u2028", "\u2029", "\u202f", "\u205f", "\u3000", "\ufeff"};
  std::string_view rest(name);
  while (!rest.empty()) {
    const auto blank = std::find_if(std::begin(kBlanks), std::end(kBlanks), [&](std::string_view b) { return rest.substr(0, b.size()) == b; });
    if (blank == std::end(kBlanks)) return false;
    rest.remove_prefix(blank->size());
  }
  return true;
}

/// A walls database's own failure (locked, unwritable, corrupt) is the server's, not the
/// request's: 503 with the reason. Other refusals keep `status`.
[[noreturn]] void rethrowWallsDbError(const InputError& e, int status) {
  if (e.field() == "(database)") throw HttpError(503, std::string("walls database: ") + e.what());
  throw HttpError(status, e.what());
}

}  // namespace

// --- the plan helper ----------------------------------------------------------------------------

PlanHelper::PlanHelper(std::string exe, double max_time_limit_s) : exe_(std::move(exe)), max_time_limit_s_(max_time_limit_s) { start(); }
PlanHelper::~PlanHelper() { stop(); }

RunRecord PlanHelper::plan(const std::string& body, std::chrono::steady_clock::time_point deadline) {
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

void PlanHelper::start() {
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

void PlanHelper::stop() {
  if (pid_ < 0) return;
  ::kill(-pid_, SIGKILL);  // the helper and the workers it forked
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, nullptr, 0);
  forget();
}

void PlanHelper::forget() {
  ::close(to_);
  ::close(from_);
  pid_ = -1, to_ = -1, from_ = -1;
}

Gate::Pass Gate::enter(const char* what) {
  if (++n_ > most_) {
    --n_;
    throw HttpError(503, std::string(what) + ": " + std::to_string(most_) + " are being worked on; ask again when one has ended");
  }
  return Pass{&n_};
}

// --- walls ---------------------------------------------------------------------------------------

WorkbenchServer::WorkbenchServer(const ServeOptions& o, const std::string& helper_exe)
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

WorkbenchServer::~WorkbenchServer() {
  for (const auto& f : folders_) ::close(f.second);
}

json WorkbenchServer::walls() {
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

std::string WorkbenchServer::folderWall(std::size_t i) {
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

std::string WorkbenchServer::databaseWall(const std::string& name) {
  if (!walls_db_) throw HttpError(404, "no walls database is served (serve --walls-db FILE)");
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    return walls_db_->content(name);
  } catch (const InputError& e) {
    rethrowWallsDbError(e, 404);
  }
}

json WorkbenchServer::check(const std::string& body) {
  const Gate::Pass pass = checks_.enter("wall checks");
  try {
    const WorkbenchRequest r = readWorkbenchRequest(body, max_time_limit_s_);
    return {{"ok", true}, {"name", r.wall.wall.name}, {"wall", r.wall.json}, {"obstacles", r.wall.wall.obstacles.size()}};
  } catch (const InputError& e) {
    return {{"ok", false}, {"error", e.what()}};
  }
}

json WorkbenchServer::save(const std::string& body) {
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

void WorkbenchServer::checkSavedName(const std::string& name) {
  if (isBlank(name))
    throw InputError("request body", "wall.name", "a saved wall needs a name that is not blank (it is how it is opened again)");
  if (name.size() > kMaxSavedNameBytes)
    throw InputError("request body", "wall.name",
                     "is " + std::to_string(name.size()) + " bytes; a saved wall's name has at most " + std::to_string(kMaxSavedNameBytes));
  for (const unsigned char c : name)
    if (c < 0x20 || c == 0x7f) throw InputError("request body", "wall.name", "has a control character (a newline, a tab, a NUL); a saved wall's name may not");
}

// --- plans ---------------------------------------------------------------------------------------

json WorkbenchServer::plan(const std::string& body) {
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

std::string WorkbenchServer::drawing(long long id, bool playback) {
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

}  // namespace coverbench::cli::serve_internal
