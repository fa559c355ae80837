// Runs in child processes: fork per run, hard limits, a pipe for the record, wait4 for rusage.
#include "isolation.hpp"

#include "allocation_meter.hpp"
#include "coverbench/external_planner.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>

namespace coverbench {
namespace {

using Clock = std::chrono::steady_clock;

// --- the record's bytes ---------------------------------------------------------------------------

class Writer {
 public:
  void u64(std::uint64_t v) {
    for (int b = 0; b < 8; ++b) out_.push_back(static_cast<char>((v >> (8 * b)) & 0xff));
  }
  void f64(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, 8);
    u64(bits);
  }
  void str(const std::string& s) {
    u64(s.size());
    out_ += s;
  }
  void map(const std::map<std::string, double>& m) {
    u64(m.size());
    for (const auto& [k, v] : m) str(k), f64(v);
  }
  /// A run field's value (kRunFields).
  void field(const std::string& v) { str(v); }
  void field(RunStatus v) { u64(static_cast<std::uint64_t>(v)); }
  void field(bool v) { u64(v ? 1 : 0); }
  void field(long long v) { u64(static_cast<std::uint64_t>(v)); }
  void field(double v) { f64(v); }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& in) : in_(in) {}
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int b = 0; b < 8; ++b) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(in_[at_ + b])) << (8 * b);
    at_ += 8;
    return v;
  }
  double f64() {
    const std::uint64_t bits = u64();
    double v;
    std::memcpy(&v, &bits, 8);
    return v;
  }
  std::string str() {
    const std::uint64_t n = u64();
    need(n);
    std::string s = in_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::map<std::string, double> map() {
    std::map<std::string, double> m;
    for (std::uint64_t n = count(); n > 0; --n) {
      std::string k = str();
      m[k] = f64();
    }
    return m;
  }
  std::uint64_t count() {  // an element count, at least one byte per element left
    const std::uint64_t n = u64();
    need(n);
    return n;
  }
  bool done() const { return at_ == in_.size(); }
  void field(std::string& v) { v = str(); }
  void field(RunStatus& v) {
    const std::uint64_t n = u64();
    if (n >= std::size(kRunStatuses)) throw std::runtime_error("run record: status " + std::to_string(n) + " is none");
    v = static_cast<RunStatus>(n);
  }
  void field(bool& v) { v = u64() != 0; }
  void field(long long& v) { v = static_cast<long long>(u64()); }
  void field(double& v) { v = f64(); }

 private:
  void need(std::uint64_t n) const {
    if (n > in_.size() - at_) throw std::runtime_error("truncated run record");
  }
  const std::string& in_;
  std::size_t at_ = 0;
};

constexpr std::uint64_t kRecordMagic = 0x31726e7262766363ULL;  // "ccvbrnr1"

// --- the worker ----------------------------------------------------------------------------------

bool g_out_of_memory = false;

void outOfMemory() {
  g_out_of_memory = true;
  std::set_new_handler(nullptr);
  throw std::bad_alloc();
}

/// A "Name:  N kB" line of /proc/self/status, in bytes.
double statusBytes(const char* name) {
  std::ifstream in("/proc/self/status");
  const std::size_t n = std::strlen(name);
  for (std::string line; std::getline(in, line);)
    if (line.compare(0, n, name) == 0) return std::atof(line.c_str() + n + 1) * 1024.0;
  return NAN;
}

double cpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
}

bool readAll(int fd, char* data, std::size_t size) {
  std::size_t off = 0;
  while (off < size) {
    const ssize_t n = ::read(fd, data + off, size - off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    off += static_cast<std::size_t>(n);
  }
  return true;
}

void writeAll(int fd, const std::string& bytes) {
  std::size_t off = 0;
  while (off < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(3);
    off += static_cast<std::size_t>(n);
  }
}

/// One run in the worker, measured: CPU from getrusage, peak resident set from VmHWM after the
/// kernel's peak was reset to the current resident set (clear_refs 5), and the run's own peak
/// memory from the allocation meter (a reused worker's resident set hides what a run reuses).
/// A run of a planner outside the tree keeps what executeRun measured of its own processes.
RunRecord measuredRun(const RunSpec& spec) {
  if (spec.memory_limit_bytes > 0) {  // address space: what the worker has now plus the limit
    const double now = statusBytes("VmSize:");
    const rlimit as{static_cast<rlim_t>(now + static_cast<double>(spec.memory_limit_bytes)), RLIM_INFINITY};
    ::setrlimit(RLIMIT_AS, &as);
  }
  const double cpu_before = cpuSeconds();
  const rlimit cpu_limit{static_cast<rlim_t>(std::ceil(cpu_before + hardDeadlineSeconds(spec))), RLIM_INFINITY};
  ::setrlimit(RLIMIT_CPU, &cpu_limit);  // past it: SIGXCPU
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  const double start_rss = statusBytes("VmRSS:");
  std::set_new_handler(outOfMemory);
  RunRecord rec;
  startAllocationMeter();
  try {
    rec = executeRun(spec);
  } catch (const std::exception& e) {
    rec = RunRecord{};
    rec.key = spec.key;
    rec.status = RunStatus::Error;
    rec.reason = std::string("the run failed outside the planner: ") + e.what();
  }
  const double allocated_peak = stopAllocationMeter();
  std::set_new_handler(nullptr);
  if (g_out_of_memory) {
    rec = RunRecord{};
    rec.key = spec.key;
    rec.status = RunStatus::MemoryLimit;
    char limit[64];
    std::snprintf(limit, sizeof limit, "%.4g MiB", static_cast<double>(spec.memory_limit_bytes) / (1024.0 * 1024.0));
    rec.reason = std::string("an allocation failed at the memory limit of ") + limit;
  }
  const rlimit no_limit{RLIM_INFINITY, RLIM_INFINITY};
  ::setrlimit(RLIMIT_AS, &no_limit);
  if (std::isfinite(rec.cpu_time_s)) return rec;  // an external planner's: its own processes' (executeRun)
  rec.cpu_time_s = cpuSeconds() - cpu_before;
  rec.start_rss_bytes = start_rss;
  rec.peak_rss_bytes = statusBytes("VmHWM:");
  if (rec.status != RunStatus::MemoryLimit)
    rec.peak_memory_bytes = allocationMeterAvailable() ? allocated_peak : std::max(0.0, rec.peak_rss_bytes - start_rss);
  return rec;
}

/// A worker: reads run indices, answers each with a length-prefixed record. Exits at the end of
/// its input, and after a run that hit the memory limit (its heap may be in any state).
[[noreturn]] void workerLoop(const std::vector<const RunSpec*>& runs, int cmd_fd, int result_fd, pid_t runner) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // the runner died (kill -9): stop too
  if (::getppid() != runner) ::_exit(0);  // it died before this worker could ask for that
  // A planner that prints must not garble the runner's terminal or the results.
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) {
    ::dup2(devnull, STDOUT_FILENO);
    ::dup2(devnull, STDERR_FILENO);
    ::close(devnull);
  }
  const rlimit no_core{0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  for (;;) {
    std::uint64_t index = 0;
    if (!readAll(cmd_fd, reinterpret_cast<char*>(&index), sizeof index) || index >= runs.size()) {
      external::stopPlannerProcesses();  // its planners' processes, and every process they started
      ::_exit(0);
    }
    const RunRecord rec = measuredRun(*runs[index]);
    const std::string bytes = serializeRecord(rec);
    const std::uint64_t size = bytes.size();
    writeAll(result_fd, std::string(reinterpret_cast<const char*>(&size), sizeof size) + bytes);
    if (g_out_of_memory) {
      external::stopPlannerProcesses();
      ::_exit(0);
    }
  }
}

// --- the parent -----------------------------------------------------------------------------------

struct Worker {
  pid_t pid = -1;
  int cmd_fd = -1, result_fd = -1;
  const RunSpec* spec = nullptr;  ///< the run it is executing; nullptr when idle
  Clock::time_point deadline;
  std::string bytes;
  bool killed_at_deadline = false;
};

std::string signalName(int sig) {
  const char* name = ::strsignal(sig);
  return "signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
}

/// The record of a run whose worker died before answering: what its end says.
RunRecord deathRecord(const Worker& w, int wait_status) {
  RunRecord rec;
  rec.key = w.spec->key;
  char limit[64];
  std::snprintf(limit, sizeof limit, "%.4g s", hardDeadlineSeconds(*w.spec));
  if (w.killed_at_deadline) {
    rec.status = RunStatus::Timeout;
    rec.reason = std::string("killed at the hard deadline of ") + limit + " (the planner ignored its budget)";
  } else if (WIFSIGNALED(wait_status) && WTERMSIG(wait_status) == SIGXCPU) {
    rec.status = RunStatus::Timeout;
    rec.reason = std::string("stopped at the CPU-time limit of ") + limit;
  } else if (WIFSIGNALED(wait_status)) {
    rec.status = RunStatus::Crash;
    rec.signal = WTERMSIG(wait_status);
    rec.reason = "the run's process died of " + signalName(WTERMSIG(wait_status));
  } else {
    rec.status = RunStatus::Crash;
    rec.reason = WIFEXITED(wait_status) ? "the run's process exited with code " + std::to_string(WEXITSTATUS(wait_status)) +
                                              " without a result"
                                        : "the run's process ended without a result";
  }
  return rec;
}

class Pool {
 public:
  Pool(const std::vector<const RunSpec*>& runs, unsigned size) : runs_(runs), workers_(size) {}
  ~Pool() {
    for (Worker& w : workers_) stop(w, true);
  }

  void run(const std::function<void(const RunSpec&, RunRecord)>& done) {
    std::size_t next = 0, busy = 0;
    while (next < runs_.size() || busy > 0) {
      for (Worker& w : workers_) {
        if (w.spec || next >= runs_.size()) continue;
        if (w.pid < 0) start(w);
        const std::uint64_t index = next++;
        w.spec = runs_[index];
        w.bytes.clear();
        w.killed_at_deadline = false;
        w.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(hardDeadlineSeconds(*w.spec)));
        if (::write(w.cmd_fd, &index, sizeof index) != sizeof index) {
          // The worker is gone (it exits after a memory limit): a fresh one takes the run.
          stop(w, true);
          start(w);
          if (::write(w.cmd_fd, &index, sizeof index) != sizeof index) throw std::runtime_error("cannot reach a worker");
        }
        ++busy;
      }
      std::vector<pollfd> fds;
      std::vector<Worker*> polled;
      auto nearest = Clock::time_point::max();
      for (Worker& w : workers_)
        if (w.spec) {
          fds.push_back({w.result_fd, POLLIN, 0});
          polled.push_back(&w);
          nearest = std::min(nearest, w.deadline);
        }
      const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(nearest - Clock::now()).count();
      const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(std::clamp<long long>(wait_ms + 1, 0, 60000)));
      if (ready < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
      for (std::size_t i = 0; i < polled.size(); ++i) {
        Worker& w = *polled[i];
        if (ready > 0 && (fds[i].revents & (POLLIN | POLLHUP | POLLERR))) {
          char buf[65536];
          const ssize_t n = ::read(w.result_fd, buf, sizeof buf);
          if (n > 0) {
            w.bytes.append(buf, static_cast<std::size_t>(n));
            std::uint64_t size = 0;
            if (w.bytes.size() >= sizeof size) std::memcpy(&size, w.bytes.data(), sizeof size);
            if (w.bytes.size() >= sizeof size && w.bytes.size() - sizeof size >= size) {
              RunRecord rec = deserializeRecord(w.bytes.substr(sizeof size, size));
              const RunSpec& spec = *w.spec;
              w.spec = nullptr;
              --busy;
              if (rec.key != spec.key) throw std::runtime_error("a worker answered for another run");
              // A worker whose run hit the memory limit ends (its heap may be in any state): it is
              // reaped now, so no later run is sent to it, and a fresh one is started when needed.
              if (rec.status == RunStatus::MemoryLimit) stop(w, true);
              done(spec, std::move(rec));
            }
          } else if (n == 0 || errno != EINTR) {  // died before answering
            const int status = stop(w, false);
            const RunSpec& spec = *w.spec;
            RunRecord rec = deathRecord(w, status);
            w.spec = nullptr;
            --busy;
            done(spec, std::move(rec));
          }
        } else if (Clock::now() >= w.deadline && !w.killed_at_deadline) {
          ::kill(w.pid, SIGKILL);
          w.killed_at_deadline = true;
        }
      }
    }
  }

 private:
  void start(Worker& w) {
    int cmd[2], result[2];
    if (::pipe2(cmd, O_CLOEXEC) != 0 || ::pipe2(result, O_CLOEXEC) != 0)
      throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    std::fflush(nullptr);  // nothing buffered is written twice by a worker
    const pid_t runner = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
      ::close(cmd[1]);
      ::close(result[0]);
      for (const Worker& other : workers_)
        if (other.pid > 0) ::close(other.cmd_fd), ::close(other.result_fd);
      workerLoop(runs_, cmd[0], result[1], runner);
    }
    ::close(cmd[0]);
    ::close(result[1]);
    w.pid = pid;
    w.cmd_fd = cmd[1];
    w.result_fd = result[0];
  }
  /// Closes a worker's pipes and reaps it (killing it first if `kill`); returns its wait status.
  int stop(Worker& w, bool kill) {
    if (w.pid < 0) return 0;
    if (kill) ::kill(w.pid, SIGKILL);
    ::close(w.cmd_fd);
    ::close(w.result_fd);
    int status = 0;
    while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
    }
    w.pid = -1;
    return status;
  }

  const std::vector<const RunSpec*>& runs_;
  std::vector<Worker> workers_;
};

/// Every process a run starts (workers, planners' processes and theirs, also those that left the
/// process group with setsid) carries the run's token in its environment (COVERBENCH_RUN_TOKEN),
/// and a planner's cgroup is named for it. When the run ends normally the runner kills what is
/// left of them; when the runner is killed (kill -9), its workers die with it (PR_SET_PDEATHSIG),
/// their planners' processes with them, and a guardian process, which holds the read end of a pipe
/// only the runner and its workers can write to, sees the pipe close and kills the rest.
class RunGuard {
 public:
  RunGuard() {
    static long long n = 0;
    token_ = std::to_string(::getpid()) + "-" + std::to_string(++n) + "-" +
             std::to_string(Clock::now().time_since_epoch().count() % 1000000007);
    if (const char* old = std::getenv("COVERBENCH_RUN_TOKEN")) old_ = old, had_old_ = true;
    ::setenv("COVERBENCH_RUN_TOKEN", token_.c_str(), 1);
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    std::fflush(nullptr);
    const pid_t runner = ::getpid();
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(fds[1]);
      ::setpgid(0, 0);  // a signal to the runner's process group does not stop the clean-up
      for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}) ::signal(sig, SIG_IGN);
      char c;
      while (::read(fds[0], &c, 1) != 0 && errno == EINTR) {
      }
      external::killRunProcesses(token_, runner);
      ::_exit(0);
    }
    ::close(fds[0]);
    if (pid < 0) {
      ::close(fds[1]);
      return;
    }
    guardian_ = pid;
    pipe_ = fds[1];
  }
  ~RunGuard() {
    external::killRunProcesses(token_, ::getpid());  // the guardian too: its work is done here
    if (pipe_ >= 0) ::close(pipe_);
    if (guardian_ > 0) {
      ::kill(guardian_, SIGKILL);
      while (::waitpid(guardian_, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
    if (had_old_)
      ::setenv("COVERBENCH_RUN_TOKEN", old_.c_str(), 1);
    else
      ::unsetenv("COVERBENCH_RUN_TOKEN");
  }
  RunGuard(const RunGuard&) = delete;
  RunGuard& operator=(const RunGuard&) = delete;

 private:
  std::string token_, old_;
  bool had_old_ = false;
  pid_t guardian_ = -1;
  int pipe_ = -1;
};

}  // namespace

double hardDeadlineSeconds(const RunSpec& spec) {
  // Replanning plans once more per fraction (the plan from scratch with the obstacles known) and
  // repairs and scores up to twice: two budgets more per fraction.
  return 2.0 * spec.time_limit_s * static_cast<double>(std::max(1, spec.repetitions) + 2 * spec.replanning.at.size()) + 5.0;
}

std::string serializeRecord(const RunRecord& r) {
  Writer w;
  w.u64(kRecordMagic);
  forEachRunField(r, [&](const RunField&, const auto& value) { w.field(value); });
  w.u64(r.plan_times_ms.size());
  for (double t : r.plan_times_ms) w.f64(t);
  w.u64(r.metrics.size());
  for (const auto& [name, value] : r.metrics) w.str(name), w.f64(value);
  w.map(r.stats);
  w.map(r.timings_ms);
  w.str(r.path.waypoints.empty() ? std::string() : encodePath(r.path));
  w.u64(r.replans.size());
  for (const ReplanRecord& p : r.replans) {
    w.f64(p.fraction);
    w.str(p.repair);
    w.u64(p.obstacles);
    w.u64(p.requested);
    w.str(p.obstacles_json);
    w.str(p.status);
    w.str(p.reason);
    w.u64(p.valid ? 1 : 0);
    w.f64(p.repair_ms);
    w.map(p.figures);
    w.str(p.path.waypoints.empty() ? std::string() : encodePath(p.path));
    w.u64(p.cut_waypoint);
  }
  return w.take();
}

RunRecord deserializeRecord(const std::string& bytes) {
  Reader in(bytes);
  if (in.u64() != kRecordMagic) throw std::runtime_error("not a run record");
  RunRecord r;
  forEachRunField(r, [&](const RunField&, auto& value) { in.field(value); });
  for (std::uint64_t n = in.count(); n > 0; --n) r.plan_times_ms.push_back(in.f64());
  for (std::uint64_t n = in.count(); n > 0; --n) {
    std::string name = in.str();
    r.metrics.emplace_back(std::move(name), in.f64());
  }
  r.stats = in.map();
  r.timings_ms = in.map();
  const std::string path = in.str();
  if (!path.empty()) r.path = decodePath(path), r.path_blob = path;
  for (std::uint64_t n = in.count(); n > 0; --n) {
    ReplanRecord p;
    p.fraction = in.f64();
    p.repair = in.str();
    p.obstacles = in.u64();
    p.requested = in.u64();
    p.obstacles_json = in.str();
    p.status = in.str();
    p.reason = in.str();
    p.valid = in.u64() != 0;
    p.repair_ms = in.f64();
    p.figures = in.map();
    if (const std::string blob = in.str(); !blob.empty()) p.path = decodePath(blob);
    p.cut_waypoint = in.u64();
    r.replans.push_back(std::move(p));
  }
  if (!in.done()) throw std::runtime_error("trailing bytes after the run record");
  return r;
}

void executeIsolated(const std::vector<const RunSpec*>& runs, unsigned workers,
                     const std::function<void(const RunSpec&, RunRecord)>& done) {
  ::signal(SIGPIPE, SIG_IGN);  // a worker that died shows as a failed write, not a dead runner
  const RunGuard guard;       // destroyed after the pool: every process the run started is gone
  Pool pool(runs, std::max(1u, std::min<unsigned>(workers, static_cast<unsigned>(std::max<std::size_t>(runs.size(), 1)))));
  pool.run(done);
}

}  // namespace coverbench
