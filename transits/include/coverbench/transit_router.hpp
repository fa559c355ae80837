#pragma once
/// The visibility transit planner: shortest collision-free moves between points of the free
/// centre region F, on the problem's clearance field (docs/transits.md). Every other transit
/// planner checks its moves with it.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "coverbench/clearance.hpp"
#include "coverbench/geometry.hpp"
#include "coverbench/path.hpp"

namespace coverbench {

/// Spare distance planners demand of their own straight moves beyond the exact requirement.
inline constexpr double kPlanningMargin = 1e-6;

/// Shortest collision-free polylines between free points, on a visibility graph whose nodes sit
/// just outside the rounded corners of F (around convex obstacle corners, circles and reflex wall
/// corners). Edges are checked exactly, lazily: an A* search checks a move only when it is the
/// cheapest way left to reach its end. A query searches the nodes in a box around its ends,
/// growing the box until the route found is shorter than any route leaving the box could be, so
/// it is the shortest through all nodes. Only when that finds nothing (an end in a cusp of F) is
/// the whole graph linked, once, for the fallback below.
class TransitRouter {
 public:
  TransitRouter(const ClearanceField& field, const ToolParams& tool);
  ~TransitRouter();
  TransitRouter(const TransitRouter&) = delete;
  TransitRouter& operator=(const TransitRouter&) = delete;

  /// A straight move from a to b keeps the tool valid (with kPlanningMargin to spare).
  bool isFree(Point a, Point b) const;
  /// The shortest polyline a, ..., b whose segments are all free; nullopt when b is unreachable.
  /// Searches the visibility graph of nodes around obstacle corners; when that finds nothing
  /// (an endpoint in a cusp of F, a passage barely wider than the tool), it searches again with
  /// the vertices of F's boundary near a and b added, linked along F's edges, and last with every
  /// vertex of F's boundary.
  std::optional<std::vector<Point>> route(Point a, Point b);
  /// The conservative free region the fallback walks along (set by Workspace; optional).
  void setFreeRegion(const Region* free) { free_ = free; }
  std::size_t nodeCount();

 private:
  struct Graph;
  void build();  // the nodes
  void link();   // the edges between all nodes
  /// The shortest route through the nodes in a box around a and b, grown until no route leaving
  /// the box could be shorter (at most to every node); nullopt when there is none.
  std::optional<std::vector<Point>> localRoute(Point a, Point b);
  /// Marks a point of a search that is not one of the nodes.
  static constexpr std::size_t kNoNode = static_cast<std::size_t>(-1);
  /// The shortest route from pos[0] to pos[1] through pos, no longer than `bound` (lazy A*);
  /// node[i] is pos[i]'s index among the nodes (kNoNode if it is none): moves between nodes are
  /// checked once per router.
  std::optional<std::vector<Point>> lazySearch(const std::vector<Point>& pos, const std::vector<std::size_t>& node, double bound) const;
  /// lazySearch's A* over all of pos.
  std::optional<std::vector<Point>> searchWithin(const std::vector<Point>& pos, const std::vector<std::size_t>& node, double bound) const;
  /// Runs of F's boundary vertices near a or b (needs the free region).
  std::vector<std::vector<Point>> boundaryChains(Point a, Point b) const;

  std::optional<std::vector<Point>> search(Point a, Point b, const std::vector<std::vector<Point>>& chains);
  /// The shortest route through the nodes and every vertex of F's boundary (lazy A*).
  std::optional<std::vector<Point>> wholeBoundaryRoute(Point a, Point b);

  const ClearanceField* field_;
  ToolParams tool_;
  const Region* free_ = nullptr;
  std::unique_ptr<Graph> graph_;
};

}  // namespace coverbench
