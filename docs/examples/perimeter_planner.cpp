// A complete, tiny planner: one loop around every ring of the free region (wall edge and each
// obstacle). It is the example of docs/ADDING_A_PLANNER.md and is compiled and tested by
// tests/example_planner_test.cpp, so the guide cannot drift from the real interface.
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

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
    Workspace ws(*problem.wall, problem);  // F, exact checks, transits
    if (ws.free().empty())
      return PlanResult::failure(PlanStatus::NoReachableArea, "the tool fits nowhere on this wall");
    // F's pieces, largest first: the largest is covered, or every one for a vehicle that lifts its
    // tool (docs/vehicles.md).
    const std::vector<PolygonWithHoles> components = componentsByArea(ws.free());
    const Region part = coveredPart(components, problem.vehicle);
    PathBuilder builder(ws);  // never writes an unchecked move
    const Region rings = params.inset > 0 ? offsetRegion(part, -params.inset, 1e-4) : part;
    const std::size_t unreachable = coverRings(builder, allRings(rings), problem.tool.tool_width);
    PlanResult result;
    result.status = PlanStatus::Ok;
    result.path = builder.take();
    fitBoundaryArcs(result, ws, problem);  // F's round corners as arcs, not chains of chords
    // Partial, saying why, when pieces of F or rings were left out (the conformance walls check it).
    recordOutcome(result, builder, components.size(), unreachable);
    return result;
  }
};

PlannerInfo info() {
  PlannerInfo info;
  info.name = "perimeter";
  info.version = "1";  // change it when the results change on purpose
  info.code_folders = {"perimeter"};  // algorithms/perimeter/: its code's hash is in every run key
  info.summary = "One loop around the wall edge and around each obstacle";
  info.reference = "docs/ADDING_A_PLANNER.md";
  info.params = paramTable().specs();
  info.make = [] { return std::make_unique<PerimeterPlanner>(); };
  return info;
}

}  // namespace coverbench::perimeter
