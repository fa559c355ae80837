#include "spiral.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::spiral {
namespace {

class SpiralPlanner final : public Planner {
 public:
  PlanResult plan(const Problem& problem, const Budget& budget) override {
    const double s = problem.tool.tool_width;
    const double r = problem.tool.radius();
    const double spacing = s * (1.0 - problem.params.number("overlap"));
    // Inner rings only affect coverage, not validity, so they use a coarser arc tolerance. Round
    // offsets err only toward the previous ring (chords cut arcs short), so successive bands
    // overlap by the chord error instead of leaving a gap, even when each level is eroded from the
    // previous one.
    const double tolerance = std::clamp(s / 20.0, kArcTolerance, 5e-3);
    const double coarse = s / 8.0;

    Workspace ws(*problem.wall, problem.tool);
    const std::vector<PolygonWithHoles> components = componentsByArea(ws.free());
    if (components.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "the tool fits nowhere: the free region F is empty for this tool and clearance");
    const Region main{components.front()};

    // Ring j is the boundary of F eroded by j * spacing (outer rings shrink, rings around
    // obstacles grow, until they meet).
    std::vector<Ring> rings = allRings(main);
    std::size_t levels = 1, centres = 0;
    // Every level is eroded from one simplified copy of F (eroding level from level would double
    // the chords of every arc each time).
    const Region base = simplifyRegion(main, tolerance);
    for (std::size_t j = 1;; ++j) {
      if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      const double depth = static_cast<double>(j) * spacing;
      const Region inner = offsetRegion(base, -depth, tolerance);
      // Where the previous ring's band ends; whatever of it the next ring's band misses is a
      // leftover centre (a vanishing peninsula or the middle of the last ring): it gets its own
      // loop. Finding leftovers tolerates coarser chords (the loop around a leftover reaches r
      // beyond it); the extra 2 * coarse keeps chord noise from showing up as leftovers.
      const Region beyond = offsetRegion(base, -(depth - spacing + r), coarse);
      if (beyond.empty()) break;
      const Region leftover = subtract(beyond, offsetRegion(inner, r + 2.0 * coarse, coarse));
      for (const Ring& ring : allRings(inner)) rings.push_back(ring);
      for (const PolygonWithHoles& piece : leftover) {
        if (area(piece) < s * coarse) continue;  // numerical specks, not uncovered area
        for (const Ring& ring : allRings({piece})) rings.push_back(ring);
        ++centres;
      }
      if (inner.empty()) break;
      ++levels;
    }

    // Greedy nearest ring next: the rings chain inward from the wall and outward from each
    // obstacle one step at a time, so most links are a single tool-on step of `spacing`.
    PathBuilder builder(ws);
    const std::size_t unreachable = coverRings(builder, std::move(rings), 2.0 * spacing);

    PlanResult result;
    result.status = PlanStatus::Ok;
    result.path = builder.take();
    result.stats["levels"] = static_cast<double>(levels);
    result.stats["centre_loops"] = static_cast<double>(centres);
    result.stats["routed_transits"] = static_cast<double>(builder.transits());
    result.stats["free_components"] = static_cast<double>(components.size());
    result.stats["unreachable_parts"] = static_cast<double>(unreachable);
    if (components.size() > 1)
      result.reason = "covered the largest of " + std::to_string(components.size()) +
                      " disconnected free components; the others cannot be reached without leaving F";
    return result;
  }
};

}  // namespace

PlannerInfo info() {
  PlannerInfo info;
  info.name = "spiral";
  info.summary = "Concentric passes offset inward from the free region's boundary, around obstacles, centre covered";
  info.reference = "Held, On the Computational Geometry of Pocket Machining, LNCS 500, 1991";
  info.params = {
      {"overlap", ParamType::Number, 0.0, 0.0, 0.9, {}, "", "fraction of the tool width adjacent rings overlap"},
  };
  info.make = [] { return std::make_unique<SpiralPlanner>(); };
  return info;
}

}  // namespace coverbench::spiral
