#pragma once
/// Plan files (JSON): what `coverbench plan` writes and `coverbench metrics` reads.
/// Format: docs/file_formats.md.

#include <string>

#include "coverbench/metrics.hpp"
#include "coverbench/planner.hpp"

namespace coverbench {

struct PlanFile {
  std::string planner;
  std::string wall;
  ToolParams tool;
  Params params;
  PlanResult result;
  Validity validity;
};

/// The plan file as JSON text. Everything but the "timing" object is a deterministic function of
/// the inputs.
std::string planFileJson(const PlanFile& plan);

/// Writes `text` to `path` atomically (a temporary file renamed into place), so a failure never
/// leaves a partial file. Throws InputError naming the path if it cannot be written.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace coverbench
