#include "workbench.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>

#include "commands.hpp"
#include "serve.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/runner.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench::cli {

using nlohmann::json;

namespace {

constexpr const char* kBody = "request body";

/// A number field of the body: absent gives `fallback`.
double numberField(const json& body, const char* name, double fallback) {
  if (!body.contains(name)) return fallback;
  const json& v = body[name];
  if (!v.is_number()) throw InputError(kBody, name, std::string("must be a number, got ") + (v.is_string() ? "a string" : v.type_name()));
  return v.get<double>();
}

}  // namespace

json plannersJson() {
  json out = json::array();
  for (const PlannerInfo& p : registeredPlanners()) {
    json params = json::array();
    for (const ParamSpec& s : p.params) params.push_back(json(paramSpecJson(s)));
    out.push_back({{"name", p.name}, {"version", p.version}, {"summary", p.summary}, {"reference", p.reference}, {"params", params}});
  }
  return {{"planners", out}};
}

WorkbenchRequest readWorkbenchRequest(const std::string& text, double max_time_limit_s) {
  // Strictly, as every file is read: no duplicate key, no nesting past kMaxJsonDepth (a value
  // nested 100,000 deep was printed back by recursion and ended the server), no number no
  // double holds (1e999).
  const json body = parseJsonStrict(text, kBody);
  if (!body.is_object()) throw InputError(kBody, "(document)", "must be an object");
  for (const auto& [key, value] : body.items())
    if (key != "wall" && key != "planner" && key != "params" && key != "tool_width" && key != "clearance" && key != "time_limit_s")
      throw InputError(kBody, key, "unknown key (wall, planner, params, tool_width, clearance, time_limit_s)");
  if (!body.contains("wall") || !body["wall"].is_string()) throw InputError(kBody, "wall", "must be the wall file's text");
  WorkbenchRequest r;
  r.wall.wall = parseWallJson(body["wall"].get<std::string>(), "wall");
  r.wall.json = wallToJson(r.wall.wall);
  r.wall.hash = sha256Hex(r.wall.json);
  r.wall.dataset = "workbench";
  r.tool.tool_width = numberField(body, "tool_width", r.tool.tool_width);
  r.tool.clearance = numberField(body, "clearance", r.tool.clearance);
  validateTool(r.tool, "tool");
  validateToolForWall(r.tool, r.wall.wall, "tool");
  r.time_limit_s = numberField(body, "time_limit_s", r.time_limit_s);
  validateTimeLimit(r.time_limit_s, kBody, "time_limit_s");
  if (r.time_limit_s > max_time_limit_s)
    throw InputError(kBody, "time_limit_s",
                     "must be at most " + shortNumber(max_time_limit_s) + " s (serve --plan-time-limit), got " + shortNumber(r.time_limit_s));
  if (body.contains("params") && !body.contains("planner")) throw InputError(kBody, "params", "given without a planner");
  if (!body.contains("planner")) return r;
  if (!body["planner"].is_string()) throw InputError(kBody, "planner", "must be a planner's name");
  r.planner = &findPlanner(body["planner"].get<std::string>(), "planner");
  ParamSettings settings;
  if (body.contains("params")) {
    if (!body["params"].is_object()) throw InputError(kBody, "params", "must be an object of name: value");
    settings = parseSettingsJson(*r.planner, body["params"], "params");
  }
  r.config.planner = r.planner->name;
  r.config.params = withDefaults(*r.planner, settings);
  r.config.settings = std::move(settings);
  r.config.label = r.planner->name;
  return r;
}

RunRecord planInWorker(const WorkbenchRequest& request) {
  RunSpec spec;
  spec.wall = &request.wall;
  spec.planner = &request.config;
  spec.tool = request.tool;
  spec.time_limit_s = request.time_limit_s;
  spec.memory_limit_bytes = std::size_t{4} << 30;
  spec.planner_version = request.planner->version;
  spec.base_key = runBaseKey(spec);
  spec.key = runKey(spec);
  return executeInWorker(spec);
}

namespace {

/// Reads `size` bytes; with a deadline, gives up (false, *timed_out set) when it passes.
bool readAll(int fd, char* data, std::size_t size, const std::chrono::steady_clock::time_point* deadline = nullptr,
             bool* timed_out = nullptr) {
  for (std::size_t off = 0; off < size;) {
    if (deadline) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(*deadline - std::chrono::steady_clock::now()).count();
      if (left <= 0) {
        if (timed_out) *timed_out = true;
        return false;
      }
      pollfd p{fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
      if (ready < 0 && errno != EINTR) return false;
      if (ready <= 0) continue;
    }
    const ssize_t r = ::read(fd, data + off, size - off);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    off += static_cast<std::size_t>(r);
  }
  return true;
}

}  // namespace

bool writeMessage(int fd, const std::string& text) {
  const std::uint64_t n = text.size();
  const std::string bytes = std::string(reinterpret_cast<const char*>(&n), sizeof n) + text;
  for (std::size_t off = 0; off < bytes.size();) {
    const ssize_t w = ::write(fd, bytes.data() + off, bytes.size() - off);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    off += static_cast<std::size_t>(w);
  }
  return true;
}

bool readMessage(int fd, std::string& text, const std::chrono::steady_clock::time_point* deadline, bool* timed_out) {
  std::uint64_t n = 0;
  if (!readAll(fd, reinterpret_cast<char*>(&n), sizeof n, deadline, timed_out) || n > (std::uint64_t{1} << 32)) return false;
  text.assign(static_cast<std::size_t>(n), '\0');
  return readAll(fd, text.data(), text.size(), deadline, timed_out);
}


int planHelperMain(int argc, char** argv) {
  if (argc != 3) return 2;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  const double max_time_limit_s = std::strtod(argv[2], nullptr);
  for (;;) {
    std::string body;
    if (!readMessage(3, body)) return 0;
    std::string answer;
    try {
      answer = "R" + serializeRecord(planInWorker(readWorkbenchRequest(body, max_time_limit_s)));
    } catch (const InputError& e) {
      answer = std::string("I") + e.what();
    } catch (const std::exception& e) {
      answer = std::string("X") + e.what();
    }
    if (!writeMessage(4, answer)) return 0;
  }
}

}  // namespace coverbench::cli
