#include "adaptive_resolution.hpp"

#include <algorithm>
#include <cmath>

#include "coverbench/limits.hpp"
#include "coverbench/edge_index.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::adaptive_resolution {
namespace {

/// A straight piece of a row: from x0 to x1 at row `row` (x0 == x1 for a single cell).
struct Piece {
  double x0, x1;
};

/// The planner's parameters (paramTable declares them).
struct AdaptiveParams {
  bool dense_waypoints = false;
  double near_spacing = 0.005, mid_spacing = 0.01, far_spacing = 0.02;  ///< m
  double near_distance = 0.1, mid_distance = 0.5;                        ///< m
  bool corner_spurs = false;
};

const ParamTable<AdaptiveParams>& paramTable() {
  static const ParamTable<AdaptiveParams> table =
      ParamTable<AdaptiveParams>()
          .add({"dense_waypoints", ParamType::Bool, false, 0, 0, {}, "",
                "resample the path by distance to obstacles (controllers that need dense waypoints; no arcs)"},
               &AdaptiveParams::dense_waypoints)
          .add({"near_spacing", ParamType::Number, 0.005, 0.0005, 1.0, {}, "m", "waypoint spacing near obstacles and edges"},
               &AdaptiveParams::near_spacing)
          .add({"mid_spacing", ParamType::Number, 0.01, 0.0005, 1.0, {}, "m", "waypoint spacing within mid_distance"},
               &AdaptiveParams::mid_spacing)
          .add({"far_spacing", ParamType::Number, 0.02, 0.0005, 1.0, {}, "m", "waypoint spacing elsewhere"},
               &AdaptiveParams::far_spacing)
          .add({"near_distance", ParamType::Number, 0.1, 0.0, 100.0, {}, "m", "gap (from the tool's edge) that counts as near"},
               &AdaptiveParams::near_distance)
          .add({"mid_distance", ParamType::Number, 0.5, 0.0, 100.0, {}, "m", "gap that counts as mid"},
               &AdaptiveParams::mid_distance)
          .add(cornerSpursParam(), &AdaptiveParams::corner_spurs);
  return table;
}

class AdaptivePlanner final : public TypedPlanner<AdaptiveParams> {
 public:
  AdaptivePlanner() : TypedPlanner(paramTable()) {}

 protected:
  PlanResult planWith(const Problem& problem, const AdaptiveParams& params, const Budget& budget) override {
    const double s = problem.tool.tool_width;
    if (const std::string why = gridCellsProblem(problem.tool, *problem.wall); !why.empty())
      return PlanResult::failure(PlanStatus::InvalidInput, why);
    Workspace ws(*problem.wall, problem);
    const std::vector<PolygonWithHoles> components = componentsByArea(ws.free());
    if (components.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "the tool fits nowhere: the free region F is empty for this tool and clearance");
    const Region main = coveredPart(components, problem.vehicle);
    auto inMain = [&](Point p) {
      return std::any_of(main.begin(), main.end(), [&](const PolygonWithHoles& part) { return pointInPolygon(part, p); });
    };
    const std::vector<Ring> rings = allRings(main);
    const EdgeIndex edges(rings, 4.0 * s);

    // Quadtree over F's bounding square, cells aligned to a grid of pitch s. A node whose inner
    // rectangle (cell shrunk by s/2, where row centres run) meets no boundary edge of F is wholly
    // inside or outside; inside, it becomes an open leaf covered by rows. Nodes the boundary
    // crosses split down to single cells (fine leaves), kept when their centre is in F.
    const Box box = boundingBox(main);
    int levels = 0;
    while (s * std::ldexp(1.0, levels) < std::fmax(box.width(), box.height()) + s) ++levels;
    const double X0 = box.min_x - s / 2.0 + 1e-4, Y0 = box.min_y - s / 2.0 + 1e-4;
    const int rows_total = 1 << levels;
    std::vector<std::vector<Piece>> rows(rows_total);
    std::size_t open_leaves = 0, fine_leaves = 0, nodes = 0, largest = 1;
    struct Node {
      int cx, cy, size;  // in cells
    };
    std::vector<Node> stack{{0, 0, 1 << levels}};
    while (!stack.empty()) {
      const Node n = stack.back();
      stack.pop_back();
      ++nodes;
      if ((nodes & 1023) == 0 && budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      Box inner;
      inner.add({X0 + (n.cx + 0.5) * s, Y0 + (n.cy + 0.5) * s});
      inner.add({X0 + (n.cx + n.size - 0.5) * s, Y0 + (n.cy + n.size - 0.5) * s});
      if (inner.min_x > box.max_x || inner.min_y > box.max_y) continue;  // beyond F entirely
      if (!edges.meetsBox(inner)) {
        if (!inMain({inner.min_x, inner.min_y})) continue;  // wholly outside F
        for (int j = 0; j < n.size; ++j) rows[n.cy + j].push_back({inner.min_x, inner.max_x});
        ++(n.size == 1 ? fine_leaves : open_leaves);
        largest = std::max<std::size_t>(largest, static_cast<std::size_t>(n.size));
        continue;
      }
      if (n.size == 1) {
        const Point c{inner.min_x, inner.min_y};
        if (inMain(c) && ws.router().isFree(c, c)) {
          rows[n.cy].push_back({c.x, c.x});
          ++fine_leaves;
        }
        continue;
      }
      const int h = n.size / 2;
      for (int k : {3, 2, 1, 0}) stack.push_back({n.cx + (k & 1) * h, n.cy + (k >> 1) * h, h});
    }

    PathBuilder builder(ws);
    // Extra passes that reach into corners: one loop along F's boundary (the wall edge and every
    // obstacle), where cells stop short.
    std::size_t unreachable = coverRings(builder, rings, 1.01 * s);
    // Pieces: per row, leaf rows that touch are merged when the join is free, so open leaves
    // side by side become one pass.
    struct Run {
      Point a, b;
      int row;
    };
    std::vector<Run> runs;
    std::vector<std::vector<std::size_t>> runs_of_row(rows_total);
    for (int r = 0; r < rows_total; ++r) {
      if (rows[r].empty()) continue;
      if (budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      const double y = Y0 + (r + 0.5) * s;
      std::vector<Piece>& row = rows[r];
      std::sort(row.begin(), row.end(), [](const Piece& p, const Piece& q) { return p.x0 < q.x0; });
      std::vector<Piece> merged;
      for (const Piece& p : row) {
        if (!merged.empty() && p.x0 - merged.back().x1 <= 1.0001 * s &&
            ws.router().isFree({merged.back().x1, y}, {p.x0, y}))
          merged.back().x1 = std::fmax(merged.back().x1, p.x1);
        else
          merged.push_back(p);
      }
      for (const Piece& p : merged) {
        runs_of_row[r].push_back(runs.size());
        runs.push_back({{p.x0, y}, {p.x1, y}, r});
      }
    }
    // Boustrophedon by regions: from the end of a run, the next is the nearest unvisited run in
    // the row above or below whose end is within reach by a free, painted step; only when none
    // is, the nearest unvisited run anywhere, reached by a routed transit.
    std::vector<char> done(runs.size(), 0);
    std::size_t left = runs.size(), passes = 0;
    auto enter = [&](std::size_t k, bool from_a) {
      const Point a = from_a ? runs[k].a : runs[k].b, b = from_a ? runs[k].b : runs[k].a;
      done[k] = 1;
      --left;
      const bool near = !builder.empty() && distance(builder.current(), a) <= 1.5 * s;
      if (!builder.moveTo(a, near)) {
        ++unreachable;
        return;
      }
      if (!(a == b)) builder.follow({b}, true);
      else if (!near) builder.follow({a}, true);  // a lone cell: paint where we stand
      ++passes;
    };
    int row = -1;
    while (left > 0) {
      if ((passes & 255) == 0 && budget.expired()) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
      std::size_t best = runs.size();
      bool best_a = true;
      double best_d = INFINITY;
      if (!builder.empty() && row >= 0) {
        const Point here = builder.current();
        for (int r : {row + 1, row - 1}) {
          if (r < 0 || r >= rows_total) continue;
          for (std::size_t k : runs_of_row[r]) {
            if (done[k]) continue;
            for (bool at_a : {true, false}) {
              const Point e = at_a ? runs[k].a : runs[k].b;
              const double d = distance(here, e);
              if (d < best_d && d <= 1.5 * s) best = k, best_a = at_a, best_d = d;
            }
          }
        }
        if (best < runs.size() && !ws.router().isFree(here, best_a ? runs[best].a : runs[best].b)) best = runs.size();
      }
      if (best == runs.size()) {
        const Point here = builder.empty() ? Point{-INFINITY, -INFINITY} : builder.current();
        best_d = INFINITY;
        for (std::size_t k = 0; k < runs.size(); ++k) {
          if (done[k]) continue;
          for (bool at_a : {true, false}) {
            const Point e = at_a ? runs[k].a : runs[k].b;
            // The first run: the lowest, then leftmost; afterwards the nearest.
            const double d = builder.empty() ? e.y * 1e6 + e.x : distance(here, e);
            if (d < best_d) best = k, best_a = at_a, best_d = d;
          }
        }
      }
      enter(best, best_a);
      row = runs[best].row;
    }
    Path path = builder.take();
    if (path.waypoints.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea, "no cell centre of the quadtree lies in F");

    std::size_t spurs = 0;
    if (params.corner_spurs) path = withCornerSpurs(path, problem.tool.radius(), ws.router(), spurs);
    if (params.dense_waypoints) path = densify(path, ws, params);

    PlanResult result;
    result.status = PlanStatus::Ok;
    result.path = std::move(path);
    // Dense waypoints are asked for by the spacing: F's round boundary stays a chain of them.
    if (!params.dense_waypoints) fitBoundaryArcs(result, ws, problem);
    result.stats["quadtree_nodes"] = static_cast<double>(nodes);
    result.stats["open_leaves"] = static_cast<double>(open_leaves);
    result.stats["fine_leaves"] = static_cast<double>(fine_leaves);
    result.stats["largest_leaf_cells"] = static_cast<double>(largest);
    result.stats["rows"] = static_cast<double>(passes);
    if (params.corner_spurs) result.stats["corner_spurs"] = static_cast<double>(spurs);
    recordOutcome(result, builder, components.size(), unreachable);
    return result;
  }

 private:
  /// Waypoints every `near_spacing` on segments within `near_distance` of an obstacle or the wall
  /// edge (measured from the tool's edge), every `mid_spacing` within `mid_distance`, every
  /// `far_spacing` elsewhere. Intermediate points lie on the segments, so validity is unchanged.
  static Path densify(const Path& in, const Workspace& ws, const AdaptiveParams& params) {
    const double r = ws.tool().radius();
    const double near_d = params.near_distance, mid_d = params.mid_distance;
    Path out;
    out.waypoints.push_back(in.waypoints.front());
    for (std::size_t i = 0; i < in.tool_on.size(); ++i) {
      const Point a = in.waypoints[i], b = in.waypoints[i + 1];
      const SegmentClearance m = ws.field().measure(a, b);
      const double gap = std::fmin(m.boundary_distance, m.obstacle_distance) - r;
      const double step = gap <= near_d ? params.near_spacing : gap <= mid_d ? params.mid_spacing : params.far_spacing;
      const auto pieces = static_cast<std::size_t>(std::ceil(distance(a, b) / step - 1e-9));
      for (std::size_t k = 1; k < pieces; ++k) out.moveTo(a + (b - a) * (static_cast<double>(k) / static_cast<double>(pieces)), in.tool_on[i]);
      out.waypoints.push_back(b);
      out.tool_on.push_back(in.tool_on[i]);
    }
    return out;
  }
};

}  // namespace

PlannerInfo info() {
  PlannerInfo info;
  info.name = "adaptive-resolution";
  info.version = "3";
  info.code_folders = {"adaptive_resolution"};
  info.summary = "Quadtree over F: rows across open leaves, single cells where obstacles cut in, a loop along every edge; optional waypoint density by distance";
  info.reference = "Seed 000 (adaptive resolution); quadtree coverage as in Choset, Coverage for robotics, AMAI 31, 2001";
  info.params = paramTable().specs();
  info.min_coverage_reachable = 0.99;
  info.make = [] { return std::make_unique<AdaptivePlanner>(); };
  return info;
}

}  // namespace coverbench::adaptive_resolution
