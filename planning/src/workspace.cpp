#include "coverbench/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "coverbench/region_ops.hpp"

namespace coverbench {

Workspace::Workspace(const Wall& wall, const ToolParams& tool, const VehicleModel& vehicle,
                     const TransitSpec& transit, std::uint64_t seed)
    : wall_(wall),
      tool_(tool),
      vehicle_(vehicle),
      transit_(transit),
      seed_(seed),
      field_(wall_),
      free_(freeRegion(wall_, tool_)),
      router_(field_, tool_) {
  router_.setFreeRegion(&free_);
}

Workspace::~Workspace() = default;

std::optional<std::vector<Point>> Workspace::route(Point a, Point b) {
  if (transit_.isDefault()) return router_.route(a, b);
  if (!sampling_) sampling_ = makeSamplingTransit(transit_, router_, boundingBox(wall_.boundary), seed_);
  const auto t0 = std::chrono::steady_clock::now();
  SampledRoute found = sampling_->route(a, b);
  transit_stats_.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ++transit_stats_.queries;
  transit_stats_.time_capped += found.time_capped;
  if (!found.route) {
    ++transit_stats_.failures;
    return std::nullopt;
  }
  transit_stats_.length += polylineLength(*found.route);
  if (const auto exact = router_.route(a, b)) transit_stats_.shortest += polylineLength(*exact);
  return found.route;
}

void PathBuilder::follow(const std::vector<Point>& points, bool tool_on) {
  for (const Point& p : points) path_.moveTo(p, tool_on);
}

bool PathBuilder::moveTo(Point to, bool tool_on_if_straight) {
  if (path_.waypoints.empty()) {
    path_.moveTo(to, false);
    return true;
  }
  const Point from = current();
  if (from == to) return true;
  if (ws_->router().isFree(from, to)) {
    path_.moveTo(to, tool_on_if_straight);
    return true;
  }
  if (ws_->vehicle().liftsTool()) {
    path_.moveTo(to, false);
    ++lifted_;
    return true;
  }
  const auto route = ws_->route(from, to);
  if (!route) return false;
  for (std::size_t i = 1; i < route->size(); ++i) path_.moveTo((*route)[i], false);
  ++transits_;
  return true;
}

std::pair<std::size_t, bool> takeNearestPass(const std::vector<std::pair<Point, Point>>& passes, std::vector<bool>& done,
                                             Point at) {
  std::size_t best = 0;
  bool flip = false;
  double best_d = INFINITY;
  for (std::size_t i = 0; i < passes.size(); ++i) {
    if (done[i]) continue;
    const double d0 = distance(at, passes[i].first), d1 = distance(at, passes[i].second);
    if (d0 < best_d) best_d = d0, best = i, flip = false;
    if (d1 < best_d) best_d = d1, best = i, flip = true;
  }
  done[best] = true;
  return {best, flip};
}

std::size_t coverRings(PathBuilder& builder, std::vector<Ring> rings, double max_painted_link) {
  std::size_t unreachable = 0;
  std::vector<Box> boxes;
  boxes.reserve(rings.size());
  for (const Ring& ring : rings) boxes.push_back(boundingBox(ring));
  std::vector<bool> done(rings.size(), false);
  for (std::size_t left = rings.size(); left > 0; --left) {
    // Nearest vertex of any remaining ring; boxes prune rings that cannot beat the best so far.
    std::size_t best_ring = 0, best_vertex = 0;
    double best = INFINITY;
    Box here;
    if (!builder.empty()) here.add(builder.current());
    for (std::size_t i = 0; i < rings.size(); ++i) {
      if (done[i]) continue;
      if (!builder.empty() && squaredBoxDistance(here, boxes[i]) >= best) continue;
      for (std::size_t k = 0; k < rings[i].size(); ++k) {
        const Point p = rings[i][k];
        // The very first loop starts at the lowest, then leftmost, vertex. (Squared distances.)
        const Point v = builder.empty() ? Point{} : p - builder.current();
        const double d = builder.empty() ? p.y * 1e6 + p.x : dot(v, v);
        if (d < best) {
          best = d;
          best_ring = i;
          best_vertex = k;
        }
      }
    }
    done[best_ring] = true;
    const Ring& ring = rings[best_ring];
    const Point entry = ring[best_vertex];
    const bool short_link = !builder.empty() && distance(builder.current(), entry) <= max_painted_link;
    if (!builder.moveTo(entry, short_link)) {
      ++unreachable;
      continue;
    }
    std::vector<Point> loop;
    loop.reserve(ring.size());
    for (std::size_t k = 1; k <= ring.size(); ++k) loop.push_back(ring[(best_vertex + k) % ring.size()]);
    builder.follow(loop, true);
  }
  return unreachable;
}

std::optional<Point> cornerSpurTip(Point prev, Point v, Point next, double angle, double r, const TransitRouter& router) {
  const Point u = v - prev, w = next - v;
  const double lu = norm(u), lw = norm(w);
  if (lu == 0.0 || lw == 0.0) return std::nullopt;
  const Point outward = u * (1.0 / lu) - w * (1.0 / lw);  // minus the inward bisector
  const double lo = norm(outward);
  if (lo == 0.0) return std::nullopt;
  double length = std::fmin(r / std::sin(angle / 2.0) - r, 2.0 * r);
  for (int attempt = 0; attempt < 3; ++attempt, length /= 2.0) {
    const Point tip = v + outward * (length / lo);
    if (router.isFree(v, tip)) return tip;
  }
  return std::nullopt;
}

Path withCornerSpurs(const Path& path, double r, const TransitRouter& router, std::size_t& spurs) {
  const std::size_t n = path.waypoints.size();
  Path out;
  if (n == 0) return out;
  out.waypoints.reserve(n);
  out.tool_on.reserve(n);
  auto spur = [&](Point v, Point tip) {
    out.waypoints.push_back(tip);
    out.tool_on.push_back(true);
    out.waypoints.push_back(v);
    out.tool_on.push_back(true);
    ++spurs;
  };
  // An end of a painted run: r straight on (or back) reaches the cell's far corners; halved while
  // not free.
  auto endSpur = [&](Point v, Point along) {
    const double l = norm(along);
    if (l == 0.0) return;
    for (double length = r; length > r / 8.0; length /= 2.0) {
      const Point tip = v + along * (length / l);
      if (!router.isFree(v, tip)) continue;
      spur(v, tip);
      return;
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    // Waypoint i, reached by segment i - 1, left by segment i.
    const Point v = path.waypoints[i];
    out.waypoints.push_back(v);
    if (i > 0) out.tool_on.push_back(path.tool_on[i - 1]);
    const bool in = i > 0 && path.tool_on[i - 1], on = i + 1 < n && path.tool_on[i];
    if (on && !in) endSpur(v, v - path.waypoints[i + 1]);  // a painted run starts here
    if (in && !on) endSpur(v, v - path.waypoints[i - 1]);  // a painted run ends here
    if (!in || !on) continue;
    const Point prev = path.waypoints[i - 1], next = path.waypoints[i + 1];
    const Point u = v - prev, w = next - v;
    const double angle = M_PI - std::fabs(std::atan2(cross(u, w), dot(u, w)));
    if (angle >= kStraightCorner) continue;
    if (const auto tip = cornerSpurTip(prev, v, next, angle, r, router)) spur(v, *tip);
  }
  return out;
}

ParamSpec cornerSpursParam() {
  return {"corner_spurs", ParamType::Bool, false, 0, 0, {}, "",
          "an out-and-back spur at every painted corner, so the disk reaches the corner the turn leaves "
          "unpainted (longer, more overlap; docs/planner_quality.md)"};
}

std::string partialCoverageNote(std::size_t free_components, std::size_t covered_components,
                                std::size_t unreachable_parts) {
  std::string note;
  if (covered_components < free_components)
    note = "covered the largest of " + std::to_string(free_components) +
           " disconnected free components; the others cannot be reached without leaving F";
  if (unreachable_parts > 0)
    note += (note.empty() ? "" : "; ") + std::to_string(unreachable_parts) +
            " part(s) of the covered component were left out: no collision-free transit reached them";
  return note;
}

void recordOutcome(PlanResult& result, const PathBuilder& builder, std::size_t free_components,
                   std::size_t unreachable_parts) {
  const bool lifts = builder.workspace().vehicle().liftsTool();
  result.stats["routed_transits"] = static_cast<double>(builder.transits());
  if (lifts) result.stats["lifted_crossings"] = static_cast<double>(builder.liftedCrossings());
  if (!builder.workspace().transitSpec().isDefault()) {
    const TransitStats& t = builder.workspace().transitStats();
    result.stats["transit_queries"] = static_cast<double>(t.queries);
    result.stats["transit_failures"] = static_cast<double>(t.failures);
    result.stats["transit_length_m"] = t.length;
    result.stats["transit_shortest_m"] = t.shortest;
    if (t.shortest > 0.0) result.stats["transit_length_ratio"] = t.length / t.shortest;  // none without a route
    result.timings_ms["transit"] = t.ms;
    if (t.time_capped > 0) result.timings_ms["transit_time_capped_queries"] = static_cast<double>(t.time_capped);
  }
  result.free_components = free_components;
  result.covered_components = lifts ? free_components : std::min<std::size_t>(free_components, 1);
  result.unreachable_parts = unreachable_parts;
  result.reason = partialCoverageNote(free_components, result.covered_components, unreachable_parts);
  if (const std::size_t capped = builder.workspace().transitStats().time_capped; capped > 0)
    result.reason += (result.reason.empty() ? "" : "; ") + std::to_string(capped) +
                     " transit queries were stopped by the time cap, not the iterations: a rerun may differ";
  if (result.status == PlanStatus::Ok && result.leftPartsOut()) result.status = PlanStatus::Partial;
}

std::vector<PolygonWithHoles> componentsByArea(const Region& region) {
  std::vector<PolygonWithHoles> parts(region.begin(), region.end());
  std::stable_sort(parts.begin(), parts.end(), [](const PolygonWithHoles& a, const PolygonWithHoles& b) {
    const double aa = area(a), ab = area(b);
    if (aa != ab) return aa > ab;
    const Box ba = boundingBox(a.outer), bb = boundingBox(b.outer);
    if (ba.min_y != bb.min_y) return ba.min_y < bb.min_y;
    return ba.min_x < bb.min_x;
  });
  return parts;
}

Region coveredPart(const std::vector<PolygonWithHoles>& components, const VehicleModel& vehicle) {
  if (components.empty()) return {};
  if (vehicle.liftsTool()) return Region(components.begin(), components.end());
  return Region{components.front()};
}

std::vector<DetourQuery> detourQueries(Workspace& ws, std::size_t count) {
  std::vector<DetourQuery> out;
  const std::vector<PolygonWithHoles> components = componentsByArea(ws.free());
  if (components.empty()) return out;
  const Box box = boundingBox(ws.wall().boundary);
  std::vector<Point> points;
  constexpr int kGrid = 12;
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const Point p{box.min_x + (i + 0.5) * box.width() / kGrid, box.min_y + (j + 0.5) * box.height() / kGrid};
      if (pointInPolygon(components.front(), p) && ws.router().isFree(p, p)) points.push_back(p);
    }
  // Pairs far apart in the list first (opposite sides of the wall), then nearer ones.
  for (std::size_t gap = points.size() / 2; gap > 0 && out.size() < count; gap = gap * 2 / 3)
    for (std::size_t k = 0; k + gap < points.size() && out.size() < count; k += gap + 1) {
      const Point a = points[k], b = points[k + gap];
      if (ws.router().isFree(a, b)) continue;
      const auto route = ws.router().route(a, b);
      if (!route) continue;
      out.push_back({a, b, polylineLength(*route)});
    }
  return out;
}

}  // namespace coverbench
