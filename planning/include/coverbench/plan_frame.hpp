#pragma once
/// The opening and the closing every planner built on Workspace shares, in one place.
///
/// A planner opens a PlanFrame on its problem (on the wall as it is, or turned into the planner's
/// working frame), returns PlanFrame::fitsNowhere() when F is empty, plans on `ws()` and
/// `covered()`, and closes with `finish`, which makes the Ok result of the finished path: F's
/// round boundary as arcs, the path turned back to the world, what was covered recorded
/// (recordOutcome). The planner then adds its own statistics.
///
///   PlanFrame frame(problem);
///   if (frame.empty()) return PlanFrame::fitsNowhere();
///   PathBuilder builder(frame.ws());
///   ...
///   PlanResult result = frame.finish(builder, unreachable);
///   result.stats["rows"] = ...;

#include <cstddef>
#include <optional>
#include <vector>

#include "coverbench/planner.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {

class PlanFrame {
 public:
  /// The problem's Workspace on its wall as it is.
  explicit PlanFrame(const Problem& problem);
  /// The problem's Workspace on its wall turned by -turn radians (the planner's working frame);
  /// finish turns the path back by `turn`.
  PlanFrame(const Problem& problem, double turn);
  PlanFrame(const PlanFrame&) = delete;
  PlanFrame& operator=(const PlanFrame&) = delete;

  /// F is empty for this tool and clearance: the planner returns fitsNowhere().
  bool empty() const { return components_.empty(); }
  /// The failure of a problem whose F is empty (NoReachableArea, "the tool fits nowhere").
  static PlanResult fitsNowhere();

  Workspace& ws() { return ws_; }
  const Workspace& ws() const { return ws_; }
  /// The problem the frame was opened on (the planner's, after any change of vehicle).
  const Problem& problem() const { return *problem_; }
  /// F's connected components, largest first (componentsByArea).
  const std::vector<PolygonWithHoles>& components() const { return components_; }
  /// The part of F the planner covers (coveredPart): the largest component, or all of them for
  /// a vehicle that lifts its tool.
  const Region& covered() const { return covered_; }

  /// The Ok result of `path` (built by `builder`, and possibly changed after): F's round boundary
  /// as arcs unless `boundary_arcs` is false (fitBoundaryArcs), the waypoints turned back to the
  /// world for a turned frame, and the outcome recorded (recordOutcome: the builder's transit
  /// statistics, the components, the `unreachable` parts, status Partial when parts were left out).
  PlanResult finish(const PathBuilder& builder, Path path, std::size_t unreachable, bool boundary_arcs = true) const;
  /// The same, for the path the builder holds (taken from it).
  PlanResult finish(PathBuilder& builder, std::size_t unreachable) const;

 private:
  PlanFrame(const Problem& problem, const Wall& wall, std::optional<double> turn);

  const Problem* problem_;
  std::optional<double> turn_;
  Workspace ws_;
  std::vector<PolygonWithHoles> components_;
  Region covered_;
};

}  // namespace coverbench
