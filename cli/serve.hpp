// `coverbench serve` as an object: the explorer's and the workbench's routes on one HTTP server,
// bound when made, serving when `listen` is called. The command (serveCommand) and the request
// handler's fuzz target (tests/fuzz/fuzz_serve.cpp) both make one.
#pragma once

#include <memory>
#include <string>

#include "commands.hpp"

namespace coverbench::cli {

/// The first argument that starts the workbench's plan helper instead of a command: the server
/// starts `helper_exe` with it (and restarts it when it ends), and the helper plans the requests
/// it reads from fd 3, answering on fd 4 (planHelperMain).
inline constexpr const char* kPlanHelperArgument = "--internal-plan-helper";

/// Runs the plan helper: `argv` is {program, kPlanHelperArgument, max time limit in s}. Returns
/// the process's exit code when the server closes its end.
int planHelperMain(int argc, char** argv);

class ServeApp {
 public:
  /// Checks the options, opens the databases and wall folders, starts the plan helper
  /// (`helper_exe` run with kPlanHelperArgument) and binds the port (0: any free one). Throws
  /// InputError for what the user must change (a busy port among them).
  ServeApp(const ServeOptions& options, const std::string& helper_exe);
  ~ServeApp();
  ServeApp(const ServeApp&) = delete;
  ServeApp& operator=(const ServeApp&) = delete;

  int port() const;
  /// Serves until stop(); returns false if the server could not serve.
  bool listen();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coverbench::cli
