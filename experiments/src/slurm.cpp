#include "coverbench/slurm.hpp"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <regex>

#include "coverbench/shards.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

std::string shellQuote(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

SlurmScripts slurmScripts(const ExperimentConfig& config, const SlurmOptions& o) {
  namespace fs = std::filesystem;
  if (o.shards < 1 || o.shards > kMaxShards)
    throw InputError("--shards", "shards", "must be in [1, " + std::to_string(kMaxShards) + "], got " + std::to_string(o.shards));
  if (o.cpus_per_task < 1 || o.cpus_per_task > 1024)
    throw InputError("--cpus-per-task", "cpus_per_task", "must be in [1, 1024], got " + std::to_string(o.cpus_per_task));
  // Slurm's time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S; or UNLIMITED.
  static const std::regex time_re(R"(^(\d+|\d+:\d{1,2}|\d+:\d{1,2}:\d{1,2}|\d+-\d+|\d+-\d+:\d{1,2}|\d+-\d+:\d{1,2}:\d{1,2}|UNLIMITED|INFINITE)$)");
  if (!std::regex_match(o.time, time_re))
    throw InputError("--time", "time", "must be in Slurm's format (minutes, HH:MM:SS or D-HH:MM:SS), got '" + o.time + "'");
  static const std::regex mem_re(R"(^\d+[KMGT]?$)");
  if (!o.mem.empty() && !std::regex_match(o.mem, mem_re))
    throw InputError("--mem", "mem", "must be a whole number with an optional K, M, G or T suffix (e.g. 4G), got '" + o.mem + "'");
  static const std::regex name_re(R"(^[A-Za-z0-9_.,-]+$)");
  if (!o.partition.empty() && !std::regex_match(o.partition, name_re))
    throw InputError("--partition", "partition", "must be a partition name (letters, digits, _ . , -), got '" + o.partition + "'");
  if (!o.account.empty() && !std::regex_match(o.account, name_re))
    throw InputError("--account", "account", "must be an account name (letters, digits, _ . , -), got '" + o.account + "'");
  if (o.binary.empty() || !fs::path(o.binary).is_absolute())
    throw InputError("slurm", "binary", "the coverbench executable's absolute path is needed, got '" + o.binary + "'");

  SlurmScripts s;
  const fs::path output = fs::absolute(config.output);
  // Paths go into #SBATCH lines, which Slurm splits at white space and expands % in.
  for (const auto& [what, path] : {std::pair<std::string, std::string>{"output", output.string()}, {"workdir", o.workdir}})
    if (path.find_first_of(" \t\n%") != std::string::npos)
      throw InputError(config.path, what, "'" + path + "' has white space or %, which #SBATCH lines cannot hold");
  std::string job = config.name;
  for (char& c : job)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') c = '_';
  s.folder = (output / "slurm").string();
  s.run_script = (output / "slurm" / "run.sbatch").string();
  s.merge_script = (output / "slurm" / "merge.sbatch").string();
  const std::string logs = (output / "slurm" / "logs").string();
  const std::string n = std::to_string(o.shards);
  const std::string config_path = fs::absolute(config.path).string();
  // Each task's memory: every worker may reach the config's limit, plus the runner and walls.
  const std::string mem = !o.mem.empty() ? o.mem
                                         : std::to_string(static_cast<long long>(std::ceil(config.memory_limit_mb)) *
                                                              o.cpus_per_task + 1024) + "M";
  std::string throttle;
  if (o.throttle) throttle = std::string("%").append(std::to_string(o.throttle));
  std::string common;
  if (!o.partition.empty()) common += "#SBATCH --partition=" + o.partition + "\n";
  if (!o.account.empty()) common += "#SBATCH --account=" + o.account + "\n";
  common += "#SBATCH --chdir=" + o.workdir + "\n";

  s.run_text = "#!/bin/bash\n"
               "# Written by `coverbench slurm` for " + config_path + ": task I of the array runs shard I/" + n + " of the\n"
               "# experiment into " + (output / "shards").string() + "/shard-I-of-" + n + ".sqlite. A task that was\n"
               "# killed resumes where it stopped when submitted again: sbatch --array=I " + s.run_script + "\n"
               "#SBATCH --job-name=coverbench-" + job + "\n"
               "#SBATCH --array=0-" + std::to_string(o.shards - 1) + throttle + "\n"
               "#SBATCH --ntasks=1\n"
               "#SBATCH --cpus-per-task=" + std::to_string(o.cpus_per_task) + "\n"
               "#SBATCH --mem=" + mem + "\n"
               "#SBATCH --time=" + o.time + "\n"
               "#SBATCH --output=" + logs + "/run-%A_%a.out\n" + common +
               "set -euo pipefail\n"
               "exec " + shellQuote(o.binary) + " run " + shellQuote(config_path) + " --shard \"${SLURM_ARRAY_TASK_ID}/" + n +
               "\" --threads \"${SLURM_CPUS_PER_TASK:-" + std::to_string(o.cpus_per_task) + "}\" --no-report --yes\n";
  const std::string merged = (output / "results.sqlite").string();
  s.merge_text = "#!/bin/bash\n"
                 "# Written by `coverbench slurm` for " + config_path + ": after the array (afterany, so a failed task\n"
                 "# is named here rather than leaving this job pending forever), merges the " + n + " shards into\n"
                 "# " + merged + (o.report ? " and writes the report" : "") + ". The merge refuses, naming them, missing\n"
                 "# shards and shards with missing runs; resubmit those tasks, then this script.\n"
                 "#SBATCH --job-name=coverbench-" + job + "-merge\n"
                 "#SBATCH --ntasks=1\n"
                 "#SBATCH --cpus-per-task=1\n"
                 "#SBATCH --mem=4096M\n"
                 "#SBATCH --time=" + o.time + "\n"
                 "#SBATCH --output=" + logs + "/merge-%j.out\n" + common +
                 "set -euo pipefail\n"
                 "shards=()\n"
                 "for i in $(seq 0 " + std::to_string(o.shards - 1) + "); do shards+=(" +
                 shellQuote((output / "shards").string()) + "/shard-$i-of-" + n + ".sqlite); done\n" +
                 shellQuote(o.binary) + " merge " + shellQuote(merged) + " \"${shards[@]}\"\n" +
                 (o.report ? shellQuote(o.binary) + " report " + shellQuote(merged) + " --format html --out " +
                                 shellQuote((output / "report").string()) + "\n"
                           : std::string());
  return s;
}

}  // namespace coverbench
