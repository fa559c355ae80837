#pragma once
/// Runs in child processes (internal to the runner). A pool of worker processes, forked from the
/// runner, executes one run at a time each under hard limits (address space, CPU time) and sends
/// its record back through a pipe; the runner enforces the wall-clock deadline, kills a worker
/// that passes it, names what went wrong when a worker dies without answering (crash with the
/// signal, timeout), and starts a fresh worker in its place.
#include <functional>
#include <string>
#include <vector>

#include "coverbench/experiment.hpp"

namespace coverbench {

/// Executes `runs` in child processes, at most `workers` at a time, and calls `done` in this
/// process (one at a time, in completion order) with each run's record. The record's measured
/// fields come from the kernel, per run: CPU time from getrusage, the peak resident set from VmHWM
/// reset at the run's start; for a planner outside the tree, its own processes' (PlanResult::
/// process_cpu_s, process_peak_bytes).
void executeIsolated(const std::vector<const RunSpec*>& runs, unsigned workers,
                     const std::function<void(const RunSpec&, RunRecord)>& done);

/// The hard wall-clock deadline of a run: planning has `time_limit_s` (the cooperative budget),
/// repeated `repetitions` times, and scoring gets as long again, plus 5 s to start and report;
/// with replanning, two budgets more per fraction (a plan from scratch, repairs, their scores).
double hardDeadlineSeconds(const RunSpec& spec);

/// A record as bytes and back (the pipe's protocol). Throws std::runtime_error on malformed bytes.
std::string serializeRecord(const RunRecord& record);
RunRecord deserializeRecord(const std::string& bytes);

}  // namespace coverbench
