// An external planner's process (planner_process.cpp): started once, asked one line at a time,
// held to a run's time and memory limits, measured, and stopped with every process it started.
// Internal to the runner's library.
#pragma once

#include <sys/types.h>

#include <cmath>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "coverbench/planner.hpp"

namespace coverbench::external {

/// What a manifest declares beyond PlannerInfo: how to start the planner.
struct Launch {
  std::vector<std::string> command;  ///< argv; relative programs and files resolve in `folder`
  std::string folder;                ///< the manifest's folder: the process's working directory
  std::string manifest;              ///< the manifest's absolute path (names the process)
};

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
  Answer ask(const std::string& request, double timeout_s, std::size_t memory_limit);

  /// Stops the process and every process it started.
  void stop();

 private:
  /// One question: the process started (or restarted under a new limit) if need be, the request
  /// written and the answer's line read as they become possible, the limits watched meanwhile.
  Answer askOnce(const std::string& request, double timeout_s, std::size_t memory_limit);
  /// Reads what the planner's processes wrote to stderr so far (without waiting), passes it on
  /// to this process's stderr and keeps its end; closes the pipe at its end.
  void drainStderr();
  /// Passes a planner's stderr on to ours as it came, best effort and bounded: at most
  /// kPassedOnBytes a question (then one line says the rest is not shown), and never waiting for
  /// a reader (a pipe nobody reads held the planner past its time limit): what ours cannot take
  /// at once is dropped. The kept tail is not affected.
  void passOn(const char* data, std::size_t n);
  /// The last kStderrTailBytes kept, from the first whole character on, as valid UTF-8.
  std::string stderrTail() const;
  /// The planner's processes now: its cgroup's, or those carrying its token.
  std::vector<pid_t> treePids() const;
  /// A process's CPU time (s) from /proc: its own and that of its children it waited for; NaN
  /// when it is gone.
  static double processCpu(pid_t pid);
  /// The start of a question's measurement: each process's CPU time, and the peaks reset (the
  /// cgroup's peak usage; without one, each process's peak resident set).
  void startMeasuring();
  /// The end of it (before the processes are stopped): CPU time since the start summed over the
  /// processes (the planner's own from its wait status when it has ended), and the peak.
  void stopMeasuring();
  /// Output left over from the last answer (a second line, written after it was read) fails the
  /// run about to be asked: it would otherwise be read as that run's answer.
  bool leftoverCheck(Answer& a);
  /// The memory limit of the planner's cgroup (0: none); false when it cannot be set.
  bool setLimit(std::size_t memory_limit);
  /// Past the memory limit: the kernel killed one of the planner's processes at its cgroup's limit,
  /// or (without a cgroup) their resident sets add up to more than the limit.
  bool overMemory(Answer& a);
  /// Starts the process (in its cgroup where one can be made, under `memory_limit`); false, with
  /// the reason in `a`, when it cannot be started.
  bool start(Answer& a, std::size_t memory_limit);
  /// Fails the question with `status` and `reason`, after stopping the process and its tree.
  Answer& fail(Answer& a, PlanStatus status, std::string reason);
  /// Whether the process it started has exited (not reaped here: died() reaps it).
  bool exitedMeanwhile() const;
  /// The process ended (or will): crash, with how it ended; memory_limit when the kernel stopped
  /// one of its processes at the limit.
  Answer& died(Answer& a, const std::string& what);

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

}  // namespace coverbench::external
