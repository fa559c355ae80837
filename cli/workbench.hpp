#pragma once
/// The explorer's workbench (docs/explorer.md#workbench): a wall and a planner as a request gives
/// them, checked with the command line's messages, and planned in a worker process of its own
/// under the time limit, as the runner plans.
#include <nlohmann/json.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "coverbench/experiment.hpp"
#include "coverbench/run_record.hpp"

namespace coverbench::cli {

/// The registry's planners with their parameter specs (type, default, range, unit, choices), as
/// the workbench builds its form from them.
nlohmann::json plannersJson();

/// A workbench request: {"wall": wall file text, "planner", "params": {name: value},
/// "tool_width", "clearance", "time_limit_s"}; only "wall" is required.
struct WorkbenchRequest {
  WallEntry wall;                        ///< the wall as parsed, its canonical text and hash
  const PlannerInfo* planner = nullptr;  ///< when the request names one
  PlannerConfig config;                  ///< its resolved parameters
  ToolParams tool;
  double time_limit_s = 10.0;
};
/// Reads a request body, checking each part as the command line checks it (the wall as a wall
/// file "wall", parameters as --param, the tool, the time limit). Throws InputError with the
/// command line's one-line message; a time limit over `max_time_limit_s` too.
WorkbenchRequest readWorkbenchRequest(const std::string& body, double max_time_limit_s);

/// Plans the request in a worker process (executeInWorker) and scores the path with the metrics
/// engine, as a run of an experiment is planned and scored.
RunRecord planInWorker(const WorkbenchRequest& request);

/// Length-prefixed messages over a pipe: the protocol between `serve` and its plan helper
/// (planHelperMain, serve.hpp). With a deadline, a read gives up when it passes (false,
/// *timed_out set).
bool writeMessage(int fd, const std::string& text);
bool readMessage(int fd, std::string& text, const std::chrono::steady_clock::time_point* deadline = nullptr,
                 bool* timed_out = nullptr);

}  // namespace coverbench::cli
