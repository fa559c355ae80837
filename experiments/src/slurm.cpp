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

namespace {

/// Whole-number fields of a Slurm value, at most 12 digits each (a bigger one is no real limit).
bool fields(const std::smatch& m, std::vector<unsigned long long>& out) {
  for (std::size_t i = 1; i < m.size(); ++i) {
    if (!m[i].matched) {
      out.push_back(0);
      continue;
    }
    const std::string t = m[i].str();
    if (t.size() > 12) return false;
    out.push_back(std::stoull(t));
  }
  return true;
}

/// The longest --time, --mem, --partition or --account read (Slurm's own names are shorter).
constexpr std::size_t kMaxSlurmValue = 256;

/// Slurm's time formats (M, M:S, H:M:S, D-H, D-H:M, D-H:M:S, or UNLIMITED), at most a year.
void checkSlurmTime(const std::string& time) {
  if (time == "UNLIMITED" || time == "INFINITE") return;
  static const std::regex minutes(R"(^(\d+)(?::(\d{1,2}))?(?::(\d{1,2}))?$)");
  static const std::regex days(R"(^(\d+)-(\d+)(?::(\d{1,2}))?(?::(\d{1,2}))?$)");
  std::smatch m;
  std::vector<unsigned long long> f;
  double seconds = -1.0;
  if (std::regex_match(time, m, days) && fields(m, f))
    seconds = ((static_cast<double>(f[0]) * 24.0 + static_cast<double>(f[1])) * 60.0 + static_cast<double>(f[2])) * 60.0 +
              static_cast<double>(f[3]);
  else if (std::regex_match(time, m, minutes) && fields(m, f))
    // M; M:S; H:M:S
    seconds = !m[2].matched   ? static_cast<double>(f[0]) * 60.0
              : !m[3].matched ? static_cast<double>(f[0]) * 60.0 + static_cast<double>(f[1])
                              : (static_cast<double>(f[0]) * 60.0 + static_cast<double>(f[1])) * 60.0 + static_cast<double>(f[2]);
  if (seconds < 0.0)
    throw InputError("--time", "time", "must be in Slurm's format (minutes, HH:MM:SS or D-HH:MM:SS), got '" + shownBytes(time) + "'");
  if (seconds > 366.0 * 86400.0)
    throw InputError("--time", "time", "must be at most a year (366-00:00:00; UNLIMITED for none), got '" + shownBytes(time) + "'");
}

/// A whole number with an optional K, M, G or T suffix (Slurm's default unit is M), at most 1 PiB
/// (0: all of a node's memory, as Slurm reads it).
void checkSlurmMemory(const std::string& mem) {
  if (mem.empty()) return;
  static const std::regex mem_re(R"(^(\d+)([KMGT]?)$)");
  std::smatch m;
  if (!std::regex_match(mem, m, mem_re))
    throw InputError("--mem", "mem", "must be a whole number with an optional K, M, G or T suffix (e.g. 4G), got '" + shownBytes(mem) + "'");
  const std::string digits = m[1].str(), unit = m[2].matched && m[2].length() ? m[2].str() : "M";
  const double scale = unit == "K" ? 1.0 / 1024.0 : unit == "M" ? 1.0 : unit == "G" ? 1024.0 : 1024.0 * 1024.0;
  const double mib = digits.size() > 18 ? HUGE_VAL : static_cast<double>(std::stoull(digits)) * scale;
  if (mib > 1024.0 * 1024.0 * 1024.0)
    throw InputError("--mem", "mem", "must be at most 1 PiB (1073741824M) per task, got '" + shownBytes(mem) + "'");
}

}  // namespace

SlurmScripts slurmScripts(const ExperimentConfig& config, const SlurmOptions& o) {
  namespace fs = std::filesystem;
  if (o.shards < 1 || o.shards > kMaxShards)
    throw InputError("--shards", "shards", "must be in [1, " + std::to_string(kMaxShards) + "], got " + std::to_string(o.shards));
  if (o.cpus_per_task < 1 || o.cpus_per_task > 1024)
    throw InputError("--cpus-per-task", "cpus_per_task", "must be in [1, 1024], got " + std::to_string(o.cpus_per_task));
  // Before any pattern: std::regex recurses per character, and a value of 50 kB overflows the stack.
  for (const auto& [flag, value] : {std::pair<const char*, const std::string&>{"--time", o.time}, {"--mem", o.mem},
                                    {"--partition", o.partition}, {"--account", o.account}})
    if (value.size() > kMaxSlurmValue)
      throw InputError(flag, flag + 2, "must be at most " + std::to_string(kMaxSlurmValue) + " bytes, got " + std::to_string(value.size()));
  // Slurm's time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S; or UNLIMITED.
  checkSlurmTime(o.time);
  checkSlurmMemory(o.mem);
  static const std::regex name_re(R"(^[A-Za-z0-9_.,-]+$)");
  if (!o.partition.empty() && !std::regex_match(o.partition, name_re))
    throw InputError("--partition", "partition", "must be a partition name (letters, digits, _ . , -), got '" + shownBytes(o.partition) + "'");
  if (!o.account.empty() && !std::regex_match(o.account, name_re))
    throw InputError("--account", "account", "must be an account name (letters, digits, _ . , -), got '" + shownBytes(o.account) + "'");
  if (o.binary.empty() || !fs::path(o.binary).is_absolute())
    throw InputError("slurm", "binary", "the coverbench executable's absolute path is needed, got '" + shownBytes(o.binary) + "'");

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
