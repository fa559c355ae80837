// Planners outside the tree: the manifest, the planner that asks its process (planner_process.cpp)
// in its manifest's protocol (external_protocol.cpp), and the processes this process keeps for the next run.
#include "coverbench/external_planner.hpp"

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "coverbench/hash.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/registry.hpp"
#include "planner_process.hpp"

namespace coverbench::external {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A file's bytes; InputError naming `source` and `field` when it cannot be read.
std::string slurp(const std::string& path, const std::string& source, const std::string& field) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source, field, "cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// --- the manifest -------------------------------------------------------------------------------

/// Reads a manifest's fields; every error names the manifest and the field.
using ManifestReader = JsonFields;

// --- the planner ---------------------------------------------------------------------------------

/// The processes of this process (a worker keeps its planners' processes across runs), by manifest.
std::map<std::string, std::unique_ptr<PlannerProcess>>& processes() {
  static std::map<std::string, std::unique_ptr<PlannerProcess>> all;
  return all;
}

/// A planner outside the tree: each plan is one question to its manifest's process, kept for the next.
class ExternalPlanner final : public Planner {
 public:
  ExternalPlanner(Launch launch, int protocol) : launch_(std::move(launch)), protocol_(protocol) {}
  PlanResult plan(const Problem& problem, const Budget& budget) override {
    ::signal(SIGPIPE, SIG_IGN);  // a planner that died shows as a failed write
    auto& proc = processes()[launch_.manifest];
    if (!proc) proc = std::make_unique<PlannerProcess>(launch_);
    static long long next_id = 0;
    const long long id = ++next_id;
    const double limit = budget.remainingSeconds();
    const PlannerProcess::Answer a =
        proc->ask(requestJson(problem, limit, id, protocol_) + "\n", limit, problem.memory_limit_bytes);
    auto withProcess = [&](PlanResult r) {
      r.stderr_tail = a.stderr_tail;
      r.process_cpu_s = a.cpu_s;
      r.process_peak_bytes = a.peak_bytes;
      return r;
    };
    if (!a.ok) return withProcess(PlanResult::failure(a.failure, a.reason));
    PlanResult result;
    std::string why;
    if (!readAnswer(a.line, id, result, why, protocol_)) {
      proc.reset();  // a process that breaks the protocol is not asked again
      return withProcess(PlanResult::failure(PlanStatus::InvalidOutput, "the planner's answer: " + why));
    }
    return withProcess(std::move(result));
  }

 private:
  Launch launch_;
  int protocol_;  ///< the manifest's: what its requests carry and its answers repeat
};

}  // namespace

void stopPlannerProcesses() { processes().clear(); }

PlannerInfo loadManifest(const std::string& path) {
  const std::string text = slurp(path, path, "(file)");
  const json doc = parseJsonStrict(text, path);
  const ManifestReader r(path);
  if (!doc.is_object()) r.fail("(document)", "must be a JSON object");
  r.onlyKeys(doc, "", {"coverbench_planner", "name", "version", "summary", "reference", "command", "files", "params",
                       "min_coverage_reachable"});
  const json& version = doc.contains("coverbench_planner") ? doc["coverbench_planner"] : json();
  if (!version.is_number_integer() || version.get<long long>() < 1 || version.get<long long>() > kProtocolVersion)
    r.fail("coverbench_planner", "must be 1 or " + std::to_string(kProtocolVersion) + " (the protocol version)");
  const int protocol = version.get<int>();
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
  info.make = [launch, protocol] { return std::make_unique<ExternalPlanner>(launch, protocol); };
  return info;
}

const PlannerInfo& addFromManifest(const std::string& path) { return addPlanner(loadManifest(path), path); }

const PlannerInfo& plannerNamed(const std::string& name, const std::string& source) {
  if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) return addFromManifest(name);
  return findPlanner(name, source);
}

}  // namespace coverbench::external
