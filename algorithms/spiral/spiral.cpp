#include "spiral.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/edge_index.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/car_sweep.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::spiral {
namespace {

/// Interior angle of a ring at vertex i when the region lies to the left of its edges (outer
/// rings counter-clockwise, holes clockwise); pi or more where the region is not convex.
double interiorAngle(const Ring& ring, std::size_t i) {
  const std::size_t n = ring.size();
  const Point u = ring[i] - ring[(i + n - 1) % n], w = ring[(i + 1) % n] - ring[i];
  return M_PI - std::atan2(cross(u, w), dot(u, w));
}

/// Whether eroding `outer` (a level) by `step` into `inner` (the next level) lost more than its
/// corners. In an erosion by `step`, every boundary point of the outer level has the inner level
/// within `step`, except near a convex corner of interior angle a, where the inner corner lies
/// up to `step / sin(a / 2)` away. A boundary point (vertices, and points every `step` along
/// edges) with nothing of the inner level that close marks a part that vanished (a peninsula, a
/// strip, a whole component), where a leftover centre may remain. `slack` absorbs chord error.
bool somethingVanished(const std::vector<Ring>& outer, const std::vector<Ring>& inner, double step, double slack) {
  if (inner.empty()) return true;
  const EdgeIndex grid(inner, 2.0 * step);
  // Distance to the inner level expected at distance t along an edge from a corner of angle a.
  auto expected = [&](double a, double t) {
    if (a >= M_PI) return step;
    const double half = std::fmax(a / 2.0, 0.02);
    const double reach = std::fmax(0.0, step / std::tan(half) - t);
    return std::sqrt(step * step + reach * reach);
  };
  for (const Ring& ring : outer) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point a = ring[i], b = ring[(i + 1) % n];
      const double angle_a = interiorAngle(ring, i), angle_b = interiorAngle(ring, (i + 1) % n);
      const double len = distance(a, b);
      const auto samples = static_cast<std::size_t>(std::ceil(len / step));
      for (std::size_t k = 0; k < std::max<std::size_t>(samples, 1); ++k) {
        const double t = samples == 0 ? 0.0 : len * static_cast<double>(k) / static_cast<double>(samples);
        const Point p = len == 0.0 ? a : a + (b - a) * (t / len);
        const double want = std::fmax(expected(angle_a, t), expected(angle_b, len - t));
        if (!grid.anyWithin(p, want + slack)) return true;
      }
    }
  }
  return false;
}

/// An inner ring with out-and-back spurs at its convex corners (cornerSpurTip). Between two
/// levels `spacing` apart the bands of the two loops meet along the edges, but at a convex corner
/// the inner loop sweeps a disk, leaving a curved triangle uncovered beyond the corner.
Ring withCornerSpurs(const Ring& ring, double r, const TransitRouter& router, std::size_t& spurs) {
  const std::size_t n = ring.size();
  Ring out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(ring[i]);
    const double angle = interiorAngle(ring, i);
    if (angle >= kStraightCorner) continue;  // nearly straight or reflex: nothing left beyond it
    if (const auto tip = cornerSpurTip(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n], angle, r, router)) {
      out.push_back(*tip);
      out.push_back(ring[i]);
      ++spurs;
    }
  }
  return out;
}

/// The planner's parameters (paramTable declares them).
struct SpiralParams {
  double overlap = 0.0;
  CarPlan car_plan = CarPlan::Headland;
};

const ParamTable<SpiralParams>& paramTable() {
  static const ParamTable<SpiralParams> table =
      ParamTable<SpiralParams>()
          .add({"overlap", ParamType::Number, 0.0, 0.0, 0.9, {}, "", "fraction of the tool width adjacent rings overlap"},
               &SpiralParams::overlap)
          .add(carPlanParam(), &SpiralParams::car_plan, carPlanChoices());
  return table;
}

class SpiralPlanner final : public TypedPlanner<SpiralParams> {
 public:
  SpiralPlanner() : TypedPlanner(paramTable()) {}

 private:
  /// For a car (car_plan: headland): every level's rings (no corner spurs or centre loops: a car
  /// turns round neither), the rings round obstacles replaced by passes along their straight
  /// edges (carHolePasses), all driven by the car's sweep (car_sweep.hpp): the rings smoothed for
  /// the car, from the outermost, and what their smoothing skips (corners tighter than it turns,
  /// the innermost rings) as passes taken in a turn-aware order with the obstacles' passes, then
  /// (`fill`, car_plan: headland) the sweep's fill rounds.
  PlanResult planForCar(const Budget& budget, double spacing, double tolerance, PlanFrame& frame, bool fill) {
    Workspace& ws = frame.ws();
    const Region base = simplifyRegion(frame.covered(), tolerance);
    std::vector<Ring> loops = allRings(frame.covered());
    std::size_t levels = 1;
    for (std::size_t j = 1;; ++j, ++levels) {
      if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      const Region inner = offsetRegion(base, -static_cast<double>(j) * spacing, tolerance);
      if (inner.empty()) break;
      for (Ring& ring : allRings(inner)) loops.push_back(std::move(ring));
    }
    const std::vector<CarRow> passes = carHolePasses(ws, loops, spacing);
    PathBuilder builder(ws);
    const CarSweep sweep = carSweep(ws, builder, loops, passes, spacing, budget, fill);
    PlanResult result = carSweepPlan(sweep, builder, loops.size(), 0.0, frame.components().size());
    result.stats["levels"] = static_cast<double>(levels);
    return result;
  }

 protected:
  PlanResult planWith(const Problem& problem, const SpiralParams& params, const Budget& budget) override {
    // A car comes only with car_plan headland or headland_no_fill: for smoothed, runPlanner gives
    // a tool that turns on the spot and smooths the path.
    const double s = problem.tool.tool_width;
    const double r = problem.tool.radius();
    const double spacing = s * (1.0 - params.overlap);
    // Inner rings only affect coverage, not validity, so they use a coarser arc tolerance. Round
    // offsets err only toward the previous ring (chords cut arcs short), so successive bands
    // overlap by the chord error instead of leaving a gap, even when each level is eroded from the
    // previous one.
    const double tolerance = std::clamp(s / 10.0, kArcTolerance, 1e-2);
    const double coarse = s / 5.0;

    PlanFrame frame(problem);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    if (problem.vehicle.isCar()) return planForCar(budget, spacing, tolerance, frame, params.car_plan == CarPlan::Headland);
    const Region& main = frame.covered();

    // Ring j is the boundary of F eroded by j * spacing (outer rings shrink, rings around
    // obstacles grow, until they meet).
    std::vector<Ring> rings = allRings(main);
    std::size_t levels = 1, centres = 0, leftover_checks = 0, spurs = 0;
    // Every level is eroded from one simplified copy of F (eroding level from level would double
    // the chords of every arc each time).
    const Region base = simplifyRegion(main, tolerance);
    std::vector<Ring> previous = allRings(base);
    for (std::size_t j = 1;; ++j) {
      if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      const double depth = static_cast<double>(j) * spacing;
      const Region inner = offsetRegion(base, -depth, tolerance);
      const std::vector<Ring> inner_rings = allRings(inner);
      // Where the previous ring's band ends, whatever the next ring's band misses is a leftover
      // centre (a vanishing peninsula or the middle of the last ring): it gets its own loop. That
      // only happens where part of the previous level vanished, so the exact (and costly)
      // computation runs only there. It tolerates coarser chords (the loop around a leftover
      // reaches r beyond it); the extra 2 * coarse keeps chord noise from showing up.
      if (somethingVanished(previous, inner_rings, spacing, 0.1 * spacing + 4.0 * tolerance)) {
        ++leftover_checks;
        const Region beyond = offsetRegion(base, -(depth - spacing + r), coarse);
        const Region leftover =
            beyond.empty() ? Region{} : subtract(beyond, offsetRegion(inner, r + 2.0 * coarse, coarse));
        for (const PolygonWithHoles& piece : leftover) {
          if (area(piece) < s * coarse) continue;  // numerical specks, not uncovered area
          for (const Ring& ring : allRings({piece})) rings.push_back(ring);
          ++centres;
        }
      }
      if (inner.empty()) break;
      for (const Ring& ring : inner_rings) rings.push_back(withCornerSpurs(ring, r, frame.ws().router(), spurs));
      previous = inner_rings;
      ++levels;
    }

    // Greedy nearest ring next: the rings chain inward from the wall and outward from each
    // obstacle one step at a time, so most links are a single tool-on step of `spacing`.
    PathBuilder builder(frame.ws());
    const std::size_t unreachable = coverRings(builder, std::move(rings), 2.0 * spacing);

    PlanResult result = frame.finish(builder, unreachable);
    result.stats["levels"] = static_cast<double>(levels);
    result.stats["centre_loops"] = static_cast<double>(centres);
    result.stats["leftover_checks"] = static_cast<double>(leftover_checks);
    result.stats["corner_spurs"] = static_cast<double>(spurs);
    return result;
  }
};

}  // namespace

PlannerInfo info() {
  return typedPlannerInfo<SpiralPlanner>(
      {.name = "spiral", .version = "9", .code_folders = {"spiral"},
       .summary = "Concentric passes offset inward from the free region's boundary, around obstacles, centre covered",
       .reference = "Held, On the Computational Geometry of Pocket Machining, LNCS 500, 1991",
       .min_coverage_reachable = 0.995, .plans_for_car = true},
      paramTable());
}

}  // namespace coverbench::spiral
