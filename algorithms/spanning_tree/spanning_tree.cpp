#include "spanning_tree.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::spanning_tree {
namespace {

/// Grid centres keep this far inside F's bounding offsets, so a wall whose size is a multiple of
/// s keeps its outermost cells (F's conservative boundary lies 55 micrometres inside).
constexpr double kInset = 1e-4;

/// A grid of cell centres over a region: which cells are free, which neighbours are joined by a
/// free segment. Cell i is column i % cols, row i / cols.
struct Grid {
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  int cols = 0, rows = 0;
  std::vector<char> cell, right, up;  // right[i]: i -- i+1 free; up[i]: i -- i+cols free

  int size() const { return cols * rows; }
  Point centre(int i) const { return {x0 + (i % cols) * dx, y0 + (i / cols) * dy}; }
  /// Neighbour of i in direction d (0 up, 1 right, 2 down, 3 left) if joined, else -1.
  int neighbour(int i, int d) const {
    const int c = i % cols, r = i / cols;
    switch (d) {
      case 0: return r + 1 < rows && up[i] ? i + cols : -1;
      case 1: return c + 1 < cols && right[i] ? i + 1 : -1;
      case 2: return r > 0 && up[i - cols] ? i - cols : -1;
      default: return c > 0 && right[i - 1] ? i - 1 : -1;
    }
  }
};

/// Intervals where the line (y = v if horizontal, x = v otherwise) lies inside the region,
/// sorted. Every ring edge crossing the line contributes one endpoint (half-open rule).
std::vector<std::pair<double, double>> inside(const std::vector<Ring>& rings, bool horizontal, double v) {
  std::vector<double> xs;
  for (const Ring& ring : rings)
    for (std::size_t k = 0; k < ring.size(); ++k) {
      Point a = ring[k], b = ring[(k + 1) % ring.size()];
      if (!horizontal) a = {a.y, a.x}, b = {b.y, b.x};
      if ((a.y > v) == (b.y > v)) continue;
      xs.push_back(a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y));
    }
  std::sort(xs.begin(), xs.end());
  std::vector<std::pair<double, double>> out;
  for (std::size_t k = 0; k + 1 < xs.size(); k += 2) out.push_back({xs[k], xs[k + 1]});
  return out;
}

/// Index of the interval containing x, or -1.
int intervalOf(const std::vector<std::pair<double, double>>& intervals, double x) {
  const auto it = std::upper_bound(intervals.begin(), intervals.end(), x,
                                   [](double v, const std::pair<double, double>& iv) { return v < iv.second; });
  if (it == intervals.end() || x < it->first) return -1;
  return static_cast<int>(it - intervals.begin());
}

/// Cells of about `s` (never more) across the box; with `even`, an even number each way.
Grid buildGrid(const Region& free, const Box& box, double s, bool even) {
  Grid g;
  auto axis = [&](double lo, double hi, double& origin, double& step, int& n) {
    const double span = hi - lo - s - 2.0 * kInset;
    n = span <= 0.0 ? 1 : static_cast<int>(std::ceil(span / s - 1e-9)) + 1;
    if (even && n % 2) ++n;
    step = n > 1 && span > 0.0 ? span / (n - 1) : s;
    origin = span > 0.0 ? lo + s / 2.0 + kInset : (lo + hi) / 2.0;
  };
  axis(box.min_x, box.max_x, g.x0, g.dx, g.cols);
  axis(box.min_y, box.max_y, g.y0, g.dy, g.rows);
  const std::vector<Ring> rings = allRings(free);
  g.cell.assign(g.size(), 0);
  g.right.assign(g.size(), 0);
  g.up.assign(g.size(), 0);
  std::vector<int> row_interval(g.size(), -1);
  for (int r = 0; r < g.rows; ++r) {
    const auto iv = inside(rings, true, g.y0 + r * g.dy);
    for (int c = 0; c < g.cols; ++c) {
      const int i = r * g.cols + c;
      row_interval[i] = intervalOf(iv, g.x0 + c * g.dx);
      g.cell[i] = row_interval[i] >= 0;
      if (c > 0 && g.cell[i] && g.cell[i - 1] && row_interval[i] == row_interval[i - 1]) g.right[i - 1] = 1;
    }
  }
  for (int c = 0; c < g.cols; ++c) {
    const auto iv = inside(rings, false, g.x0 + c * g.dx);
    int below = -2;
    for (int r = 0; r < g.rows; ++r) {
      const int i = r * g.cols + c;
      const int here = g.cell[i] ? intervalOf(iv, g.y0 + r * g.dy) : -3;
      if (r > 0 && g.cell[i] && g.cell[i - g.cols] && here >= 0 && here == below) g.up[i - g.cols] = 1;
      below = here;
    }
  }
  return g;
}

/// A grid node's children: at most four (its neighbours), stored in place, so a forest over tens
/// of thousands of cells allocates nothing per cell.
struct Children {
  int items[4] = {-1, -1, -1, -1};
  int count = 0;
  void push_back(int c) { items[count++] = c; }
  std::size_t size() const { return static_cast<std::size_t>(count); }
  int operator[](std::size_t k) const { return items[k]; }
  int* begin() { return items; }
  int* end() { return items + count; }
  const int* begin() const { return items; }
  const int* end() const { return items + count; }
  std::reverse_iterator<const int*> rbegin() const { return std::reverse_iterator<const int*>(end()); }
  std::reverse_iterator<const int*> rend() const { return std::reverse_iterator<const int*>(begin()); }
};

/// Storage for every tree over one grid, indexed by cell (each cell belongs to one tree at most,
/// so nothing is reset between trees): memory linear in the number of cells.
struct Forest {
  explicit Forest(int cells) : children(cells), height(cells, 0), local(cells, -1), placed(cells, 0) {}
  std::vector<Children> children;  // in traversal order
  std::vector<int> height;                 // subtree height (a leaf has 0)
  std::vector<int> local;                  // index within its tree's part (MST)
  std::vector<char> placed;                // already hung into its tree (MST)
};

/// A rooted spanning tree of one connected part of a grid.
struct Tree {
  int root = -1;
  std::vector<int> nodes;  // parents before children
};

/// Depth-first tree, neighbours tried in `order` (directions 0 up, 1 right, 2 down, 3 left).
Tree dfsTree(const Grid& g, int root, const std::array<int, 4>& order, std::vector<char>& seen, Forest& f) {
  Tree t;
  t.root = root;
  std::vector<std::pair<int, int>> stack{{root, 0}};
  seen[root] = 1;
  t.nodes.push_back(root);
  while (!stack.empty()) {
    auto& [node, k] = stack.back();
    if (k == 4) {
      stack.pop_back();
      continue;
    }
    const int next = g.neighbour(node, order[k++]);
    if (next < 0 || seen[next]) continue;
    seen[next] = 1;
    f.children[node].push_back(next);
    t.nodes.push_back(next);
    stack.push_back({next, 0});
  }
  return t;
}

/// Minimum spanning tree (Kruskal, Boost.Graph) of the part reachable from `root`, with edges
/// across the preferred direction costing more, so the tree runs in long straight lines; then
/// rooted, children in `order`.
Tree mstTree(const Grid& g, int root, const std::array<int, 4>& order, std::vector<char>& seen, Forest& f) {
  // The part: breadth-first from the root.
  std::vector<int> part{root};
  f.local[root] = 0;
  seen[root] = 1;
  for (std::size_t k = 0; k < part.size(); ++k)
    for (int d = 0; d < 4; ++d) {
      const int n = g.neighbour(part[k], d);
      if (n >= 0 && !seen[n]) {
        seen[n] = 1;
        f.local[n] = static_cast<int>(part.size());
        part.push_back(n);
      }
    }
  using G = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                  boost::property<boost::edge_weight_t, double>>;
  G graph(part.size());
  const bool rows_first = order[0] == 1 || order[0] == 3;  // first direction horizontal: rows
  for (int i : part)
    for (int d : {0, 1}) {
      const int n = g.neighbour(i, d);
      if (n < 0 || f.local[n] < 0 || part[f.local[n]] != n) continue;  // not joined, or not to cover
      boost::add_edge(f.local[i], f.local[n], (d == 1) == rows_first ? 1.0 : 1.5, graph);
    }
  std::vector<boost::graph_traits<G>::edge_descriptor> edges;
  edges.reserve(part.size());
  boost::kruskal_minimum_spanning_tree(graph, std::back_inserter(edges));
  // Tree edges by direction: bit d of joined[local] says the edge toward direction d is in the tree.
  std::vector<unsigned char> joined(part.size(), 0);
  for (const auto& e : edges) {
    const int a = part[boost::source(e, graph)], b = part[boost::target(e, graph)];
    for (int d = 0; d < 4; ++d) {
      if (g.neighbour(a, d) == b) joined[f.local[a]] |= static_cast<unsigned char>(1 << d);
      if (g.neighbour(b, d) == a) joined[f.local[b]] |= static_cast<unsigned char>(1 << d);
    }
  }
  Tree t;
  t.root = root;
  f.placed[root] = 1;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    t.nodes.push_back(node);
    for (int d : order) {
      if (!(joined[f.local[node]] & (1 << d))) continue;
      const int n = g.neighbour(node, d);
      if (f.placed[n]) continue;
      f.placed[n] = 1;
      f.children[node].push_back(n);
    }
    for (auto it = f.children[node].rbegin(); it != f.children[node].rend(); ++it) stack.push_back(*it);
  }
  return t;
}

enum class Variant { Return, Stop, ShortBranchesFirst, SpiralStc };

/// Appends `p` to a run of moves that starts at `from`, replacing the run's last point when it
/// lies on the straight line on to `p`, going the same way (the same segment, painted the same),
/// unless `every_cell` keeps a waypoint per cell.
void appendStraight(std::vector<Point>& run, Point from, Point p, bool every_cell) {
  const Point a = run.size() >= 2 ? run[run.size() - 2] : from;
  if (!run.empty() && !every_cell) {
    const Point b = run.back();
    const Point u = b - a, w = p - b;
    if (cross(u, w) == 0.0 && dot(u, w) > 0.0) {
      run.back() = p;
      return;
    }
  }
  run.push_back(p);
}

/// The walk around a tree: (cell, first visit) steps; `stop` variants end at the last new cell.
std::vector<std::pair<int, bool>> walk(const Tree& t, Forest& f, Variant variant) {
  if (variant == Variant::ShortBranchesFirst) {
    for (auto it = t.nodes.rbegin(); it != t.nodes.rend(); ++it) {  // children before parents
      int h = 0;
      for (int child : f.children[*it]) h = std::max(h, f.height[child] + 1);
      f.height[*it] = h;
      // Stable insertion sort of at most four children (std::stable_sort allocates a buffer).
      Children& c = f.children[*it];
      for (int i = 1; i < c.count; ++i)
        for (int j = i; j > 0 && f.height[c.items[j]] < f.height[c.items[j - 1]]; --j) std::swap(c.items[j], c.items[j - 1]);
    }
  }
  std::vector<std::pair<int, bool>> steps{{t.root, true}};
  steps.reserve(2 * t.nodes.size());
  std::vector<std::pair<int, std::size_t>> stack{{t.root, 0}};
  while (!stack.empty()) {
    auto& [node, k] = stack.back();
    if (k < f.children[node].size()) {
      const int child = f.children[node][k++];
      steps.push_back({child, true});
      stack.push_back({child, 0});
    } else {
      stack.pop_back();
      if (!stack.empty()) steps.push_back({stack.back().first, false});
    }
  }
  if (variant != Variant::Return)
    while (!steps.empty() && !steps.back().second) steps.pop_back();
  return steps;
}

std::array<int, 4> parseOrder(const std::string& text) {
  std::array<int, 4> order{};
  for (int k = 0; k < 4; ++k) order[k] = static_cast<int>(std::string("URDL").find(text[k]));
  return order;
}

std::vector<std::string> allOrders() {
  std::string letters = "DLRU";  // sorted, for next_permutation
  std::vector<std::string> out;
  do out.push_back(letters);
  while (std::next_permutation(letters.begin(), letters.end()));
  std::stable_partition(out.begin(), out.end(), [](const std::string& o) { return o == "URDL"; });
  return out;
}

class SpanningTreePlanner final : public Planner {
 public:
  PlanResult plan(const Problem& problem, const Budget& budget) override {
    const std::string variant_name = problem.params.choice("variant");
    const Variant variant = variant_name == "return" ? Variant::Return
                            : variant_name == "stop" ? Variant::Stop
                            : variant_name == "spiral-stc" ? Variant::SpiralStc
                                                           : Variant::ShortBranchesFirst;
    const bool mst = problem.params.choice("tree") == "mst";
    const bool every_cell = problem.params.flag("waypoint_per_cell");
    const std::array<int, 4> order = parseOrder(problem.params.choice("neighbour_order"));
    const double s = problem.tool.tool_width;

    Workspace ws(*problem.wall, problem.tool);
    const std::vector<PolygonWithHoles> components = componentsByArea(ws.free());
    if (components.empty())
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "the tool fits nowhere: the free region F is empty for this tool and clearance");
    // Like every planner here: the largest free component (the others cannot be reached).
    const Box box = boundingBox(problem.wall->boundary);
    const Grid grid = buildGrid(Region{components.front()}, box, s, variant == Variant::SpiralStc);
    int free_cells = 0;
    for (char c : grid.cell) free_cells += c;
    if (free_cells == 0)
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "no grid cell centre lies in F: the free region is narrower than the grid spacing");

    PathBuilder builder(ws);
    std::size_t parts = 0, unreachable = 0, tree_cells = 0, leftover_cells = 0, mega_cells = 0;
    // Covers a set of cells (`open` marks them) part by part with trees of `variant`.
    auto coverParts = [&](const Grid& g, std::vector<char> open, Variant v) {
      std::vector<char> seen(g.size(), 0);
      for (int i = 0; i < g.size(); ++i) seen[i] = !open[i];
      Forest forest(g.size());
      for (int root = 0; root < g.size(); ++root) {  // lowest row first, then leftmost
        if (seen[root]) continue;
        if (budget.expired()) return false;
        Tree t = mst ? mstTree(g, root, order, seen, forest) : dfsTree(g, root, order, seen, forest);
        ++parts;
        tree_cells += t.nodes.size();
        if (!builder.moveTo(g.centre(root), false)) {
          ++unreachable;
          continue;
        }
        // One follow per run of equal tool state (the walk alternates new cells and returns),
        // and a waypoint only where the walk turns: cells in a straight line are one segment.
        std::vector<Point> run;
        bool run_tool = true;
        for (const auto& [cell, first] : walk(t, forest, v)) {
          if (first != run_tool && !run.empty()) {
            builder.follow(run, run_tool);
            run.clear();
          }
          run_tool = first;
          appendStraight(run, builder.empty() ? Point{} : builder.current(), g.centre(cell), every_cell);
        }
        builder.follow(run, run_tool);
      }
      return true;
    };

    bool finished = true;
    if (variant != Variant::SpiralStc) {
      finished = coverParts(grid, grid.cell, variant);
    } else {
      // Mega-cells: 2 x 2 sub-cells, all four free and joined; neighbours joined on both rows or
      // columns they share.
      Grid mega;
      mega.cols = grid.cols / 2;
      mega.rows = grid.rows / 2;
      mega.x0 = grid.x0 + grid.dx / 2.0;
      mega.y0 = grid.y0 + grid.dy / 2.0;
      mega.dx = 2.0 * grid.dx;
      mega.dy = 2.0 * grid.dy;
      mega.cell.assign(mega.size(), 0);
      mega.right.assign(mega.size(), 0);
      mega.up.assign(mega.size(), 0);
      auto sub = [&](int m, int corner) {  // 0 BL, 1 BR, 2 TR, 3 TL
        const int c = 2 * (m % mega.cols) + (corner == 1 || corner == 2), r = 2 * (m / mega.cols) + (corner >= 2);
        return r * grid.cols + c;
      };
      for (int m = 0; m < mega.size(); ++m) {
        const int bl = sub(m, 0), br = sub(m, 1), tl = sub(m, 3);
        mega.cell[m] = grid.cell[bl] && grid.cell[br] && grid.cell[sub(m, 2)] && grid.cell[tl] && grid.right[bl] &&
                       grid.right[tl] && grid.up[bl] && grid.up[br];
        mega_cells += mega.cell[m];
      }
      for (int m = 0; m < mega.size(); ++m) {
        if (!mega.cell[m]) continue;
        const int c = m % mega.cols, r = m / mega.cols;
        if (c + 1 < mega.cols && mega.cell[m + 1]) mega.right[m] = grid.right[sub(m, 1)] && grid.right[sub(m, 2)];
        if (r + 1 < mega.rows && mega.cell[m + mega.cols]) mega.up[m] = grid.up[sub(m, 3)] && grid.up[sub(m, 2)];
      }
      // Circumnavigate each mega-cell tree: every mega-cell's four sub-cells form a
      // counter-clockwise cycle; each tree edge splices its two cycles into one.
      std::vector<int> next(grid.size(), -1);
      for (int m = 0; m < mega.size(); ++m)
        if (mega.cell[m])
          for (int k = 0; k < 4; ++k) next[sub(m, k)] = sub(m, (k + 1) % 4);
      std::vector<char> seen(mega.size(), 0);
      for (int m = 0; m < mega.size(); ++m) seen[m] = !mega.cell[m];
      Forest forest(mega.size());
      for (int root = 0; root < mega.size(); ++root) {
        if (seen[root]) continue;
        if (budget.expired()) {
          finished = false;
          break;
        }
        Tree t = mst ? mstTree(mega, root, order, seen, forest) : dfsTree(mega, root, order, seen, forest);
        ++parts;
        tree_cells += 4 * t.nodes.size();
        for (int parent : t.nodes)
          for (int child : forest.children[parent]) {
            if (child == parent + 1 || child == parent - 1) {  // side by side
              const int left = std::min(parent, child), right = std::max(parent, child);
              next[sub(left, 1)] = sub(right, 0);
              next[sub(right, 3)] = sub(left, 2);
            } else {  // one above the other
              const int low = std::min(parent, child), high = std::max(parent, child);
              next[sub(low, 2)] = sub(high, 1);
              next[sub(high, 0)] = sub(low, 3);
            }
          }
        const int start = sub(root, 0);
        if (!builder.moveTo(grid.centre(start), false)) {
          ++unreachable;
          continue;
        }
        std::vector<Point> loop;
        for (int cell = next[start]; cell != start; cell = next[cell])
          appendStraight(loop, builder.current(), grid.centre(cell), every_cell);
        builder.follow(loop, true);
      }
      // Free sub-cells of partially blocked mega-cells: ordinary trees over what is left.
      std::vector<char> left = grid.cell;
      for (int m = 0; m < mega.size(); ++m)
        if (mega.cell[m])
          for (int k = 0; k < 4; ++k) left[sub(m, k)] = 0;
      for (char c : left) leftover_cells += c;
      if (finished) finished = coverParts(grid, left, Variant::ShortBranchesFirst);
    }
    if (!finished) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");

    PlanResult result;
    result.status = PlanStatus::Ok;
    result.path = builder.take();
    result.stats["grid_cells"] = static_cast<double>(grid.size());
    result.stats["free_cells"] = static_cast<double>(free_cells);
    result.stats["grid_spacing_x"] = grid.dx;
    result.stats["grid_spacing_y"] = grid.dy;
    result.stats["trees"] = static_cast<double>(parts);
    result.stats["tree_cells"] = static_cast<double>(tree_cells);
    if (variant == Variant::SpiralStc) {
      result.stats["mega_cells"] = static_cast<double>(mega_cells);
      result.stats["partially_blocked_sub_cells"] = static_cast<double>(leftover_cells);
    }
    recordOutcome(result, builder, components.size(), unreachable);
    return result;
  }
};

}  // namespace

PlannerInfo info() {
  PlannerInfo info;
  info.name = "spanning-tree";
  info.version = std::string("2");  // not = "2": GCC 12 warns falsely (-Wrestrict) on that assignment here
  info.code_folders = {"spanning_tree"};
  info.summary = "Spanning-tree coverage of a grid of tool-sized cells in F; return, stop, short-branches-first or Spiral-STC";
  info.reference = "Gabriely & Rimon, Spanning-tree based coverage of continuous areas by a mobile robot, AMAI 31, 2001";
  info.params = {
      {"variant", ParamType::Choice, std::string("short-branches-first"), 0, 0,
       {"return", "stop", "short-branches-first", "spiral-stc"}, "", "how the tree is walked (see README)"},
      {"tree", ParamType::Choice, std::string("dfs"), 0, 0, {"dfs", "mst"}, "",
       "depth-first in neighbour order, or a minimum spanning tree preferring straight runs"},
      {"neighbour_order", ParamType::Choice, std::string("URDL"), 0, 0, allOrders(), "",
       "order neighbours are tried in: U up, R right, D down, L left"},
      {"waypoint_per_cell", ParamType::Bool, false, 0, 0, {}, "",
       "a waypoint at every cell visited (the classic STC output) instead of only where the walk turns; "
       "the same path"},
  };
  info.min_coverage_reachable = 0.0;  // a grid method: corners and strips narrower than a cell stay uncovered
  info.make = [] { return std::make_unique<SpanningTreePlanner>(); };
  return info;
}

}  // namespace coverbench::spanning_tree
