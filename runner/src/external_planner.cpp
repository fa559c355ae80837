// Planners outside the tree: the manifest, protocol 1 (a problem per JSON line in, a plan per JSON
// line out), and the planner's process, started once and kept for the next run.
#include "coverbench/external_planner.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "coverbench/files.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench::external {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

/// What a manifest declares beyond PlannerInfo: how to start the planner.
struct Launch {
  std::vector<std::string> command;  ///< argv; relative programs and files resolve in `folder`
  std::string folder;                ///< the manifest's folder: the process's working directory
  std::string manifest;              ///< the manifest's absolute path (names the process)
};

std::string slurp(const std::string& path, const std::string& source, const std::string& field) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source, field, "cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// --- the manifest -------------------------------------------------------------------------------

class ManifestReader {
 public:
  explicit ManifestReader(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(source_, field, problem);
  }
  void onlyKeys(const json& obj, const std::string& where, const std::set<std::string>& allowed) const {
    for (const auto& [key, value] : obj.items())
      if (!allowed.count(key)) fail(where.empty() ? key : where + "." + key, "unknown key");
  }
  std::string text(const json& obj, const std::string& key, const std::string& field, bool required = true) const {
    if (!obj.contains(key)) {
      if (required) fail(field, "missing");
      return "";
    }
    if (!obj[key].is_string()) fail(field, "must be a string");
    return obj[key].get<std::string>();
  }
  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "must be finite");
    return d;
  }

 private:
  std::string source_;
};

// --- the process ---------------------------------------------------------------------------------

std::string describeExit(int status) {
  if (WIFSIGNALED(status)) {
    const char* name = ::strsignal(WTERMSIG(status));
    return "died of signal " + std::to_string(WTERMSIG(status)) + (name ? std::string(" (") + name + ")" : "");
  }
  return "exited with code " + std::to_string(WEXITSTATUS(status));
}

std::string mib(double bytes) { return std::to_string(static_cast<long long>(bytes / 1048576.0)); }

/// Reads a small file whole ("" when it cannot be read).
std::string readSmall(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool writeSmall(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return ok;
}

/// The processes now running (not zombies) whose environment holds `entry` ("NAME=value").
std::vector<pid_t> processesWithEntry(const std::string& entry) {
  std::vector<pid_t> out;
  DIR* proc = ::opendir("/proc");
  if (!proc) return out;
  while (const dirent* e = ::readdir(proc)) {
    char* end = nullptr;
    const long pid = std::strtol(e->d_name, &end, 10);
    if (pid <= 0 || *end != '\0' || pid == ::getpid()) continue;
    const std::string env = readSmall("/proc/" + std::string(e->d_name) + "/environ");
    std::size_t at = 0;
    bool found = false;
    while (at < env.size() && !found) {
      const std::size_t stop = env.find('\0', at);
      const std::size_t len = (stop == std::string::npos ? env.size() : stop) - at;
      found = len == entry.size() && env.compare(at, len, entry) == 0;
      if (stop == std::string::npos) break;
      at = stop + 1;
    }
    if (!found) continue;
    const std::string stat = readSmall("/proc/" + std::string(e->d_name) + "/stat");
    const std::size_t paren = stat.rfind(')');
    if (paren != std::string::npos && paren + 2 < stat.size() && (stat[paren + 2] == 'Z' || stat[paren + 2] == 'X')) continue;
    out.push_back(static_cast<pid_t>(pid));
  }
  ::closedir(proc);
  return out;
}

/// The pids in a cgroup ("" folder: none).
std::vector<pid_t> cgroupPids(const std::string& folder) {
  std::vector<pid_t> out;
  if (folder.empty()) return out;
  std::istringstream in(readSmall(folder + "/cgroup.procs"));
  for (long pid = 0; in >> pid;)
    if (pid > 0 && pid != ::getpid()) out.push_back(static_cast<pid_t>(pid));
  return out;
}

/// The memory controller's folder of this process's cgroup (cgroup v1), where a planner's cgroup
/// is made; "" when there is none. Where there is none, or a cgroup cannot be made in it, a
/// planner's processes are found by their environment and their memory is their summed resident sets.
const std::string& memoryCgroupBase() {
  static const std::string base = [] {
    // COVERBENCH_PLANNER_CGROUPS=0: none (what a machine without the controller does; tests).
    if (const char* use = std::getenv("COVERBENCH_PLANNER_CGROUPS"); use && std::string(use) == "0") return std::string();
    std::istringstream in(readSmall("/proc/self/cgroup"));
    for (std::string line; std::getline(in, line);) {
      const std::size_t a = line.find(':'), b = line.find(':', a + 1);
      if (a == std::string::npos || b == std::string::npos) continue;
      std::string controllers = "," + line.substr(a + 1, b - a - 1) + ",";
      if (controllers.find(",memory,") == std::string::npos) continue;
      // Whether cgroups may be made there shows when a planner's is made (start()).
      const std::string folder = "/sys/fs/cgroup/memory" + line.substr(b + 1);
      struct stat st {};
      if (::stat((folder + "/cgroup.procs").c_str(), &st) != 0) return std::string();
      return folder;
    }
    return std::string();
  }();
  return base;
}

/// "oom_kill N" of a v1 memory cgroup: how many of its processes the kernel killed at its limit.
long long oomKills(const std::string& folder) {
  std::istringstream in(readSmall(folder + "/memory.oom_control"));
  for (std::string key; in >> key;) {
    long long n = 0;
    in >> n;
    if (key == "oom_kill") return n;
  }
  return 0;
}

/// Kills every process in `folder` (a cgroup, may be "") and every process whose environment holds
/// `entry`, until none is left (a process may fork while it is being killed), then removes the cgroup.
void killTree(const std::string& folder, const std::string& entry) {
  for (int round = 0; round < 200; ++round) {
    std::vector<pid_t> pids = cgroupPids(folder);
    const std::vector<pid_t> tagged = entry.empty() ? std::vector<pid_t>() : processesWithEntry(entry);
    pids.insert(pids.end(), tagged.begin(), tagged.end());
    if (pids.empty()) break;
    for (pid_t p : pids) ::kill(p, SIGKILL);
    ::usleep(round < 10 ? 1000 : 10000);
  }
  for (int i = 0; !folder.empty() && i < 200 && ::rmdir(folder.c_str()) != 0 && errno == EBUSY; ++i) ::usleep(5000);
}

/// This process's sequence of planner processes (names their cgroups and tokens).
long long nextProcessNumber() {
  static long long n = 0;
  return ++n;
}

/// One planner process: started on the first question, asked one line at a time. It and every
/// process it starts (its tree) are one unit: in a cgroup of their own where the memory controller
/// allows it (limited and accounted together), and tagged by an environment variable
/// (COVERBENCH_PLANNER_TOKEN), so that a child that left the process group (setsid) is found and
/// killed with the rest.
class PlannerProcess {
 public:
  explicit PlannerProcess(Launch launch) : launch_(std::move(launch)) {}
  ~PlannerProcess() { stop(); }
  PlannerProcess(const PlannerProcess&) = delete;
  PlannerProcess& operator=(const PlannerProcess&) = delete;

  struct Answer {
    bool ok = false;
    std::string line;                        ///< the answer, without its newline
    PlanStatus failure = PlanStatus::Error;  ///< when not ok
    std::string reason;
    std::string stderr_tail;  ///< the end of what its processes wrote to stderr meanwhile (UTF-8)
    double cpu_s = NAN;       ///< their CPU time meanwhile (s)
    double peak_bytes = NAN;  ///< their peak memory meanwhile (bytes)
  };

  /// Sends `request` and reads one line back, within `timeout_s` and `memory_limit` bytes for the
  /// planner's processes together (0: none). Any failure stops the process and its tree. The
  /// answer carries the end of the stderr written meanwhile, and the processes' CPU and memory.
  Answer ask(const std::string& request, double timeout_s, std::size_t memory_limit) {
    drainStderr();  // written between two questions: passed on, not this question's
    tail_.clear();
    passed_on_ = 0;
    measuring_ = false;
    Answer a = askOnce(request, timeout_s, memory_limit);
    drainStderr();
    a.stderr_tail = stderrTail();
    a.cpu_s = cpu_s_;
    a.peak_bytes = peak_bytes_;
    return a;
  }

  /// Stops the process and every process it started.
  void stop() {
    drainStderr();
    if (err_ >= 0) ::close(err_);
    err_ = -1;
    if (in_ >= 0) ::close(in_);
    if (out_ >= 0) ::close(out_);
    in_ = out_ = -1;
    if (pid_ > 0) {
      ::kill(-pid_, SIGKILL);
      ::kill(pid_, SIGKILL);
      int status = 0;
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
    if (!token_.empty()) killTree(cgroup_, "COVERBENCH_PLANNER_TOKEN=" + token_);
    pid_ = -1;
    cgroup_.clear();
    token_.clear();
    limit_ = 0;
  }

 private:
  Answer askOnce(const std::string& request, double timeout_s, std::size_t memory_limit) {
    Answer a;
    if (pid_ > 0 && !leftoverCheck(a)) return a;
    if (pid_ > 0 && memory_limit != limit_ && !setLimit(memory_limit)) stop();  // restarted under the new limit
    if (pid_ < 0 && !start(a, memory_limit)) return a;
    startMeasuring();
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                             std::chrono::duration<double>(std::min(timeout_s, 1e9)));
    std::size_t sent = 0;
    std::string got;
    for (;;) {
      const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
      if (overMemory(a)) return a;
      if (left <= 0.0) return fail(a, PlanStatus::Timeout, "the planner's process did not answer within the time limit (killed)");
      pollfd fds[3] = {{out_, POLLIN, 0}, {err_, POLLIN, 0}, {in_, POLLOUT, 0}};
      const int n = ::poll(fds, sent < request.size() ? 3 : 2, static_cast<int>(std::clamp(left * 1000.0, 1.0, 10.0)));
      if (n < 0 && errno != EINTR) return fail(a, PlanStatus::Crash, std::string("poll: ") + std::strerror(errno));
      if (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) drainStderr();
      // The process it started is gone while one of its own keeps the output open (no hang-up
      // comes): a crash with its exit, not a timeout at the limit. Once what it wrote is read.
      if (!(fds[0].revents & (POLLIN | POLLHUP | POLLERR)) && exitedMeanwhile()) {
        pollfd o{out_, POLLIN, 0};
        if (::poll(&o, 1, 0) <= 0) return died(a, "before answering, while a process it started kept its output open");
      }
      if (sent < request.size() && (fds[2].revents & (POLLOUT | POLLERR | POLLHUP))) {
        const ssize_t w = ::write(in_, request.data() + sent, request.size() - sent);
        if (w < 0 && errno != EAGAIN && errno != EINTR) return died(a, "stopped reading its input");
        if (w > 0) sent += static_cast<std::size_t>(w);
      }
      if (fds[0].revents & (POLLIN | POLLHUP | POLLERR)) {
        static thread_local std::vector<char> buf(std::size_t{1} << 20);
        const ssize_t r = ::read(out_, buf.data(), buf.size());
        if (r == 0) return died(a, "closed its output before answering");
        if (r < 0) {
          if (errno == EAGAIN || errno == EINTR) continue;
          return died(a, std::string("read: ") + std::strerror(errno));
        }
        const std::size_t scanned = got.size();  // only the new bytes are searched for the newline
        got.append(buf.data(), static_cast<std::size_t>(r));
        const std::size_t nl = got.find('\n', scanned);
        if (nl != std::string::npos) {
          if (nl + 1 != got.size())
            return fail(a, PlanStatus::InvalidOutput, "the planner printed more than one line for one problem");
          if (overMemory(a)) return a;  // a child killed at the limit, and the planner answered anyway
          stopMeasuring();
          a.ok = true;
          a.line = got.substr(0, nl);
          return a;
        }
        if (got.size() > kMaxAnswerBytes)
          return fail(a, PlanStatus::InvalidOutput,
                      "the planner's answer is over " + std::to_string(kMaxAnswerBytes >> 20) + " MiB (killed)");
      }
    }
  }

  /// Reads what the planner's processes wrote to stderr so far (without waiting), passes it on
  /// to this process's stderr and keeps its end; closes the pipe at its end.
  void drainStderr() {
    if (err_ < 0) return;
    static thread_local std::vector<char> buf(std::size_t{1} << 16);
    for (std::size_t total = 0; total < (std::size_t{16} << 20);) {  // a flood waits for the next poll
      const ssize_t r = ::read(err_, buf.data(), buf.size());
      if (r < 0 && errno == EINTR) continue;
      if (r == 0) {
        ::close(err_);
        err_ = -1;
      }
      if (r <= 0) return;
      const auto n = static_cast<std::size_t>(r);
      total += n;
      passOn(buf.data(), n);
      tail_.append(buf.data(), n);
      if (tail_.size() > 2 * kStderrTailBytes) tail_.erase(0, tail_.size() - kStderrTailBytes);
    }
  }

  /// Passes a planner's stderr on to ours as it came, best effort and bounded: at most
  /// kPassedOnBytes a question (then one line says the rest is not shown), and never waiting for
  /// a reader (a pipe nobody reads held the planner past its time limit): what ours cannot take
  /// at once is dropped. The kept tail is not affected.
  void passOn(const char* data, std::size_t n) {
    if (passed_on_ >= kPassedOnBytes) return;
    if (passed_on_ + n > kPassedOnBytes) {
      n = kPassedOnBytes - passed_on_;
      passed_on_ = kPassedOnBytes;
    } else {
      passed_on_ += n;
    }
    for (std::size_t off = 0; off < n;) {
      pollfd p{STDERR_FILENO, POLLOUT, 0};
      if (::poll(&p, 1, 0) <= 0 || !(p.revents & POLLOUT)) return;
      const ssize_t w = ::write(STDERR_FILENO, data + off, std::min<std::size_t>(n - off, 4096));  // PIPE_BUF: no wait
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) return;
      off += static_cast<std::size_t>(w);
    }
    if (passed_on_ == kPassedOnBytes) {
      static const char kCut[] = "\n[coverbench: the planner's stderr past 1 MiB in this plan is not shown]\n";
      pollfd p{STDERR_FILENO, POLLOUT, 0};
      if (::poll(&p, 1, 0) > 0 && (p.revents & POLLOUT)) (void)!::write(STDERR_FILENO, kCut, sizeof kCut - 1);
    }
  }

  /// The last kStderrTailBytes kept, from the first whole character on, as valid UTF-8.
  std::string stderrTail() const {
    std::size_t from = tail_.size() > kStderrTailBytes ? tail_.size() - kStderrTailBytes : 0;
    if (from > 0)
      for (int k = 0; k < 3 && from < tail_.size() && (static_cast<unsigned char>(tail_[from]) & 0xC0) == 0x80; ++k) ++from;
    return toValidUtf8(tail_.substr(from));
  }

  /// The planner's processes now: its cgroup's, or those carrying its token.
  std::vector<pid_t> treePids() const {
    if (!cgroup_.empty()) return cgroupPids(cgroup_);
    return processesWithEntry("COVERBENCH_PLANNER_TOKEN=" + token_);
  }

  /// A process's CPU time (s) from /proc: its own and that of its children it waited for; NaN
  /// when it is gone.
  static double processCpu(pid_t pid) {
    const std::string stat = readSmall("/proc/" + std::to_string(pid) + "/stat");
    const std::size_t paren = stat.rfind(')');
    if (paren == std::string::npos) return NAN;
    std::istringstream in(stat.substr(paren + 2));
    std::string field;
    double ticks = 0.0;
    for (int i = 3; i <= 17 && in >> field; ++i)  // utime, stime, cutime, cstime are fields 14-17
      if (i >= 14) ticks += std::atof(field.c_str());
    return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
  }

  /// The start of a question's measurement: each process's CPU time, and the peaks reset (the
  /// cgroup's peak usage; without one, each process's peak resident set).
  void startMeasuring() {
    measuring_ = true;
    cpu_s_ = peak_bytes_ = NAN;
    reaped_cpu_s_ = reaped_peak_bytes_ = NAN;
    cpu_before_.clear();
    const std::vector<pid_t> pids = treePids();
    for (pid_t p : pids) {
      const double c = processCpu(p);
      if (std::isfinite(c)) cpu_before_[p] = c;
    }
    if (!cgroup_.empty()) {
      writeSmall(cgroup_ + "/memory.max_usage_in_bytes", "0");
    } else {
      for (pid_t p : pids) writeSmall("/proc/" + std::to_string(p) + "/clear_refs", "5");
    }
  }

  /// The end of it (before the processes are stopped): CPU time since the start summed over the
  /// processes (the planner's own from its wait status when it has ended), and the peak.
  void stopMeasuring() {
    if (!measuring_) return;
    measuring_ = false;
    const std::vector<pid_t> pids = treePids();
    double cpu = 0.0, rss = 0.0;
    bool root_seen = false;
    for (pid_t p : pids) {
      const double c = processCpu(p);
      if (!std::isfinite(c)) continue;
      root_seen = root_seen || p == pid_;
      const auto before = cpu_before_.find(p);
      cpu += std::max(0.0, c - (before == cpu_before_.end() ? 0.0 : before->second));
      std::ifstream in("/proc/" + std::to_string(p) + "/status");
      for (std::string line; std::getline(in, line);)
        if (line.rfind("VmHWM:", 0) == 0) rss += std::atof(line.c_str() + 6) * 1024.0;
    }
    if (!root_seen && std::isfinite(reaped_cpu_s_)) {  // it ended: its wait status's rusage
      const auto before = cpu_before_.find(reaped_pid_);
      cpu += std::max(0.0, reaped_cpu_s_ - (before == cpu_before_.end() ? 0.0 : before->second));
      rss += reaped_peak_bytes_;
    }
    cpu_s_ = cpu;
    peak_bytes_ = rss;
    if (!cgroup_.empty()) {
      const double usage = std::atof(readSmall(cgroup_ + "/memory.max_usage_in_bytes").c_str());
      if (usage > 0.0) peak_bytes_ = usage;
    }
  }

  /// Output left over from the last answer (a second line, written after it was read) fails the
  /// run about to be asked: it would otherwise be read as that run's answer.
  bool leftoverCheck(Answer& a) {
    pollfd fd{out_, POLLIN, 0};
    if (::poll(&fd, 1, 0) <= 0 || !(fd.revents & POLLIN)) return true;
    char buf[256];
    const ssize_t r = ::read(out_, buf, sizeof buf);
    if (r <= 0) return true;  // closed: the process ended between runs; asking it says how
    std::string start(buf, static_cast<std::size_t>(std::min<ssize_t>(r, 40)));
    for (char& c : start)
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';  // the reason stays one line
    fail(a, PlanStatus::InvalidOutput,
         "the planner wrote after its previous answer ('" + start + "...'): one problem gets one line, and nothing follows it");
    return false;
  }

  /// The memory limit of the planner's cgroup (0: none); false when it cannot be set.
  bool setLimit(std::size_t memory_limit) {
    if (!cgroup_.empty()) {
      const std::string v = memory_limit > 0 ? std::to_string(memory_limit) : std::string("-1");
      if (!writeSmall(cgroup_ + "/memory.limit_in_bytes", v)) return false;
      writeSmall(cgroup_ + "/memory.memsw.limit_in_bytes", v);  // where swap is accounted: no swapping past it
    }
    limit_ = memory_limit;
    return true;
  }

  /// Past the memory limit: the kernel killed one of the planner's processes at its cgroup's limit,
  /// or (without a cgroup) their resident sets add up to more than the limit.
  bool overMemory(Answer& a) {
    if (limit_ == 0) return false;
    if (!cgroup_.empty()) {
      if (oomKills(cgroup_) == 0) return false;
      fail(a, PlanStatus::MemoryLimit,
           "the planner's processes grew past the memory limit of " + mib(static_cast<double>(limit_)) +
               " MiB (the kernel stopped one at the limit; all killed)");
      return true;
    }
    double rss = 0.0;
    std::vector<pid_t> pids = processesWithEntry("COVERBENCH_PLANNER_TOKEN=" + token_);
    for (pid_t p : pids) {
      std::ifstream in("/proc/" + std::to_string(p) + "/status");
      for (std::string line; std::getline(in, line);)
        if (line.rfind("VmRSS:", 0) == 0) rss += std::atof(line.c_str() + 6) * 1024.0;
    }
    if (rss <= static_cast<double>(limit_)) return false;
    fail(a, PlanStatus::MemoryLimit,
         "the planner's processes grew to " + mib(rss) + " MiB, past the memory limit of " +
             mib(static_cast<double>(limit_)) + " MiB (killed)");
    return true;
  }

  bool start(Answer& a, std::size_t memory_limit) {
    int to_child[2], from_child[2], err_child[2];
    if (::pipe2(to_child, O_CLOEXEC) != 0 || ::pipe2(from_child, O_CLOEXEC) != 0 || ::pipe2(err_child, O_CLOEXEC) != 0) {
      fail(a, PlanStatus::Error, std::string("pipe: ") + std::strerror(errno));
      return false;
    }
    const long long number = nextProcessNumber();
    token_ = std::to_string(::getpid()) + "-" + std::to_string(number);
    // The run's token (set by the runner) names the cgroup, so the runner's guardian finds it.
    const char* run = std::getenv("COVERBENCH_RUN_TOKEN");
    cgroup_.clear();
    if (!memoryCgroupBase().empty()) {
      const std::string folder = memoryCgroupBase() + "/coverbench-" + (run && *run ? std::string(run) : "p") + "-" + token_;
      if (::mkdir(folder.c_str(), 0755) == 0) cgroup_ = folder;
    }
    if (!setLimit(memory_limit)) {  // no limit can be set on it: without a cgroup, summed resident sets
      killTree(cgroup_, "");
      cgroup_.clear();
      setLimit(memory_limit);
    }
    const std::string procs = cgroup_.empty() ? std::string() : cgroup_ + "/cgroup.procs";
    const std::string token_entry = token_;
    std::vector<char*> argv;
    for (std::string& s : launch_.command) argv.push_back(s.data());
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    // The parent-death signal follows the thread that forks: only the main thread's end is the
    // host's end (a planner started from a Python thread that ends must live on for the next plan).
    const bool main_thread = ::gettid() == parent;
    const pid_t pid = ::fork();
    if (pid < 0) {
      fail(a, PlanStatus::Error, std::string("fork: ") + std::strerror(errno));
      return false;
    }
    if (pid == 0) {
      if (main_thread) {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // its host died (kill -9): it dies too
        if (::getppid() != parent) ::_exit(125);
      }
      ::setpgid(0, 0);  // its own group: killed whole, children included
      if (!procs.empty()) {  // into its cgroup before it can start anything
        const int fd = ::open(procs.c_str(), O_WRONLY);
        if (fd >= 0) {
          const ssize_t ignored = ::write(fd, "0", 1);
          (void)ignored;
          ::close(fd);
        }
      }
      ::setenv("COVERBENCH_PLANNER_TOKEN", token_entry.c_str(), 1);
      ::dup2(to_child[0], STDIN_FILENO);
      ::dup2(from_child[1], STDOUT_FILENO);
      ::dup2(err_child[1], STDERR_FILENO);  // read by the host: passed on, and its end kept
      // The worker's limits were set for its own run: the planner's processes are held to the run's
      // limits here, by the host (time, their cgroup's memory), not by the worker's address space.
      const rlimit none{RLIM_INFINITY, RLIM_INFINITY};
      ::setrlimit(RLIMIT_AS, &none);
      ::setrlimit(RLIMIT_CPU, &none);
      ::signal(SIGPIPE, SIG_DFL);
      if (::chdir(launch_.folder.c_str()) != 0) ::_exit(126);
#ifdef COVERBENCH_PYTHON_PACKAGE_DIR
      // The coverbench Python package (coverbench.serve) for planners written in Python.
      const char* old = std::getenv("PYTHONPATH");
      const std::string path = std::string(COVERBENCH_PYTHON_PACKAGE_DIR) + (old && *old ? std::string(":") + old : "");
      ::setenv("PYTHONPATH", path.c_str(), 1);
#endif
      ::execvp(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(to_child[0]);
    ::close(from_child[1]);
    ::close(err_child[1]);
    in_ = to_child[1];
    out_ = from_child[0];
    err_ = err_child[0];
    ::fcntl(err_, F_SETFL, ::fcntl(err_, F_GETFL) | O_NONBLOCK);
    ::fcntl(in_, F_SETFL, ::fcntl(in_, F_GETFL) | O_NONBLOCK);
    ::fcntl(out_, F_SETFL, ::fcntl(out_, F_GETFL) | O_NONBLOCK);
    pid_ = pid;
    return true;
  }

  Answer& fail(Answer& a, PlanStatus status, std::string reason) {
    stopMeasuring();
    stop();
    a.ok = false;
    a.failure = status;
    a.reason = std::move(reason);
    return a;
  }

  /// Whether the process it started has exited (not reaped here: died() reaps it).
  bool exitedMeanwhile() const {
    if (pid_ <= 0) return false;
    siginfo_t info{};
    return ::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_;
  }

  /// The process ended (or will): crash, with how it ended; memory_limit when the kernel stopped
  /// one of its processes at the limit.
  Answer& died(Answer& a, const std::string& what) {
    int status = 0;
    pid_t r = 0;
    rusage usage{};
    for (int i = 0; i < 50 && (r = ::wait4(pid_, &status, WNOHANG, &usage)) == 0; ++i) ::usleep(2000);
    const bool reaped = r == pid_;
    if (reaped) {
      reaped_pid_ = pid_;
      reaped_cpu_s_ = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                      static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
      reaped_peak_bytes_ = static_cast<double>(usage.ru_maxrss) * 1024.0;  // its lifetime's peak
      pid_ = -1;
    }
    if (overMemory(a)) return a;
    std::string reason = "the planner's process " + (reaped ? describeExit(status) + " (" + what + ")" : what);
    if (reaped && WIFEXITED(status) && WEXITSTATUS(status) == 127)
      reason = "the planner's command could not be started: " + launch_.command.front();
    return fail(a, PlanStatus::Crash, reason);
  }

  Launch launch_;
  pid_t pid_ = -1;
  int in_ = -1, out_ = -1, err_ = -1;
  std::string tail_;  ///< the end of its stderr during the current question (raw bytes)
  static constexpr std::size_t kPassedOnBytes = std::size_t{1} << 20;  ///< of its stderr shown, a question
  std::size_t passed_on_ = 0;  ///< of the current question's stderr passed on
  // The current question's measurement (startMeasuring, stopMeasuring).
  bool measuring_ = false;
  std::map<pid_t, double> cpu_before_;
  double cpu_s_ = NAN, peak_bytes_ = NAN;
  pid_t reaped_pid_ = -1;
  double reaped_cpu_s_ = NAN, reaped_peak_bytes_ = NAN;
  std::string cgroup_;     ///< its cgroup's folder ("" without one)
  std::string token_;      ///< COVERBENCH_PLANNER_TOKEN of its processes
  std::size_t limit_ = 0;  ///< the memory limit it runs under (bytes, 0: none)
};

/// The processes of this process (a worker keeps its planners' processes across runs), by manifest.
std::map<std::string, std::unique_ptr<PlannerProcess>>& processes() {
  static std::map<std::string, std::unique_ptr<PlannerProcess>> all;
  return all;
}

class ExternalPlanner final : public Planner {
 public:
  explicit ExternalPlanner(Launch launch) : launch_(std::move(launch)) {}
  PlanResult plan(const Problem& problem, const Budget& budget) override {
    ::signal(SIGPIPE, SIG_IGN);  // a planner that died shows as a failed write
    auto& proc = processes()[launch_.manifest];
    if (!proc) proc = std::make_unique<PlannerProcess>(launch_);
    static long long next_id = 0;
    const long long id = ++next_id;
    const double limit = budget.remainingSeconds();
    const PlannerProcess::Answer a =
        proc->ask(requestJson(problem, limit, id) + "\n", limit, problem.memory_limit_bytes);
    auto withProcess = [&](PlanResult r) {
      r.stderr_tail = a.stderr_tail;
      r.process_cpu_s = a.cpu_s;
      r.process_peak_bytes = a.peak_bytes;
      return r;
    };
    if (!a.ok) return withProcess(PlanResult::failure(a.failure, a.reason));
    PlanResult result;
    std::string why;
    if (!readAnswer(a.line, id, result, why)) {
      proc.reset();  // a process that breaks the protocol is not asked again
      return withProcess(PlanResult::failure(PlanStatus::InvalidOutput, "the planner's answer: " + why));
    }
    return withProcess(std::move(result));
  }

 private:
  Launch launch_;
};

PlanStatus answerStatus(const std::string& s, bool& known) {
  known = true;
  for (PlanStatus p : {PlanStatus::Ok, PlanStatus::Partial, PlanStatus::NoReachableArea, PlanStatus::InvalidInput,
                       PlanStatus::Timeout, PlanStatus::Error})
    if (s == toString(p)) return p;
  known = false;
  return PlanStatus::Error;
}

}  // namespace

std::string requestJson(const Problem& problem, double time_limit_s, long long id) {
  json p;
  p["wall"] = json::parse(wallToJson(*problem.wall));
  p["tool"] = {{"width", problem.tool.tool_width}, {"clearance", problem.tool.clearance}};
  json vehicle = {{"model", toString(problem.vehicle.kind)}};
  if (problem.vehicle.isCar()) {
    vehicle["turn_radius"] = problem.vehicle.turn_radius;
    vehicle["reverse"] = problem.vehicle.reverse;
  } else if (!problem.vehicle.isDefault()) {
    vehicle["lift_s"] = problem.vehicle.lift_s;
    vehicle["lower_s"] = problem.vehicle.lower_s;
  }
  p["vehicle"] = vehicle;
  p["params"] = paramsJson(problem.params);
  p["seed"] = problem.seed;
  if (std::isfinite(time_limit_s)) p["time_limit_s"] = time_limit_s;
  return json{{"protocol", kProtocolVersion}, {"id", id}, {"problem", p}}.dump();
}

void stopPlannerProcesses() { processes().clear(); }

void killRunProcesses(const std::string& run_token, int spare) {
  const std::string& base = memoryCgroupBase();
  std::vector<std::string> folders;
  if (!base.empty())
    if (DIR* d = ::opendir(base.c_str())) {
      const std::string prefix = "coverbench-" + run_token + "-";
      while (const dirent* e = ::readdir(d))
        if (std::string(e->d_name).rfind(prefix, 0) == 0) folders.push_back(base + "/" + e->d_name);
      ::closedir(d);
    }
  const std::string entry = "COVERBENCH_RUN_TOKEN=" + run_token;
  for (int round = 0; round < 200; ++round) {
    std::vector<pid_t> pids = processesWithEntry(entry);
    for (const std::string& f : folders)
      for (pid_t p : cgroupPids(f)) pids.push_back(p);
    pids.erase(std::remove(pids.begin(), pids.end(), spare), pids.end());
    if (pids.empty()) break;
    for (pid_t p : pids) ::kill(p, SIGKILL);
    ::usleep(round < 10 ? 1000 : 10000);
  }
  for (const std::string& f : folders) killTree(f, "");
}

static std::size_t answerProblem(const std::string& line, std::string& why) {
  // Before any parsing: a line of 20 MiB of '[' would cost the parser gigabytes and seconds.
  int depth = 0;
  std::size_t arrays = 0, keys = 0, values = 1;
  bool in_string = false, escaped = false;
  for (const char c : line) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxAnswerDepth) {
        why = "nested deeper than " + std::to_string(kMaxAnswerDepth) + " levels (an answer needs 3)";
        return 1;
      }
      if (c == '[' && ++arrays > kMaxAnswerWaypoints + 8) {
        why = "holds more than " + std::to_string(kMaxAnswerWaypoints) + " waypoints (the scoring limit)";
        return 1;
      }
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ':' && ++keys > kMaxAnswerKeys) {
      why = "holds more than " + std::to_string(kMaxAnswerKeys) + " keys";
      return 1;
    } else if (c == ',' && ++values > kMaxAnswerValues) {
      why = "holds more than " + std::to_string(kMaxAnswerValues) + " values (2 per waypoint, 1 per segment's tool_on and bulge)";
      return 1;
    }
  }
  return 0;
}

bool readAnswer(const std::string& line, long long id, PlanResult& result, std::string& why) {
  auto bad = [&](const std::string& text) {
    why = toValidUtf8(text);  // it may quote the planner's bytes
    return false;
  };
  if (line.size() > kMaxAnswerBytes)
    return bad("over " + std::to_string(kMaxAnswerBytes >> 20) + " MiB");
  if (answerProblem(line, why) != 0) return bad(why);
  json a;
  try {
    a = parseJsonStrict(line, "answer");  // no duplicate key: a second "status" is not read over the first
  } catch (const InputError& e) {
    if (e.field() != "(document)") return bad(e.field() + ": " + e.problem());
    return bad("not JSON (" + std::to_string(line.size()) + " bytes: " + line.substr(0, 60) + "): " + e.problem());
  }
  if (!a.is_object()) return bad("must be a JSON object");
  for (const auto& [key, value] : a.items())
    if (key != "protocol" && key != "id" && key != "status" && key != "reason" && key != "waypoints" &&
        key != "tool_on" && key != "bulge" && key != "stats")
      return bad(key + ": unknown key");
  if (!a.contains("protocol") || a["protocol"] != kProtocolVersion)
    return bad("protocol: must be " + std::to_string(kProtocolVersion));
  if (!a.contains("id") || !a["id"].is_number_integer() || a["id"].get<long long>() != id)
    return bad("id: must be the request's (" + std::to_string(id) + ")");
  if (!a.contains("status") || !a["status"].is_string()) return bad("status: missing");
  bool known = false;
  result.status = answerStatus(a["status"].get<std::string>(), known);
  if (!known)
    return bad("status: '" + toValidUtf8(a["status"].get<std::string>()).substr(0, 200) +
               "' is none of ok, partial, no_reachable_area, invalid_input, timeout, error");
  if (a.contains("reason")) {
    if (!a["reason"].is_string()) return bad("reason: must be a string");
    // A planner's own words, kept as text: bytes that are not UTF-8 and NULs become U+FFFD (a raw
    // 0xFF ended the JSON card; a NUL cut the stored reason).
    result.reason = toValidUtf8(a["reason"].get<std::string>());
  }
  if (a.contains("stats")) {
    if (!a["stats"].is_object()) return bad("stats: must be an object of numbers");
    for (const auto& [name, v] : a["stats"].items()) {
      if (!v.is_number() || !std::isfinite(v.get<double>())) return bad("stats." + name + ": must be a finite number");
      result.stats[name] = v.get<double>();
    }
  }
  if (!result.hasPath()) {
    if (a.contains("waypoints") && !a["waypoints"].empty()) return bad("waypoints: a failed plan has no path");
    if (result.reason.empty()) return bad("reason: a failed plan says why");
    return true;
  }
  if (!a.contains("waypoints") || !a["waypoints"].is_array() || a["waypoints"].empty())
    return bad("waypoints: a plan with status " + toString(result.status) + " needs a non-empty list of [x, y]");
  const json& w = a["waypoints"];
  Path& path = result.path;
  path.waypoints.reserve(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const json& p = w[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      return bad("waypoints[" + std::to_string(i) + "]: must be [x, y]");
    const Point pt{p[0].get<double>(), p[1].get<double>()};
    if (!std::isfinite(pt.x) || !std::isfinite(pt.y)) return bad("waypoints[" + std::to_string(i) + "]: must be finite");
    path.waypoints.push_back(pt);
  }
  const std::size_t segments = w.size() - 1;
  if (!a.contains("tool_on") || !a["tool_on"].is_array() || a["tool_on"].size() != segments)
    return bad("tool_on: must be a list of " + std::to_string(segments) + " booleans (one per segment)");
  for (std::size_t i = 0; i < segments; ++i) {
    if (!a["tool_on"][i].is_boolean()) return bad("tool_on[" + std::to_string(i) + "]: must be true or false");
    path.tool_on.push_back(a["tool_on"][i].get<bool>());
  }
  if (a.contains("bulge")) {
    const json& b = a["bulge"];
    if (!b.is_array() || b.size() != segments)
      return bad("bulge: must be a list of " + std::to_string(segments) + " numbers (one per segment)");
    for (std::size_t i = 0; i < segments; ++i) {
      if (!b[i].is_number() || !std::isfinite(b[i].get<double>()) || std::fabs(b[i].get<double>()) > 1.0)
        return bad("bulge[" + std::to_string(i) + "]: must be a number in [-1, 1]");
    }
    std::vector<double> bulge;
    for (std::size_t i = 0; i < segments; ++i) bulge.push_back(b[i].get<double>());
    bool arcs = false;
    for (double v : bulge) arcs = arcs || v != 0.0;
    if (arcs) path.bulge = std::move(bulge);
  }
  return true;
}

PlannerInfo loadManifest(const std::string& path) {
  const std::string text = slurp(path, path, "(file)");
  const json doc = parseJsonStrict(text, path);
  const ManifestReader r(path);
  if (!doc.is_object()) r.fail("(document)", "must be a JSON object");
  r.onlyKeys(doc, "", {"coverbench_planner", "name", "version", "summary", "reference", "command", "files", "params",
                       "min_coverage_reachable"});
  if (!doc.contains("coverbench_planner") || doc["coverbench_planner"] != kProtocolVersion)
    r.fail("coverbench_planner", "must be " + std::to_string(kProtocolVersion) + " (the protocol version)");
  PlannerInfo info;
  info.name = r.text(doc, "name", "name");
  if (info.name.empty() || info.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != std::string::npos)
    r.fail("name", "must be lower-case letters, digits, - and _");
  info.version = r.text(doc, "version", "version");
  if (info.version.empty()) r.fail("version", "must not be empty");
  info.summary = r.text(doc, "summary", "summary");
  info.reference = r.text(doc, "reference", "reference");
  Launch launch;
  launch.manifest = fs::absolute(path).lexically_normal().string();
  launch.folder = fs::path(launch.manifest).parent_path().string();
  if (!doc.contains("command") || !doc["command"].is_array() || doc["command"].empty())
    r.fail("command", "must be a non-empty list of strings (the program and its arguments)");
  for (const json& c : doc["command"]) {
    if (!c.is_string() || c.get<std::string>().empty()) r.fail("command", "must be a non-empty list of strings");
    launch.command.push_back(c.get<std::string>());
  }
  // Code identity: the manifest and every declared file, by content.
  std::string identity = "manifest " + sha256Hex(text) + "\n";
  if (!doc.contains("files") || !doc["files"].is_array() || doc["files"].empty())
    r.fail("files", "must list the files whose content is the planner's code (a changed file runs it again)");
  for (std::size_t i = 0; i < doc["files"].size(); ++i) {
    const json& f = doc["files"][i];
    const std::string field = "files[" + std::to_string(i) + "]";
    if (!f.is_string()) r.fail(field, "must be a path (relative to the manifest)");
    const fs::path p = fs::path(launch.folder) / f.get<std::string>();
    if (!fs::is_regular_file(p)) r.fail(field, "is not a file: " + p.string());
    identity += f.get<std::string>() + " " + sha256Hex(slurp(p.string(), path, field)) + "\n";
  }
  info.code_sha256 = sha256Hex(identity);
  info.code_folders = {};  // the host's side of the protocol (runner/) is in every run's shared code identity
  if (doc.contains("params")) {
    if (!doc["params"].is_array()) r.fail("params", "must be a list");
    std::set<std::string> names;
    for (std::size_t i = 0; i < doc["params"].size(); ++i) {
      ParamSpec s = paramSpecFromJson(doc["params"][i], path, "params[" + std::to_string(i) + "]");
      if (!names.insert(s.name).second) r.fail("params[" + std::to_string(i) + "].name", "'" + s.name + "' is declared twice");
      info.params.push_back(std::move(s));
    }
  }
  if (doc.contains("min_coverage_reachable")) {
    const double m = r.number(doc["min_coverage_reachable"], "min_coverage_reachable");
    if (m < 0.0 || m > 1.0) r.fail("min_coverage_reachable", "must be in [0, 1]");
    info.min_coverage_reachable = m;
  }
  info.external_manifest = launch.manifest;
  info.make = [launch] { return std::make_unique<ExternalPlanner>(launch); };
  return info;
}

const PlannerInfo& addFromManifest(const std::string& path) { return addPlanner(loadManifest(path), path); }

const PlannerInfo& plannerNamed(const std::string& name, const std::string& source) {
  if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) return addFromManifest(name);
  return findPlanner(name, source);
}

}  // namespace coverbench::external
