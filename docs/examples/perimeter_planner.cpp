// A complete, tiny planner: one loop around every ring of the free region (wall edge and each
// obstacle). It is the example of docs/ADDING_A_PLANNER.md and is compiled and tested by
// tests/algorithms/example_planner_test.cpp, so the guide cannot drift from the real interface.
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/region_ops.hpp"

namespace coverbench::perimeter {

/// The planner's parameters: a struct, each member declared once below with its spec.
struct PerimeterParams {
  double inset = 0.0;  ///< m
};

const ParamTable<PerimeterParams>& paramTable() {
  static const ParamTable<PerimeterParams> table = ParamTable<PerimeterParams>().add(
      {"inset", ParamType::Number, 0.0, 0.0, 1.0, {}, "m", "how far inside F the loops run"}, &PerimeterParams::inset);
  return table;
}

class PerimeterPlanner final : public TypedPlanner<PerimeterParams> {
 public:
  PerimeterPlanner() : TypedPlanner(paramTable()) {}

 protected:
  PlanResult planWith(const Problem& problem, const PerimeterParams& params, const Budget& /*budget*/) override {
    // F (exact checks, transits) and its pieces, largest first: the largest is covered, or every
    // one for a vehicle that lifts its tool (docs/vehicles.md).
    PlanFrame frame(problem);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    PathBuilder builder(frame.ws());  // never writes an unchecked move
    const Region& part = frame.covered();
    const Region rings = params.inset > 0 ? offsetRegion(part, -params.inset, 1e-4) : part;
    const std::size_t unreachable = coverRings(builder, allRings(rings), problem.tool.tool_width);
    // F's round corners as arcs, not chains of chords; Partial, saying why, when pieces of F or
    // rings were left out (the conformance walls check it).
    return frame.finish(builder, unreachable);
  }
};

PlannerInfo info() {
  // version: change it when the results change on purpose; code_folders: algorithms/perimeter/,
  // whose code's hash is in every run key.
  return typedPlannerInfo<PerimeterPlanner>({.name = "perimeter", .version = "1", .code_folders = {"perimeter"},
                                             .summary = "One loop around the wall edge and around each obstacle",
                                             .reference = "docs/ADDING_A_PLANNER.md"},
                                            paramTable());
}

}  // namespace coverbench::perimeter
