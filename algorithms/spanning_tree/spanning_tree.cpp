#include "spanning_tree.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>

#include "coverbench/limits.hpp"
#include "coverbench/clearance.hpp"
#include "coverbench/param_table.hpp"
#include "coverbench/plan_frame.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/boundary_arcs.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::spanning_tree {
namespace {

/// With the loop (which paints half a tool width into F), a cell is used when its centre lies at
/// least this many tool widths inside F: a cell centred on F's edge would paint only the loop's
/// band again, and one centred closer than this leaves a strip at most this wide unpainted.
constexpr double kLoopMargin = 0.05;

/// A grid of cell centres over a region: which cells are free, which neighbours are joined by a
/// free segment. Cell i is column i % cols, row i / cols.
struct Grid {
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  int cols = 0, rows = 0;
  std::vector<char> cell;
  std::vector<unsigned char> links;  // bit d: joined to the neighbour in direction d (see neighbour)

  int size() const { return cols * rows; }
  Point centre(int i) const { return {x0 + (i % cols) * dx, y0 + (i / cols) * dy}; }
  bool right(int i) const { return links[i] & 2; }
  bool up(int i) const { return links[i] & 1; }
  /// Joins cell i to its right neighbour (`to_right`) or to the one above, both ways.
  void join(int i, bool to_right) {
    if (to_right)
      links[i] |= 2, links[i + 1] |= 8;
    else
      links[i] |= 1, links[i + cols] |= 4;
  }
  /// Index step to the neighbour in direction d (0 up, 1 right, 2 down, 3 left).
  int step(int d) const { return d == 0 ? cols : d == 1 ? 1 : d == 2 ? -cols : -1; }
  /// The direction of the step from cell i to its neighbour j.
  int direction(int i, int j) const { return j - i == cols ? 0 : j - i == 1 ? 1 : j - i == -cols ? 2 : 3; }
  /// Neighbour of i in direction d if joined, else -1.
  int neighbour(int i, int d) const {
    if (!(links[i] >> d & 1)) return -1;
    return i + step(d);
  }
};

/// Decides what F's conservative polygon cannot, for centres within its margin of F's exact edge:
/// whether a tool disk there (or moving between two centres) keeps the wall and the clearance,
/// measured exactly, with the planning margin every transit keeps (so a route can start and end
/// at such a centre).
struct EdgeCheck {
  const ClearanceField* field = nullptr;
  double radius = 0.0, clearance = 0.0;
  bool free(Point a, Point b) const { return field->segmentFree(a, b, radius, clearance, kPlanningMargin); }
};

/// The grid over a part of F with pitch exactly `s`: cell 0's centre at `origin`, as many cells
/// each way as fit up to the part's far edges (with `even`, an even number each way). A cell is
/// free when its centre lies at least `margin` inside F along both its row and its column, and
/// two neighbours are joined when the segment between them does (they lie in one free interval of
/// their row or column): both are decided exactly from the crossings of the grid lines with F's
/// rings, with no sampling. With `exact`, centres and links in F's conservative margin (a centre
/// on F's exact edge, as on a wall whose size is a multiple of s) are measured instead.
Grid buildGrid(const Region& free, Point origin, const Box& box, double s, bool even, double margin,
               const EdgeCheck* exact) {
  Grid g;
  auto count = [&](double lo, double hi) {
    int n = hi < lo ? 1 : static_cast<int>(std::floor((hi - lo) / s)) + 1;
    if (even && n % 2) ++n;
    return n;
  };
  g.x0 = origin.x;
  g.y0 = origin.y;
  g.dx = g.dy = s;
  const double reach = exact ? kFreeSpaceMargin + 1e-6 : 0.0;  // how far beyond F's polygon a centre may lie
  g.cols = count(origin.x, box.max_x + reach);
  g.rows = count(origin.y, box.max_y + reach);
  const std::vector<Ring> rings = allRings(free);
  std::vector<Ring> swapped = rings;  // x and y swapped: the columns as rows
  for (Ring& ring : swapped)
    for (Point& p : ring) p = {p.y, p.x};
  using Intervals = std::vector<std::pair<double, double>>;
  // The free intervals of each grid line (rows if `rows`, else columns), each grown by `grow`;
  // with `shift`, also those of the lines `shift` either side (merged), so a centre on a line
  // that just misses F's polygon (running along F's exact edge) is found too.
  auto intervals = [&](bool rows, double grow, double shift) {
    const double v0 = rows ? g.y0 : g.x0;
    const int lines = rows ? g.rows : g.cols;
    std::vector<Intervals> out(static_cast<std::size_t>(lines));
    std::vector<double> ys(static_cast<std::size_t>(lines));
    for (double d : shift > 0.0 ? std::vector<double>{-shift, 0.0, shift} : std::vector<double>{0.0}) {
      for (std::size_t line = 0; line < ys.size(); ++line) ys[line] = v0 + d + static_cast<double>(line) * s;
      const std::vector<std::vector<RingCrossing>> xs = scanlineCrossings(rows ? rings : swapped, ys);
      for (std::size_t line = 0; line < xs.size(); ++line)
        for (std::size_t k = 0; k + 1 < xs[line].size(); k += 2)
          if (xs[line][k].x - grow <= xs[line][k + 1].x + grow)
            out[line].push_back({xs[line][k].x - grow, xs[line][k + 1].x + grow});
    }
    if (shift > 0.0)
      for (Intervals& iv : out) {
        std::sort(iv.begin(), iv.end());
        Intervals merged;
        for (const auto& [lo, hi] : iv)
          if (!merged.empty() && lo <= merged.back().second) merged.back().second = std::max(merged.back().second, hi);
          else merged.push_back({lo, hi});
        iv = std::move(merged);
      }
    return out;
  };
  // Calls f(cell, interval, first) for every cell whose centre lies in a free interval of its
  // line, `first` for the interval's first cell.
  const std::size_t n = static_cast<std::size_t>(g.size());
  auto each = [&](const std::vector<Intervals>& lines, bool rows, auto&& f) {
    const double v0 = rows ? g.x0 : g.y0;
    const int along = rows ? g.cols : g.rows;
    for (std::size_t line = 0; line < lines.size(); ++line)
      for (std::size_t k = 0; k < lines[line].size(); ++k) {
        const auto [lo, hi] = lines[line][k];
        const int first = std::max(0, static_cast<int>(std::ceil((lo - v0) / s)));
        for (int j = first; j < along && v0 + j * s <= hi; ++j)
          f(rows ? line * g.cols + j : j * g.cols + line, static_cast<int>(k), j == first);
      }
  };
  // Sure: at least `margin` inside F's polygon along the row (bit 0 of cell) and the column
  // (bit 1); consecutive cells of one interval are joined. Marked straight into the grid: a few
  // bytes a cell in all.
  // Until the cells are known, bits 1 and 0 of links[i] mark "i and its right (upper) neighbour
  // lie in one interval"; then both ends of every link whose cells are free are set.
  g.cell.assign(n, 0);
  g.links.assign(n, 0);
  each(intervals(true, -margin, 0.0), true, [&](std::size_t i, int, bool first) {
    g.cell[i] |= 1;
    if (!first) g.links[i - 1] |= 2;
  });
  each(intervals(false, -margin, 0.0), false, [&](std::size_t i, int, bool first) {
    g.cell[i] |= 2;
    if (!first) g.links[i - g.cols] |= 1;
  });
  for (std::size_t i = 0; i < n; ++i) g.cell[i] = g.cell[i] == 3;
  for (int i = 0; i < g.size(); ++i) {
    const unsigned char same = g.links[i] & 3;
    g.links[i] &= 12;  // the ends set by the cells before it
    if (!g.cell[i]) continue;
    if ((same & 2) && g.cell[i + 1]) g.join(i, true);
    if ((same & 1) && g.cell[i + g.cols]) g.join(i, false);
  }
  if (exact) {
    // Wide: within F's conservative margin of its exact edge. Such a cell, or a move between two
    // cells of one wide interval that is not already sure, is measured.
    std::vector<int> row_wide(n, -1), col_wide(n, -1);
    each(intervals(true, reach, reach), true, [&](std::size_t i, int k, bool) { row_wide[i] = k; });
    each(intervals(false, reach, reach), false, [&](std::size_t i, int k, bool) { col_wide[i] = k; });
    const std::vector<char> sure = g.cell;
    for (std::size_t i = 0; i < n; ++i)
      if (!sure[i] && row_wide[i] >= 0 && col_wide[i] >= 0)
        g.cell[i] = exact->free(g.centre(static_cast<int>(i)), g.centre(static_cast<int>(i)));
    auto measured = [&](std::size_t i, std::size_t j, const std::vector<int>& wide) {
      return g.cell[i] && g.cell[j] && wide[i] >= 0 && wide[i] == wide[j] &&
             exact->free(g.centre(static_cast<int>(i)), g.centre(static_cast<int>(j)));
    };
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.cols; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * g.cols + c;
        if (c + 1 < g.cols && !g.right(static_cast<int>(i)) && measured(i, i + 1, row_wide)) g.join(static_cast<int>(i), true);
        if (r + 1 < g.rows && !g.up(static_cast<int>(i)) && measured(i, i + g.cols, col_wide)) g.join(static_cast<int>(i), false);
      }
  }
  return g;
}

/// Every tree over one grid, indexed by cell (each cell belongs to one tree at most, so nothing is
/// reset between trees), in a few bytes a cell: on a wall of 40 000 cells, the first-touch page
/// faults of larger per-cell records cost more than building and walking the trees.
/// - kids: a node's children (at most four neighbours) as directions packed in 16 bits: the count
///   in bits 0-2, then 2 bits a child, in walking order;
/// - state: bit 7 taken by a tree (or not to be covered: any non-zero state), bit 5 has a parent,
///   bits 3-4 the direction to it, bits 0-2 a counter (directions tried while building, children
///   walked while walking). The parent links replace a stack: trees here are as deep as a
///   serpentine through every cell.
struct Forest {
  Forest(const Grid& grid, const std::vector<char>& open, bool heights, bool mst)
      : g(&grid), kids(open.size(), 0), state(open.size(), 0) {
    for (std::size_t i = 0; i < open.size(); ++i)
      if (!open[i]) state[i] = kTaken;
    if (heights) height.assign(kids.size(), 0);
    if (mst) local.assign(kids.size(), -1), placed.assign(kids.size(), 0);
  }
  static constexpr unsigned char kTaken = 0x80, kHasParent = 0x20;
  const Grid* g;
  std::vector<std::uint16_t> kids;
  std::vector<unsigned char> state;
  std::vector<std::uint16_t> height;  // subtree height, a leaf 0, at most 65535 (short-branches-first only)
  std::vector<int> local;    // index within its tree's part (MST only)
  std::vector<char> placed;  // already hung into its tree (MST only)
  std::vector<int> nodes;    // the current tree's nodes, parents before children (MST only)

  bool taken(int i) const { return state[i] != 0; }
  int count(int node) const { return kids[node] & 7; }
  int direction(int node, int k) const { return kids[node] >> (3 + 2 * k) & 3; }
  int child(int node, int k) const { return node + step(direction(node, k)); }
  int step(int d) const { return g->step(d); }
  bool hasParent(int node) const { return state[node] & kHasParent; }
  int parent(int node) const { return node + step(state[node] >> 3 & 3); }
  int counter(int node) const { return state[node] & 7; }
  void setCounter(int node, int k) { state[node] = static_cast<unsigned char>((state[node] & ~7) | k); }
  /// Hangs neighbour n (in direction d of node) into node's tree as its next child.
  void adopt(int node, int d, int n) {
    kids[node] = static_cast<std::uint16_t>((kids[node] | d << (3 + 2 * count(node))) + 1);
    state[n] = static_cast<unsigned char>(kTaken | kHasParent | ((d + 2) % 4) << 3);
  }
  /// With heights: the node's subtree height from its children's, and its children reordered by
  /// increasing height, ties in their order (stable), so the tallest branch is walked last.
  /// Heights stop at 65535 (two bytes a cell): branches taller than that count as equal.
  void finish(int node) {
    if (height.empty()) return;
    int d[4], n = count(node), h = 0;
    for (int k = 0; k < n; ++k) {
      d[k] = direction(node, k);
      h = std::max(h, height[node + step(d[k])] + 1);
    }
    height[node] = static_cast<std::uint16_t>(std::min(h, 65535));
    for (int i = 1; i < n; ++i)
      for (int j = i; j > 0 && height[node + step(d[j])] < height[node + step(d[j - 1])]; --j) std::swap(d[j], d[j - 1]);
    kids[node] = static_cast<std::uint16_t>(n);
    for (int k = 0; k < n; ++k) kids[node] = static_cast<std::uint16_t>(kids[node] | d[k] << (3 + 2 * k));
  }
};

/// Depth-first tree of the part around `root`, neighbours tried in `order` (directions 0 up,
/// 1 right, 2 down, 3 left); returns its number of nodes.
std::size_t dfsTree(const Grid& g, int root, const std::array<int, 4>& order, Forest& f) {
  f.state[root] = Forest::kTaken;
  std::size_t nodes = 1;
  int node = root;
  while (true) {
    int k = f.counter(node), next = -1;
    while (k < 4 && next < 0) {
      const int d = order[k++];
      const int n = g.neighbour(node, d);
      if (n >= 0 && !f.taken(n)) {
        f.adopt(node, d, n);
        next = n;
      }
    }
    f.setCounter(node, k);
    if (next >= 0) {
      node = next;
      ++nodes;
      continue;
    }
    f.finish(node);  // every child is finished
    f.setCounter(node, 0);
    if (!f.hasParent(node)) break;
    node = f.parent(node);
  }
  return nodes;
}

/// Minimum spanning tree (Kruskal, Boost.Graph) of the part reachable from `root` (its nodes in
/// f.nodes), with edges across the preferred direction costing more, so the tree runs in long
/// straight lines; then rooted, children in `order`.
std::size_t mstTree(const Grid& g, int root, const std::array<int, 4>& order, Forest& f) {
  // The part: breadth-first from the root.
  std::vector<int> part{root};
  // `local` marks the part: state is set as nodes are hung into the tree.
  f.local[root] = 0;
  for (std::size_t k = 0; k < part.size(); ++k)
    for (int d = 0; d < 4; ++d) {
      const int n = g.neighbour(part[k], d);
      if (n >= 0 && !f.taken(n) && f.local[n] < 0) {
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
  f.nodes.clear();
  f.placed[root] = 1;
  f.state[root] = Forest::kTaken;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    f.nodes.push_back(node);
    for (int d : order) {
      if (!(joined[f.local[node]] & (1 << d))) continue;
      const int n = g.neighbour(node, d);
      if (f.placed[n]) continue;
      f.placed[n] = 1;
      f.adopt(node, d, n);
    }
    for (int k = f.count(node) - 1; k >= 0; --k) stack.push_back(f.child(node, k));
  }
  for (auto it = f.nodes.rbegin(); it != f.nodes.rend(); ++it) f.finish(*it);  // children before parents
  return f.nodes.size();
}

enum class Variant { Return, Stop, ShortBranchesFirst, SpiralStc };

/// A run of moves from cell to neighbouring cell with one tool state, kept as the cells where it
/// turns: a move in the same direction as the one before replaces the run's last cell (the same
/// segment, painted the same), unless `every_cell` keeps a waypoint per cell. Directions are
/// compared as index steps on the grid, which are equal exactly when the moves are.
class CellRun {
 public:
  CellRun(const Grid& g, bool every_cell) : g_(&g), every_cell_(every_cell) {}
  /// Where the walk stands (the builder's current point), before the first add.
  void start(int cell) {
    at_ = cell;
    step_ = 0;
  }
  void add(int cell) {
    const int step = cell - at_;
    if (!cells_.empty() && !every_cell_ && step == step_)
      cells_.back() = cell;
    else
      cells_.push_back(cell);
    step_ = step;
    at_ = cell;
  }
  bool empty() const { return cells_.empty(); }
  /// Hands the run to the builder and starts a new one where it ends.
  void flush(PathBuilder& builder, bool tool_on) {
    points_.clear();
    for (int c : cells_) points_.push_back(g_->centre(c));
    builder.follow(points_, tool_on);
    cells_.clear();
  }

 private:
  const Grid* g_;
  bool every_cell_;
  int at_ = -1, step_ = 0;
  std::vector<int> cells_;
  std::vector<Point> points_;
};

/// Walks around a tree from its root, calling visit(cell, first) for every step: first is true on a
/// cell's first visit (a move that paints) and false on a move back to its parent. `stop` variants
/// end at the last new cell (the moves back after it are never made). Moves back are counted and
/// made only when a new cell follows; they retrace the parent links from where they began.
template <class Visit>
void walk(int root, Forest& f, Variant variant, Visit&& visit) {
  int node = root, back_from = -1;
  std::size_t backs = 0;
  auto goBack = [&] {
    for (int c = back_from; backs > 0; --backs) visit(c = f.parent(c), false);
  };
  while (true) {
    const int k = f.counter(node);
    if (k < f.count(node)) {
      f.setCounter(node, k + 1);
      goBack();
      node = f.child(node, k);
      visit(node, true);
      continue;
    }
    if (!f.hasParent(node)) break;
    if (backs == 0) back_from = node;
    ++backs;
    node = f.parent(node);
  }
  if (variant == Variant::Return) goBack();
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

enum class Tree { Dfs, Mst };

/// The planner's parameters (paramTable declares them).
struct SpanningTreeParams {
  Variant variant = Variant::ShortBranchesFirst;
  Tree tree = Tree::Dfs;
  std::array<int, 4> neighbour_order{};  ///< indices into URDL
  bool boundary_loop = true;
  bool waypoint_per_cell = false;
  bool corner_spurs = false;
};

const ParamTable<SpanningTreeParams>& paramTable() {
  static const ParamTable<SpanningTreeParams> table = [] {
    std::vector<std::pair<std::string, std::array<int, 4>>> orders;
    for (const std::string& o : allOrders()) orders.emplace_back(o, parseOrder(o));
    return ParamTable<SpanningTreeParams>()
        .add({"variant", ParamType::Choice, std::string("short-branches-first"), 0, 0, {}, "",
              "how the tree is walked (see README)"},
             &SpanningTreeParams::variant,
             {{"return", Variant::Return},
              {"stop", Variant::Stop},
              {"short-branches-first", Variant::ShortBranchesFirst},
              {"spiral-stc", Variant::SpiralStc}})
        .add({"tree", ParamType::Choice, std::string("dfs"), 0, 0, {}, "",
              "depth-first in neighbour order, or a minimum spanning tree preferring straight runs"},
             &SpanningTreeParams::tree, {{"dfs", Tree::Dfs}, {"mst", Tree::Mst}})
        .add({"neighbour_order", ParamType::Choice, std::string("URDL"), 0, 0, {}, "",
              "order neighbours are tried in: U up, R right, D down, L left"},
             &SpanningTreeParams::neighbour_order, orders)
        .add({"boundary_loop", ParamType::Bool, true, 0, 0, {}, "",
              "one pass along F's boundary before the trees (paints what the grid's cells leave along edges and "
              "obstacles); false gives the classic grid-only method"},
             &SpanningTreeParams::boundary_loop)
        .add({"waypoint_per_cell", ParamType::Bool, false, 0, 0, {}, "",
              "a waypoint at every cell visited (the classic STC output) instead of only where the walk turns; "
              "the same path"},
             &SpanningTreeParams::waypoint_per_cell)
        .add(cornerSpursParam(), &SpanningTreeParams::corner_spurs);
  }();
  return table;
}

/// Covers cells with trees, counting what it did: builds each part's tree, moves to its root and
/// walks it (coverParts), or, for Spiral-STC, circumnavigates the trees of mega-cells first
/// (spiralStc).
class TreeCover {
 public:
  TreeCover(PathBuilder& builder, const SpanningTreeParams& params, const Budget& budget)
      : builder_(&builder), budget_(&budget), mst_(params.tree == Tree::Mst), every_cell_(params.waypoint_per_cell),
        order_(params.neighbour_order) {}

  std::size_t parts = 0, unreachable = 0, tree_cells = 0, leftover_cells = 0, mega_cells = 0;

  /// Covers a set of cells (`open` marks them) part by part with trees of `variant`, lowest row
  /// first, then leftmost. False: the budget ran out.
  bool coverParts(const Grid& g, const std::vector<char>& open, Variant variant) {
    Forest forest(g, open, variant == Variant::ShortBranchesFirst, mst_);
    for (int root = 0; root < g.size(); ++root) {
      if (forest.taken(root)) continue;
      if (budget_->expired()) return false;
      ++parts;
      tree_cells += grow(g, root, forest);
      if (!builder_->moveTo(g.centre(root), false)) {
        ++unreachable;
        continue;
      }
      // One follow per run of equal tool state (the walk alternates new cells and returns),
      // and a waypoint only where the walk turns: cells in a straight line are one segment.
      CellRun run(g, every_cell_);
      run.start(root);
      bool run_tool = true;
      walk(root, forest, variant, [&](int cell, bool first) {
        if (first != run_tool && !run.empty()) run.flush(*builder_, run_tool);
        run_tool = first;
        run.add(cell);
      });
      run.flush(*builder_, run_tool);
    }
    return true;
  }

  /// Spiral-STC: mega-cells of 2 x 2 sub-cells of `grid`, all four free and joined, neighbours
  /// joined on both rows or columns they share; each tree of mega-cells circumnavigated, then the
  /// free sub-cells of partially blocked mega-cells covered by ordinary trees. False: the budget
  /// ran out.
  bool spiralStc(const Grid& grid) {
    Grid mega;
    mega.cols = grid.cols / 2;
    mega.rows = grid.rows / 2;
    mega.x0 = grid.x0 + grid.dx / 2.0;
    mega.y0 = grid.y0 + grid.dy / 2.0;
    mega.dx = 2.0 * grid.dx;
    mega.dy = 2.0 * grid.dy;
    mega.cell.assign(mega.size(), 0);
    mega.links.assign(mega.size(), 0);
    auto sub = [&](int m, int corner) {  // 0 BL, 1 BR, 2 TR, 3 TL
      const int c = 2 * (m % mega.cols) + (corner == 1 || corner == 2), r = 2 * (m / mega.cols) + (corner >= 2);
      return r * grid.cols + c;
    };
    for (int m = 0; m < mega.size(); ++m) {
      const int bl = sub(m, 0), br = sub(m, 1), tl = sub(m, 3);
      mega.cell[m] = grid.cell[bl] && grid.cell[br] && grid.cell[sub(m, 2)] && grid.cell[tl] && grid.right(bl) &&
                     grid.right(tl) && grid.up(bl) && grid.up(br);
      mega_cells += mega.cell[m];
    }
    for (int m = 0; m < mega.size(); ++m) {
      if (!mega.cell[m]) continue;
      const int c = m % mega.cols, r = m / mega.cols;
      if (c + 1 < mega.cols && mega.cell[m + 1] && grid.right(sub(m, 1)) && grid.right(sub(m, 2))) mega.join(m, true);
      if (r + 1 < mega.rows && mega.cell[m + mega.cols] && grid.up(sub(m, 3)) && grid.up(sub(m, 2))) mega.join(m, false);
    }
    // Circumnavigate each mega-cell tree: every mega-cell's four sub-cells form a
    // counter-clockwise cycle; each tree edge splices its two cycles into one.
    // The cycle's successor of each sub-cell, always a neighbour: its direction, a byte a cell.
    std::vector<unsigned char> next(grid.size(), 0);
    auto precede = [&](int from, int to) { next[from] = static_cast<unsigned char>(grid.direction(from, to)); };
    auto successor = [&](int cell) { return cell + grid.step(next[cell]); };
    for (int m = 0; m < mega.size(); ++m)
      if (mega.cell[m])
        for (int k = 0; k < 4; ++k) precede(sub(m, k), sub(m, (k + 1) % 4));
    Forest forest(mega, mega.cell, false, mst_);
    for (int root = 0; root < mega.size(); ++root) {
      if (forest.taken(root)) continue;
      if (budget_->expired()) return false;
      ++parts;
      tree_cells += 4 * grow(mega, root, forest);
      walk(root, forest, Variant::Stop, [&](int child, bool first) {  // every tree edge once
        if (!first) return;
        const int parent = forest.parent(child);
        if (child == parent + 1 || child == parent - 1) {  // side by side
          const int left = std::min(parent, child), right = std::max(parent, child);
          precede(sub(left, 1), sub(right, 0));
          precede(sub(right, 3), sub(left, 2));
        } else {  // one above the other
          const int low = std::min(parent, child), high = std::max(parent, child);
          precede(sub(low, 2), sub(high, 1));
          precede(sub(high, 0), sub(low, 3));
        }
      });
      const int start = sub(root, 0);
      if (!builder_->moveTo(grid.centre(start), false)) {
        ++unreachable;
        continue;
      }
      CellRun cycle(grid, every_cell_);
      cycle.start(start);
      for (int cell = successor(start); cell != start; cell = successor(cell)) cycle.add(cell);
      cycle.flush(*builder_, true);
    }
    // Free sub-cells of partially blocked mega-cells: ordinary trees over what is left.
    std::vector<char> left = grid.cell;
    for (int m = 0; m < mega.size(); ++m)
      if (mega.cell[m])
        for (int k = 0; k < 4; ++k) left[sub(m, k)] = 0;
    for (char c : left) leftover_cells += c;
    return coverParts(grid, left, Variant::ShortBranchesFirst);
  }

 private:
  /// The tree of the part around `root` (dfsTree or mstTree); its number of nodes.
  std::size_t grow(const Grid& g, int root, Forest& forest) const {
    return mst_ ? mstTree(g, root, order_, forest) : dfsTree(g, root, order_, forest);
  }

  PathBuilder* builder_;
  const Budget* budget_;
  bool mst_, every_cell_;
  std::array<int, 4> order_;
};

class SpanningTreePlanner final : public TypedPlanner<SpanningTreeParams> {
 public:
  SpanningTreePlanner() : TypedPlanner(paramTable()) {}

 protected:
  PlanResult planWith(const Problem& problem, const SpanningTreeParams& params, const Budget& budget) override {
    const Variant variant = params.variant;
    const double s = problem.tool.tool_width;
    const bool loop = params.boundary_loop;

    if (const std::string why = gridCellsProblem(problem.tool, *problem.wall); !why.empty())
      return PlanResult::failure(PlanStatus::InvalidInput, why);
    PlanFrame frame(problem);
    if (frame.empty()) return PlanFrame::fitsNowhere();
    // With the boundary loop, the cells start one tool width inside F's extent, where the loop's
    // band ends. Without it, two planning margins inside F's exact edge where the wall's edge is
    // straight (such cells are measured). A centre one cell-multiple from there lies outside the opposite
    // edge of a part exactly that wide, and is dropped: a grid of pitch exactly s cannot keep a
    // margin from both edges of it. The loop paints that strip.
    const Region& part = frame.covered();
    const Box box = boundingBox(part);
    const Box wall_box = boundingBox(problem.wall->boundary);
    const double reach = problem.tool.radius() + problem.tool.clearance + 2.0 * kPlanningMargin;
    const Point origin = loop ? Point{box.min_x + s, box.min_y + s} : Point{wall_box.min_x + reach, wall_box.min_y + reach};
    const EdgeCheck edge{&frame.ws().field(), problem.tool.radius(), problem.tool.clearance};
    const Grid grid = buildGrid(part, origin, box, s, variant == Variant::SpiralStc, loop ? kLoopMargin * s : 0.0,
                                loop ? nullptr : &edge);
    int free_cells = 0;
    for (char c : grid.cell) free_cells += c;
    if (free_cells == 0 && !loop)
      return PlanResult::failure(PlanStatus::NoReachableArea,
                                 "no grid cell centre lies in F: the free region is narrower than the grid spacing");

    PathBuilder builder(frame.ws());
    TreeCover cover(builder, params, budget);
    // The loop first: one pass along every ring of F paints the band the cells leave along F's
    // edge (partially blocked cells, slanted edges, rounded corners).
    if (loop) cover.unreachable += coverRings(builder, allRings(part), 1.01 * s);
    const bool finished =
        variant == Variant::SpiralStc ? cover.spiralStc(grid) : cover.coverParts(grid, grid.cell, variant);
    if (!finished) return PlanResult::failure(PlanStatus::Timeout, "time budget ran out");

    Path path = builder.take();
    std::size_t spurs = 0;
    if (params.corner_spurs) path = withCornerSpurs(path, problem.tool.radius(), frame.ws().router(), spurs);
    PlanResult result = frame.finish(builder, std::move(path), cover.unreachable);
    if (params.corner_spurs) result.stats["corner_spurs"] = static_cast<double>(spurs);
    result.stats["grid_cells"] = static_cast<double>(grid.size());
    result.stats["free_cells"] = static_cast<double>(free_cells);
    result.stats["grid_spacing_x"] = grid.dx;
    result.stats["grid_spacing_y"] = grid.dy;
    result.stats["trees"] = static_cast<double>(cover.parts);
    result.stats["tree_cells"] = static_cast<double>(cover.tree_cells);
    if (variant == Variant::SpiralStc) {
      result.stats["mega_cells"] = static_cast<double>(cover.mega_cells);
      result.stats["partially_blocked_sub_cells"] = static_cast<double>(cover.leftover_cells);
    }
    return result;
  }
};

}  // namespace

PlannerInfo info() {
  // The loop paints what the cells leave along F's edge; a round tool still leaves the outer corner
  // of each turn of the walk (lowest on the conformance walls: 0.988, gable walls at s = 0.1 m).
  return typedPlannerInfo<SpanningTreePlanner>(
      {.name = "spanning-tree", .version = "5", .code_folders = {"spanning_tree"},
       .summary = "A loop along F's boundary, then spanning-tree coverage of a grid of tool-sized cells; return, stop, "
                  "short-branches-first or Spiral-STC",
       .reference = "Gabriely & Rimon, Spanning-tree based coverage of continuous areas by a mobile robot, AMAI 31, 2001",
       .min_coverage_reachable = 0.98},
      paramTable());
}

}  // namespace coverbench::spanning_tree
