// The experiment config parser on any bytes (written to a scratch .yaml file, as a user's config
// would be): a config, or InputError naming the file. Anything else escaping is a finding.
#include <cstdint>
#include <string>

#include "coverbench/experiment.hpp"
#include "coverbench/wall.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace coverbench;
  const std::string path = fuzz::scratchFile(data, size, ".yaml");
  try {
    const ExperimentConfig config = loadExperimentConfig(path);
    (void)plannedRuns(config);
  } catch (const InputError& e) {
    if (e.source().empty() || e.problem().empty()) fuzz::broken(std::string("InputError without source or problem: ") + e.what());
  }
  return 0;
}
