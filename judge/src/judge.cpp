// The judge's entry point (no CGAL here: the CGAL units are exact_validity.cpp and
// exact_coverage.cpp, so an edit here does not rebuild them).
#include <chrono>

#include "coverbench/judge.hpp"

namespace coverbench::judge {

Judgement judgePath(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle,
                    const CoverageOptions& options) {
  using Clock = std::chrono::steady_clock;
  Judgement j;
  const auto t0 = Clock::now();
  j.validity = judgeValidity(wall, tool, path, vehicle);
  const auto t1 = Clock::now();
  j.coverage = judgeCoverage(wall, tool, path, options);
  const auto t2 = Clock::now();
  j.seconds_validity = std::chrono::duration<double>(t1 - t0).count();
  j.seconds_coverage = std::chrono::duration<double>(t2 - t1).count();
  return j;
}

}  // namespace coverbench::judge
