#pragma once
/// Export of an experiment's runs in OMPL's benchmark log format, so OMPL's
/// ompl_benchmark_statistics.py loads them into its database and Planner Arena plots them: one log
/// (one OMPL experiment) per dataset, one planner entry per planner configuration (and per tool,
/// when the experiment has several), CoverBench's metrics as typed run properties.
/// docs/scaling.md says how each figure maps.
#include <cstdint>
#include <string>
#include <vector>

#include "coverbench/records.hpp"

namespace coverbench {

/// What the log's header states about how the runs were made (from the experiment's config).
struct OmplLogSettings {
  double time_limit_s = 60.0;
  double memory_limit_mb = 4096.0;
  std::uint64_t seed = 0;
};
/// The settings an experiment's config text gives (its limits and seed; the config's defaults
/// where it gives none).
OmplLogSettings omplLogSettings(const std::string& config_text);

struct OmplLog {
  std::string dataset;
  std::string file_name;  ///< EXPERIMENT.DATASET.log, through uniqueFileNames
  std::string text;
  std::size_t runs = 0;
};
/// One log per dataset, in the experiment's dataset order. Same inputs, same bytes.
std::vector<OmplLog> omplBenchmarkLogs(const ResultSet& results, const ExperimentRecord& record,
                                       const OmplLogSettings& settings);

}  // namespace coverbench
