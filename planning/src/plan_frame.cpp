#include "coverbench/plan_frame.hpp"

#include <utility>

#include "coverbench/boundary_arcs.hpp"
#include "coverbench/free_region.hpp"

namespace coverbench {

PlanFrame::PlanFrame(const Problem& problem) : PlanFrame(problem, *problem.wall, std::nullopt) {}

PlanFrame::PlanFrame(const Problem& problem, double turn) : PlanFrame(problem, rotateWall(*problem.wall, -turn), turn) {}

PlanFrame::PlanFrame(const Problem& problem, const Wall& wall, std::optional<double> turn)
    : problem_(&problem),
      turn_(turn),
      ws_(wall, problem),
      components_(componentsByArea(ws_.free())),
      covered_(coveredPart(components_, problem.vehicle)) {}

PlanResult PlanFrame::fitsNowhere() {
  return PlanResult::failure(PlanStatus::NoReachableArea,
                             "the tool fits nowhere: the free region F is empty for this tool and clearance");
}

PlanResult PlanFrame::finish(const PathBuilder& builder, Path path, std::size_t unreachable, bool boundary_arcs) const {
  PlanResult result;
  result.status = PlanStatus::Ok;
  result.path = std::move(path);
  if (boundary_arcs) fitBoundaryArcs(result, ws_, *problem_);
  if (turn_) rotatePoints(result.path.waypoints, *turn_);
  recordOutcome(result, builder, components_.size(), unreachable);
  return result;
}

PlanResult PlanFrame::finish(PathBuilder& builder, std::size_t unreachable) const {
  Path path = builder.take();
  return finish(builder, std::move(path), unreachable);
}

}  // namespace coverbench
