// `coverbench report` and the report at the end of `coverbench run`: the runs are read here, the
// gallery drawn here, and the analysis (statistics, plots, pages, tables) is reports/python's,
// run with Debian's python3 (matplotlib, scipy).
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "commands.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/files.hpp"
#include "coverbench/report_data.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/svg.hpp"

extern char** environ;

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

/// Marks a folder as a CoverBench report, so writing a report again may replace it.
constexpr const char* kReportMarker = ".coverbench-report";

std::string envOr(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? v : fallback;
}

/// Whether process `pid` is alive (signal 0 tells; a process of another user counts as alive).
bool processAlive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

/// Removes what killed writers left next to `target`: ".NAME.staging-PID" and ".NAME.old-PID"
/// folders whose process is gone.
void removeLeftovers(const fs::path& parent, const std::string& name) {
  std::error_code ec;
  for (const char* kind : {".staging-", ".old-"}) {
    const std::string prefix = "." + name + kind;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string file = it->path().filename().string();
      if (file.rfind(prefix, 0) != 0) continue;
      const std::string digits = file.substr(prefix.size());
      if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
      if (!processAlive(std::stol(digits))) fs::remove_all(it->path(), ec);
    }
  }
}

/// A folder next to `target` that is removed unless published. Publishing swaps it with the
/// target in one step (renameat2 RENAME_EXCHANGE), so a reader sees the old report or the new
/// one, never none; a kill at any moment leaves at most a leftover that the next writer removes.
class Staging {
 public:
  explicit Staging(const fs::path& target) {
    const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    fs::create_directories(parent, ec);
    removeLeftovers(parent, target.filename().string());
    path_ = parent / ("." + target.filename().string() + ".staging-" + std::to_string(::getpid()));
    fs::remove_all(path_, ec);
    if (!fs::create_directories(path_, ec) || ec)
      throw InputError(target.string(), "--out", "cannot create a folder next to it: " + ec.message());
  }
  ~Staging() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  /// Puts the staged folder at `target`, replacing an earlier report there in one step.
  void publish(const fs::path& target) {
    std::error_code ec;
    std::ofstream(path_ / kReportMarker) << "written by coverbench report\n";
    if (fs::exists(target)) {
      if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) != 0)
        throw InputError(target.string(), "--out", std::string("cannot replace it: ") + std::strerror(errno));
      fs::remove_all(path_, ec);  // the old report, now at the staging name
    } else {
      fs::rename(path_, target, ec);
      if (ec) throw InputError(target.string(), "--out", "cannot write it: " + ec.message());
    }
    path_.clear();
  }

 private:
  fs::path path_;
};

/// Refuses to replace a folder that holds anything but an earlier report.
void checkReportTarget(const fs::path& target) {
  if (!fs::exists(target)) return;
  if (!fs::is_directory(target)) throw InputError(target.string(), "--out", "exists and is not a folder");
  if (fs::exists(target / kReportMarker) || fs::is_empty(target)) return;
  throw InputError(target.string(), "--out", "is a folder that is not a CoverBench report: choose a new or empty folder");
}

}  // namespace

PictureLayers pictureLayers(const Path& path, const std::string& status) {
  const bool scorable = !path.waypoints.empty() && status != toString(RunStatus::MetricsError);
  return {scorable, scorable && path.waypoints.size() <= kGalleryCoverageWaypoints};
}

namespace {

/// Runs work(i) for i in [0, count) on two threads; the first exception is thrown after all.
template <class Work>
void inParallel(std::size_t count, Work work) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto run = [&] {
    for (std::size_t i; (i = next++) < count;) {
      try {
        work(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> threads;
  const unsigned n = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
  for (unsigned t = 0; t < n; ++t) threads.emplace_back(run);
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
}

/// The gallery's pictures with their runs: what the report data says of each (file, size, note,
/// playback, coat) is known before its path is drawn, so the analysis can start while they are.
struct GalleryPlan {
  std::vector<GalleryPicture*> pictures;
  std::vector<std::string> stems;
  std::vector<ResultsDb::StoredRun> runs;
  std::vector<std::string> coats;  ///< each run's coat picture, for a tool with a flux profile
};

std::string pictureTitle(const ResultsDb::StoredRun& r, const GalleryPicture& p) {
  return r.wall.name + " / " + p.column + "  " + r.status;
}

/// Reads every gallery picture's run and sets its file names, size and note; draws the coats of a
/// tool with a flux profile (docs/deposition.md), whose raster may be refused with a reason.
GalleryPlan planGallery(ResultsDb& db, std::vector<GallerySection>& gallery, const MotionLimits& motion) {
  GalleryPlan plan;
  std::vector<std::string> names;
  for (GallerySection& s : gallery)
    for (GalleryWall& w : s.walls)
      for (GalleryPicture& p : w.pictures) {
        plan.pictures.push_back(&p);
        names.push_back(s.title + "__" + w.wall_name + "__" + p.column);
      }
  plan.stems = uniqueFileNames(names);
  plan.runs.reserve(plan.pictures.size());
  bool profiled = false;
  for (std::size_t i = 0; i < plan.pictures.size(); ++i) {
    GalleryPicture& p = *plan.pictures[i];
    const ResultsDb::StoredRun& r = plan.runs.emplace_back(db.storedRun(p.key));
    const auto [scorable, layer] = pictureLayers(r.path, r.status);
    if (scorable && !layer)
      p.note = std::to_string(r.path.waypoints.size()) + " waypoints: coverage layer and failed segments " +
               "left out (over " + std::to_string(kGalleryCoverageWaypoints) + "; `coverbench redraw` draws them)";
    const PictureSize size = pictureSize(r.wall, &r.path);
    p.width = std::llround(size.width);
    p.height = std::llround(size.height);
    p.file = "gallery/" + plan.stems[i] + ".svg";
    if (r.path.segments() > 0) p.playback = "gallery/" + plan.stems[i] + ".js";
    profiled = profiled || (scorable && r.tool.profile.set());
  }
  plan.coats.resize(plan.runs.size());
  if (!profiled) return plan;
  std::vector<std::string> refused(plan.runs.size());
  inParallel(plan.runs.size(), [&](std::size_t i) {
    const ResultsDb::StoredRun& r = plan.runs[i];
    if (!pictureLayers(r.path, r.status).scorable || !r.tool.profile.set()) return;
    try {  // the coat beside the path
      plan.coats[i] = coatPicture(r.wall, r.tool, r.path, motion, r.vehicle, pictureTitle(r, *plan.pictures[i]) + ": the coat", true);
    } catch (const InputError& e) {  // a raster over the cap: the page says why there is none
      refused[i] = e.problem();
    }
  });
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    GalleryPicture& p = *plan.pictures[i];
    if (!refused[i].empty()) p.note += (p.note.empty() ? "" : "; ") + std::string("no coat picture: ") + refused[i];
    if (plan.coats[i].empty()) continue;
    // In a folder of their own: no name there is a path picture's.
    p.coat = "gallery/coat/" + plan.stems[i] + ".svg";
    const PictureSize coat = pictureSize(plan.runs[i].wall, nullptr);
    p.coat_width = std::llround(coat.width);
    p.coat_height = std::llround(coat.height);
  }
  return plan;
}

/// Draws every planned picture into `folder`/gallery, two at a time, with the data that plays its
/// path back under the experiment's time model, and writes the coats drawn with the plan.
void drawGallery(const GalleryPlan& plan, const fs::path& folder, const MotionLimits& motion) {
  fs::create_directories(folder / "gallery");
  const std::size_t count = plan.runs.size();
  std::vector<std::string> svgs(count), scripts(count);
  inParallel(count, [&](std::size_t i) {
    const ResultsDb::StoredRun& r = plan.runs[i];
    const GalleryPicture& p = *plan.pictures[i];
    svgs[i] = pathPicture(r.wall, r.tool, r.vehicle, r.path, pictureTitle(r, p), pictureLayers(r.path, r.status).layer,
                          kGalleryOverlapStrips);
    if (!p.playback.empty()) scripts[i] = playbackScript(p.playback, r.wall, r.tool, r.vehicle, r.path, motion);
  });
  auto write = [&](const std::string& file, const std::string& text) {
    std::ofstream out(folder / file, std::ios::binary);
    out << text;
    out.flush();  // a full disk shows here, with its reason in errno
    if (!out) throw InputError((folder / file).string(), "gallery", std::string("cannot be written: ") + std::strerror(errno));
  };
  for (std::size_t i = 0; i < count; ++i) {
    const GalleryPicture& p = *plan.pictures[i];
    write(p.file, svgs[i]);
    if (!p.coat.empty()) {
      fs::create_directories(folder / "gallery" / "coat");
      write(p.coat, plan.coats[i]);
    }
    if (!scripts[i].empty()) write(p.playback, scripts[i]);
  }
}

ResultSet loadResults(ResultsDb& db, const ReportOptions& o) {
  ResultSet results = db.load(o.experiment);
  if (!o.baseline.empty()) {
    if (std::none_of(results.runs.begin(), results.runs.end(), [&](const ResultRow& r) { return r.config == o.baseline; }))
      throw InputError("--baseline", "baseline", "'" + shownBytes(o.baseline) + "' is not a planner configuration of this experiment");
    results.baseline = o.baseline;
  }
  return results;
}

/// The published table the report sets beside the planners: --published's, else the one the
/// stored config names (none without either, or with --no-published), with whether its clock is
/// the experiment's.
std::optional<PublishedTable> loadPublished(const ReportOptions& o, const ExperimentRecord& record) {
  if (o.published.empty() && !o.published_clock.empty())
    throw InputError("--published-clock", "published_clock", "needs --published");
  if (o.no_published && !o.published.empty())
    throw InputError("--no-published", "no_published", "cannot be given with --published");
  std::optional<PublishedTable> table;
  if (o.no_published) return table;
  if (!o.published.empty()) {
    if (o.published_clock.empty())
      throw InputError("--published", "published", "needs --published-clock: unknown, or a time model such as '{speed: 0.3}'");
    table = publishedTable(o.published, o.published_clock);
  } else {
    table = configPublished(record.config_text, record.config_path);
  }
  if (table && table->clock)
    table->clock_matches = sameClock(*table->clock, configMotion(record.config_text, record.config_path));
  return table;
}

}  // namespace

namespace {

/// The analysis running beside the command (startAnalysis), waited for by finishAnalysis.
struct AnalysisProcess {
  pid_t pid = -1;
  std::string python;
  std::string folder;
};

AnalysisProcess startAnalysis(const std::string& data, const std::string& folder, const std::string& formats) {
  const std::string python = envOr("COVERBENCH_PYTHON", "/usr/bin/python3");
  const std::string pythonpath = envOr("COVERBENCH_REPORT_PYTHONPATH", COVERBENCH_REPORT_PYTHONPATH);
  // No __pycache__ in the source tree (PYTHONDONTWRITEBYTECODE), whatever the caller's environment.
  std::vector<std::string> env_text = {"PYTHONPATH=" + pythonpath, "MPLBACKEND=Agg", "PYTHONHASHSEED=0",
                                       "MPLCONFIGDIR=" + folder + "/.matplotlib", "PYTHONDONTWRITEBYTECODE=1"};
  std::vector<char*> env;
  for (std::string& e : env_text) env.push_back(e.data());
  for (char** e = environ; *e; ++e) {
    const std::string v = *e;
    const bool ours = std::any_of(env_text.begin(), env_text.end(),
                                  [&](const std::string& t) { return v.compare(0, t.find('=') + 1, t, 0, t.find('=') + 1) == 0; });
    if (!ours) env.push_back(*e);
  }
  env.push_back(nullptr);
  std::vector<std::string> args = {python, "-m", "coverbench_report", data, "--out", folder, "--formats", formats};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The analysis dies with its parent (a killed `coverbench` leaves no child writing into its
  // staging folder); it is checked again after the death signal is set, in case the parent died
  // in between. Only async-signal-safe calls between fork and exec.
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0)
    throw InputError(python, "report", "cannot start the analysis (" + std::string(std::strerror(errno)) + ")");
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) ::dup2(devnull, STDOUT_FILENO);
    ::execve(python.c_str(), argv.data(), env.data());
    ::_exit(127);  // exec failed
  }
  return {pid, python, folder};
}

int waitFor(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

/// Stops an analysis that is no longer wanted (the gallery failed): nothing of it is kept.
void stopAnalysis(const AnalysisProcess& a) {
  ::kill(a.pid, SIGKILL);
  waitFor(a.pid);
}

void finishAnalysis(const AnalysisProcess& a) {
  const std::string& python = a.python;
  const int status = waitFor(a.pid);
  std::error_code ec;
  fs::remove_all(fs::path(a.folder) / ".matplotlib", ec);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127 && ::access(python.c_str(), X_OK) != 0)
    throw InputError(python, "report", "cannot start the analysis (" + std::string(std::strerror(errno)) +
                                           "): it needs python3 with matplotlib and scipy (Debian: python3-matplotlib "
                                           "python3-scipy; scripts/setup.sh installs them)");
  if (WIFEXITED(status) && WEXITSTATUS(status) == 3) throw AlreadyReported();  // a file it could not write
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("the analysis (" + python + " -m coverbench_report, reports/python) failed with " +
                             (WIFEXITED(status) ? "exit code " + std::to_string(WEXITSTATUS(status))
                                                : "signal " + std::to_string(WTERMSIG(status))) +
                             "; its message is above");
}

}  // namespace

void runAnalysis(const std::string& data, const std::string& folder, const std::string& formats) {
  finishAnalysis(startAnalysis(data, folder, formats));
}

std::string writeReport(const ReportOptions& o) {
  const fs::path target(o.out);
  checkReportTarget(target);
  ResultsDb db(o.database, ResultsDb::Mode::ReadOnly);
  const ResultSet results = loadResults(db, o);
  const ExperimentRecord record = db.record(o.experiment);
  const std::optional<PublishedTable> published = loadPublished(o, record);
  std::vector<std::string> datasets;
  for (const auto& d : record.datasets)
    if (std::find(datasets.begin(), datasets.end(), d.label) == datasets.end()) datasets.push_back(d.label);
  std::vector<GallerySection> gallery = selectGallery(results, datasets);
  Staging staging(target);
  const MotionLimits motion = configMotion(record.config_text, record.config_path);
  const GalleryPlan plan = planGallery(db, gallery, motion);
  const fs::path data = staging.path() / "report_data.json";
  {
    std::ofstream out(data, std::ios::binary);
    out << reportDataJson(results, record, gallery, published ? &*published : nullptr);
    out.flush();
    if (!out) throw InputError(data.string(), "report", std::string("cannot be written: ") + std::strerror(errno));
  }
  // The pictures are drawn while the analysis runs: it needs only what the plan put in the data.
  const AnalysisProcess analysis = startAnalysis(data.string(), staging.path().string(), "html,md,csv,latex");
  try {
    drawGallery(plan, staging.path(), motion);
  } catch (...) {
    stopAnalysis(analysis);
    throw;
  }
  finishAnalysis(analysis);
  staging.publish(target);
  return (target / "index.html").string();
}

std::string renderShowcasePage(const std::string& data_json) {
  Staging scratch(fs::temp_directory_path() / ("coverbench-showcase-" + std::to_string(::getpid())));
  const fs::path data = scratch.path() / "showcase_data.json";
  std::ofstream(data, std::ios::binary) << data_json;
  runAnalysis(data.string(), scratch.path().string(), "html");
  return readFile((scratch.path() / "index.html").string());
}

int reportCommand(const ReportOptions& o) {
  static const std::map<std::string, std::pair<std::string, std::string>> formats = {
      {"md", {"md", "report.md"}}, {"markdown", {"md", "report.md"}}, {"csv", {"csv", "report.csv"}},
      {"latex", {"latex", "report.tex"}}, {"tex", {"latex", "report.tex"}}};
  if (o.format == "html") {
    if (o.out.empty()) throw InputError("--out", "out", "--format html writes a folder: give it with --out");
    const std::string page = writeReport(o);
    std::cout << "report: " << page << "\n";
    return 0;
  }
  const auto f = formats.find(o.format);
  if (f == formats.end()) throw InputError("--format", "format", "must be html, md, csv or latex, got '" + shownBytes(o.format) + "'");
  ResultsDb db(o.database, ResultsDb::Mode::ReadOnly);
  const ResultSet results = loadResults(db, o);
  const ExperimentRecord record = db.record(o.experiment);
  const std::optional<PublishedTable> published = loadPublished(o, record);
  // The tables alone: the analysis writes them into a scratch folder, read back here.
  const fs::path scratch_target = fs::temp_directory_path() / ("coverbench-report-" + std::to_string(::getpid()));
  Staging scratch(scratch_target);
  const fs::path data = scratch.path() / "report_data.json";
  {
    std::ofstream out(data, std::ios::binary);
    out << reportDataJson(results, record, {}, published ? &*published : nullptr);
  }
  runAnalysis(data.string(), scratch.path().string(), f->second.first);
  const std::string text = readFile((scratch.path() / f->second.second).string());
  if (o.out.empty()) std::cout << text;
  else writeFileAtomically(o.out, text);
  return 0;
}

}  // namespace coverbench::cli
