#include "adaptive_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "coverbench/limits.hpp"
#include "coverbench/edge_index.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::adaptive_resolution {
namespace {

/// A straight piece of a row: from x0 to x1 at row `row` (x0 == x1 for a single cell).
struct Piece {
  double x0, x1;
};

/// The quadtree's leaves over the covered part of F, as pieces of the rows of a grid of pitch s
/// (row r's centre line at y0 + (r + 0.5) s), and how they were found.
struct Quadtree {
  double x0 = 0.0, y0 = 0.0;
  int rows_total = 0;
  std::vector<std::vector<Piece>> rows;
  std::size_t open_leaves = 0, fine_leaves = 0, nodes = 0, largest = 1;
};

/// Whether points of one grid row lie in `main`, with pointInPolygon's answer at a fraction of its
/// cost: the quadtree asks once per leaf, each time about every edge of F. A row's crossings (the
/// x where each ring's edges cross the row's line, computed by pointInRing's own expression) are
/// found once and sorted, and a point is inside a ring when an odd number of them lie to its
/// right, which is pointInRing's count. A row is keyed by its y, and any other y is answered by
/// pointInPolygon itself.
class RowsInMain {
 public:
  RowsInMain(const Region& main, std::size_t rows) : main_(main), rows_(rows) {}

  bool operator()(int row, Point p) {
    Row& r = rows_[static_cast<std::size_t>(row)];
    if (!r.known) fill(r, p.y);
    if (r.y != p.y)
      return std::any_of(main_.begin(), main_.end(), [&](const PolygonWithHoles& part) { return pointInPolygon(part, p); });
    const std::size_t* ends = ends_.data() + r.ends;
    std::size_t ring = 0;
    for (const PolygonWithHoles& part : main_) {
      const std::size_t holes_end = ring + 1 + part.holes.size();
      if (oddRightOf(ends, ring++, p.x)) {
        while (ring < holes_end && !oddRightOf(ends, ring, p.x)) ++ring;
        if (ring == holes_end) return true;
      }
      ring = holes_end;
    }
    return false;
  }

 private:
  /// Ring k's crossings on a row are xs_[ends_[r.ends + k - 1], ends_[r.ends + k]), sorted (rings
  /// in order: each part's outer ring, then its holes; ends_[r.ends - 1] is where ring 0 starts).
  struct Row {
    bool known = false;
    double y = 0.0;
    std::size_t ends = 0;
  };

  bool oddRightOf(const std::size_t* ends, std::size_t ring, double x) const {
    const std::size_t* end = ends + ring;
    const auto first = xs_.begin() + static_cast<std::ptrdiff_t>(end[-1]);
    const auto last = xs_.begin() + static_cast<std::ptrdiff_t>(end[0]);
    return ((last - std::upper_bound(first, last, x)) & 1) != 0;
  }

  void fill(Row& r, double y) {
    r.known = true;
    r.y = y;
    ends_.push_back(xs_.size());  // where ring 0 starts
    r.ends = ends_.size();
    auto add = [&](const Ring& ring) {
      const std::size_t n = ring.size(), first = xs_.size();
      for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
        const Point& a = ring[i];
        const Point& b = ring[j];
        if ((a.y > y) != (b.y > y)) xs_.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
      }
      std::sort(xs_.begin() + static_cast<std::ptrdiff_t>(first), xs_.end());
      ends_.push_back(xs_.size());
    };
    for (const PolygonWithHoles& part : main_) {
      add(part.outer);
      for (const Ring& hole : part.holes) add(hole);
    }
  }

  const Region& main_;
  std::vector<Row> rows_;
  std::vector<double> xs_;         ///< every filled row's crossings
  std::vector<std::size_t> ends_;  ///< per filled row: its start, then each ring's end
};

/// Quadtree over the bounding square of `main` (the covered part of F, whose rings are `rings`),
/// cells aligned to a grid of pitch s. A node whose inner rectangle (cell shrunk by s/2, where
/// row centres run) meets no boundary edge of F is wholly inside or outside; inside, it becomes
/// an open leaf covered by rows. Nodes the boundary crosses split down to single cells (fine
/// leaves), kept when their centre is in F. nullopt: the budget ran out.
std::optional<Quadtree> quadtree(const Region& main, const std::vector<Ring>& rings, Workspace& ws, double s,
                                 const Budget& budget) {
  const EdgeIndex edges(rings, 4.0 * s);
  const Box box = boundingBox(main);
  int levels = 0;
  while (s * std::ldexp(1.0, levels) < std::fmax(box.width(), box.height()) + s) ++levels;
  RowsInMain inMain(main, static_cast<std::size_t>(1) << levels);
  Quadtree q;
  q.x0 = box.min_x - s / 2.0 + 1e-4;
  q.y0 = box.min_y - s / 2.0 + 1e-4;
  q.rows_total = 1 << levels;
  q.rows.resize(static_cast<std::size_t>(q.rows_total));
  struct Node {
    int cx, cy, size;  // in cells
  };
  std::vector<Node> stack{{0, 0, 1 << levels}};
  while (!stack.empty()) {
    const Node n = stack.back();
    stack.pop_back();
    ++q.nodes;
    if ((q.nodes & 1023) == 0 && budget.expired()) return std::nullopt;
    Box inner;
    inner.add({q.x0 + (n.cx + 0.5) * s, q.y0 + (n.cy + 0.5) * s});
    inner.add({q.x0 + (n.cx + n.size - 0.5) * s, q.y0 + (n.cy + n.size - 0.5) * s});
    if (inner.min_x > box.max_x || inner.min_y > box.max_y) continue;  // beyond F entirely
    if (!edges.meetsBox(inner)) {
      if (!inMain(n.cy, {inner.min_x, inner.min_y})) continue;  // wholly outside F
      for (int j = 0; j < n.size; ++j) q.rows[n.cy + j].push_back({inner.min_x, inner.max_x});
      ++(n.size == 1 ? q.fine_leaves : q.open_leaves);
      q.largest = std::max<std::size_t>(q.largest, static_cast<std::size_t>(n.size));
      continue;
    }
    if (n.size == 1) {
      const Point c{inner.min_x, inner.min_y};
      if (inMain(n.cy, c) && ws.router().isFree(c, c)) {
        q.rows[n.cy].push_back({c.x, c.x});
        ++q.fine_leaves;
      }
      continue;
    }
    const int h = n.size / 2;
    for (int k : {3, 2, 1, 0}) stack.push_back({n.cx + (k & 1) * h, n.cy + (k >> 1) * h, h});
  }
  return q;
}

/// A straight pass from a to b along row `row` of the quadtree's grid.
struct Run {
  Point a, b;
  int row;
};

/// The passes: per row, leaf pieces that touch are merged when the join is free, so open leaves
/// side by side become one pass. `runs_of_row` lists each row's runs. False: the budget ran out.
bool mergeRows(Quadtree& q, Workspace& ws, double s, const Budget& budget, std::vector<Run>& runs,
               std::vector<std::vector<std::size_t>>& runs_of_row) {
  runs_of_row.assign(static_cast<std::size_t>(q.rows_total), {});
  for (int r = 0; r < q.rows_total; ++r) {
    if (q.rows[r].empty()) continue;
    if (budget.expired()) return false;
    const double y = q.y0 + (r + 0.5) * s;
    std::vector<Piece>& row = q.rows[r];
    std::sort(row.begin(), row.end(), [](const Piece& p, const Piece& o) { return p.x0 < o.x0; });
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
  return true;
}

/// Boustrophedon by regions: from the end of a run, the next is the nearest unvisited run in the
/// row above or below whose end is within reach by a free, painted step; only when none is, the
/// nearest unvisited run anywhere, reached by a routed transit. Counts the runs painted in
/// `passes` and those no transit reached in `unreachable`. False: the budget ran out.
bool coverRuns(Workspace& ws, PathBuilder& builder, const std::vector<Run>& runs,
               const std::vector<std::vector<std::size_t>>& runs_of_row, double s, const Budget& budget,
               std::size_t& passes, std::size_t& unreachable) {
  const int rows_total = static_cast<int>(runs_of_row.size());
  std::vector<char> done(runs.size(), 0);
  std::size_t left = runs.size();
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
    if ((passes & 255) == 0 && budget.expired()) return false;
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
  return true;
}

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
    PlanFrame frame(problem);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    const std::vector<Ring> rings = allRings(frame.covered());
    std::optional<Quadtree> tree = quadtree(frame.covered(), rings, frame.ws(), s, budget);
    if (!tree) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");

    PathBuilder builder(frame.ws());
    // Extra passes that reach into corners: one loop along F's boundary (the wall edge and every
    // obstacle), where cells stop short.
    std::size_t unreachable = coverRings(builder, rings, 1.01 * s);
    std::vector<Run> runs;
    std::vector<std::vector<std::size_t>> runs_of_row;
    std::size_t passes = 0;
    if (!mergeRows(*tree, frame.ws(), s, budget, runs, runs_of_row) ||
        !coverRuns(frame.ws(), builder, runs, runs_of_row, s, budget, passes, unreachable))
      return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");
    Path path = builder.take();
    if (path.waypoints.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea, "no cell centre of the quadtree lies in F");

    std::size_t spurs = 0;
    if (params.corner_spurs) path = withCornerSpurs(path, problem.tool.radius(), frame.ws().router(), spurs);
    if (params.dense_waypoints) path = densify(path, frame.ws(), params);

    // Dense waypoints are asked for by the spacing: F's round boundary stays a chain of them.
    PlanResult result = frame.finish(builder, std::move(path), unreachable, !params.dense_waypoints);
    result.stats["quadtree_nodes"] = static_cast<double>(tree->nodes);
    result.stats["open_leaves"] = static_cast<double>(tree->open_leaves);
    result.stats["fine_leaves"] = static_cast<double>(tree->fine_leaves);
    result.stats["largest_leaf_cells"] = static_cast<double>(tree->largest);
    result.stats["rows"] = static_cast<double>(passes);
    if (params.corner_spurs) result.stats["corner_spurs"] = static_cast<double>(spurs);
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
  return typedPlannerInfo<AdaptivePlanner>(
      {.name = "adaptive-resolution", .version = "3", .code_folders = {"adaptive_resolution"},
       .summary = "Quadtree over F: rows across open leaves, single cells where obstacles cut in, a loop along every "
                  "edge; optional waypoint density by distance",
       .reference = "Seed 000 (adaptive resolution); quadtree coverage as in Choset, Coverage for robotics, AMAI 31, 2001",
       .min_coverage_reachable = 0.99},
      paramTable());
}

}  // namespace coverbench::adaptive_resolution
