// Run statuses by name (the run's fields are declared in the header's table).
#include "coverbench/run_record.hpp"

namespace coverbench {

const char* toString(RunStatus status) {
  switch (status) {
    case RunStatus::Ok: return "ok";
    case RunStatus::Partial: return "partial";
    case RunStatus::NoReachableArea: return "no_reachable_area";
    case RunStatus::InvalidInput: return "invalid_input";
    case RunStatus::Timeout: return "timeout";
    case RunStatus::MemoryLimit: return "memory_limit";
    case RunStatus::Crash: return "crash";
    case RunStatus::Error: return "error";
    case RunStatus::InvalidOutput: return "invalid_output";
    case RunStatus::MetricsError: return "metrics_error";
  }
  return "error";
}

std::optional<RunStatus> parseRunStatus(std::string_view name) {
  for (RunStatus s : kRunStatuses)
    if (name == toString(s)) return s;
  return std::nullopt;
}

bool isRetryable(RunStatus s) {
  return s == RunStatus::Timeout || s == RunStatus::MemoryLimit || s == RunStatus::Crash || s == RunStatus::Error ||
         s == RunStatus::MetricsError;
}

}  // namespace coverbench
