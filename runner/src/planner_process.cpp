// An external planner's process (planner_process.hpp): how it is started (in a cgroup of its own
// where one can be made, tagged by a token), asked, measured and held to its limits, and how it and
// every process it started are found and killed.
#include "planner_process.hpp"

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
#include <cstring>
#include <fstream>
#include <sstream>

#include "coverbench/external_planner.hpp"
#include "coverbench/files.hpp"

namespace coverbench::external {
namespace {

using Clock = std::chrono::steady_clock;

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

}  // namespace

// --- asking ------------------------------------------------------------------------------------

PlannerProcess::Answer PlannerProcess::ask(const std::string& request, double timeout_s, std::size_t memory_limit) {
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

void PlannerProcess::stop() {
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

PlannerProcess::Answer PlannerProcess::askOnce(const std::string& request, double timeout_s, std::size_t memory_limit) {
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

void PlannerProcess::drainStderr() {
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

void PlannerProcess::passOn(const char* data, std::size_t n) {
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

std::string PlannerProcess::stderrTail() const {
  std::size_t from = tail_.size() > kStderrTailBytes ? tail_.size() - kStderrTailBytes : 0;
  if (from > 0)
    for (int k = 0; k < 3 && from < tail_.size() && (static_cast<unsigned char>(tail_[from]) & 0xC0) == 0x80; ++k) ++from;
  return toValidUtf8(tail_.substr(from));
}

std::vector<pid_t> PlannerProcess::treePids() const {
  if (!cgroup_.empty()) return cgroupPids(cgroup_);
  return processesWithEntry("COVERBENCH_PLANNER_TOKEN=" + token_);
}

double PlannerProcess::processCpu(pid_t pid) {
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

void PlannerProcess::startMeasuring() {
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

void PlannerProcess::stopMeasuring() {
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

bool PlannerProcess::leftoverCheck(Answer& a) {
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

bool PlannerProcess::setLimit(std::size_t memory_limit) {
  if (!cgroup_.empty()) {
    const std::string v = memory_limit > 0 ? std::to_string(memory_limit) : std::string("-1");
    if (!writeSmall(cgroup_ + "/memory.limit_in_bytes", v)) return false;
    writeSmall(cgroup_ + "/memory.memsw.limit_in_bytes", v);  // where swap is accounted: no swapping past it
  }
  limit_ = memory_limit;
  return true;
}

bool PlannerProcess::overMemory(Answer& a) {
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

bool PlannerProcess::start(Answer& a, std::size_t memory_limit) {
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

PlannerProcess::Answer& PlannerProcess::fail(Answer& a, PlanStatus status, std::string reason) {
  stopMeasuring();
  stop();
  a.ok = false;
  a.failure = status;
  a.reason = std::move(reason);
  return a;
}

bool PlannerProcess::exitedMeanwhile() const {
  if (pid_ <= 0) return false;
  siginfo_t info{};
  return ::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_;
}

PlannerProcess::Answer& PlannerProcess::died(Answer& a, const std::string& what) {
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

// --- every process of a run ----------------------------------------------------------------------

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

}  // namespace coverbench::external
