#include "cell_ordering.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/graph/depth_first_search.hpp>
#include <boost/graph/metric_tsp_approx.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <stdexcept>

namespace coverbench::decomposition {
namespace {

using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                    boost::property<boost::edge_weight_t, double>>;

/// How many nearest cells 2-opt tries to join each cell to, and Or-opt to put it beside.
constexpr std::size_t kCandidates = 10;
constexpr std::size_t kOrOptCandidates = 5;
/// Upper bounds on 2-opt sweeps over the sequence (each O(n * kCandidates)) and on rounds of
/// 2-opt followed by Or-opt: deterministic limits, so the order never depends on timing.
constexpr int kMaxSweeps = 50;
constexpr int kMaxRounds = 3;

/// Straight-line distance (plain square root: std::hypot's overflow care is not needed here).
inline double length(Point a, Point b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

/// The cost of the straight move from one visit's exit to the next visit's entry.
double step(const std::vector<CellEnds>& cells, const TourCost& cost, const Visit& a, const Visit& b) {
  return cost.move(length(cells[a.cell].exit[a.orientation], cells[b.cell].entry[b.orientation]));
}

/// The move from the start to a first visit's entry (0 without a start).
double head(const std::vector<CellEnds>& cells, const TourCost& cost, const Visit& v) {
  return cost.start ? cost.move(length(*cost.start, cells[v.cell].entry[v.orientation])) : 0.0;
}

/// The move from a last visit's exit to the end (0 without an end).
double tail(const std::vector<CellEnds>& cells, const TourCost& cost, const Visit& v) {
  return cost.end ? cost.move(length(cells[v.cell].exit[v.orientation], *cost.end)) : 0.0;
}

/// The visit whose entry is nearest to `p` (the first such, in cell and orientation order).
Visit nearestEntry(const std::vector<CellEnds>& cells, Point p) {
  Visit best{0, 0};
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int o = 0; o < 4; ++o)
      if (length(p, cells[c].entry[o]) < length(p, cells[best.cell].entry[best.orientation])) best = {c, o};
  return best;
}

Visit reversed(const std::vector<CellEnds>& cells, const Visit& v) {
  return {v.cell, cells[v.cell].reverse[v.orientation]};
}

Graph cellGraph(const std::vector<CellEnds>& cells, const std::vector<CellLink>& links) {
  const std::size_t n = cells.size();
  auto nearestEnds = [&](std::size_t a, std::size_t b) {
    double best = INFINITY;
    for (const Point& p : cells[a].entry)
      for (const Point& q : cells[b].entry) best = std::min(best, distance(p, q));
    return best;
  };
  std::map<std::pair<std::size_t, std::size_t>, double> weights;  // ordered: edges go in deterministically
  for (const CellLink& l : links)
    if (l.a != l.b) weights.emplace(std::minmax(l.a, l.b), 0.0);
  Graph g(n);
  for (const auto& [key, w] : weights) boost::add_edge(key.first, key.second, nearestEnds(key.first, key.second), g);
  // Join separate parts: each part (numbered in vertex order) to the nearest cell of an earlier one.
  std::vector<int> part(n);
  const int parts = n == 0 ? 0 : boost::connected_components(g, part.data());
  for (int p = 1; p < parts; ++p) {
    std::size_t best_u = 0, best_v = 0;
    double best = INFINITY;
    for (std::size_t u = 0; u < n; ++u) {
      if (part[u] != p) continue;
      for (std::size_t v = 0; v < n; ++v)
        if (part[v] < p && distance(cells[u].centre, cells[v].centre) < best)
          best = distance(cells[u].centre, cells[v].centre), best_u = u, best_v = v;
    }
    boost::add_edge(best_u, best_v, nearestEnds(best_u, best_v), g);
  }
  return g;
}

/// Picks every cell's orientation for a fixed sequence (dynamic programming over 4 states).
Ordering orient(const std::vector<std::size_t>& sequence, const std::vector<CellEnds>& cells, const TourCost& cost) {
  Ordering out;
  const std::size_t n = sequence.size();
  if (n == 0) return out;
  std::vector<std::array<int, 4>> from(n);
  std::array<double, 4> total{};
  for (int o = 0; o < 4; ++o) total[o] = head(cells, cost, {sequence[0], o});
  for (std::size_t k = 1; k < n; ++k) {
    const CellEnds& p = cells[sequence[k - 1]];
    const CellEnds& c = cells[sequence[k]];
    std::array<double, 4> next{};
    for (int o = 0; o < 4; ++o) {
      next[o] = INFINITY;
      for (int q = 0; q < 4; ++q) {
        const double v = total[q] + cost.move(length(p.exit[q], c.entry[o]));
        if (v < next[o]) next[o] = v, from[k][o] = q;
      }
    }
    total = next;
  }
  for (int o = 0; o < 4; ++o) total[o] += tail(cells, cost, {sequence[n - 1], o});
  int o = static_cast<int>(std::min_element(total.begin(), total.end()) - total.begin());
  out.estimated_cost = total[o];
  out.visits.resize(n);
  for (std::size_t k = n; k-- > 0;) {
    out.visits[k] = {sequence[k], o};
    if (k > 0) o = from[k][o];
  }
  return out;
}

std::vector<std::size_t> depthFirstOrder(const Graph& g, std::size_t root) {
  struct Recorder : boost::default_dfs_visitor {
    std::vector<std::size_t>* order;
    void discover_vertex(Graph::vertex_descriptor v, const Graph&) const { order->push_back(v); }
  };
  std::vector<std::size_t> order;
  if (boost::num_vertices(g) == 0) return order;
  Recorder recorder;
  recorder.order = &order;
  boost::depth_first_search(g, boost::visitor(recorder).root_vertex(root));
  return order;
}

/// Boost's MST-preorder tour from cell 0, opened at its longest step.
std::vector<std::size_t> approximateTour(const Graph& g, const std::vector<CellEnds>& cells) {
  std::vector<Graph::vertex_descriptor> cycle;
  boost::metric_tsp_approx_tour_from_vertex(g, 0, std::back_inserter(cycle));
  cycle.pop_back();  // the tour returns to its start
  const std::size_t n = cycle.size();
  auto step = [&](std::size_t i) { return distance(cells[cycle[i]].centre, cells[cycle[(i + 1) % n]].centre); };
  std::size_t cut = n - 1;
  for (std::size_t i = 0; i < n; ++i)
    if (step(i) > step(cut)) cut = i;
  std::vector<std::size_t> path;
  for (std::size_t k = 1; k <= n; ++k) path.push_back(cycle[(cut + k) % n]);
  return path;
}

/// The kCandidates cells with the nearest centres, for every cell (scan outward in x order).
std::vector<std::vector<std::size_t>> nearestCells(const std::vector<CellEnds>& cells) {
  const std::size_t n = cells.size();
  // Scan along the longer extent of the centres (fewer cells share a coordinate range there).
  Box extent;
  for (const CellEnds& c : cells) extent.add(c.centre);
  const bool along_x = extent.width() >= extent.height();
  auto key = [&](std::size_t i) { return along_x ? cells[i].centre.x : cells[i].centre.y; };
  std::vector<std::size_t> by_x(n);
  for (std::size_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
  std::vector<std::size_t> rank(n);
  for (std::size_t r = 0; r < n; ++r) rank[by_x[r]] = r;
  std::vector<std::vector<std::size_t>> out(n);
  std::vector<std::pair<double, std::size_t>> found;
  for (std::size_t i = 0; i < n; ++i) {
    found.clear();
    const Point c = cells[i].centre;
    auto kth = [&] { return found.size() < kCandidates ? INFINITY : found.back().first; };
    auto offer = [&](std::size_t j) {
      const double d = length(c, cells[j].centre);
      if (d >= kth()) return;
      found.insert(std::upper_bound(found.begin(), found.end(), std::make_pair(d, j)), {d, j});
      if (found.size() > kCandidates) found.pop_back();
    };
    for (std::size_t r = rank[i] + 1; r < n && key(by_x[r]) - key(i) < kth(); ++r) offer(by_x[r]);
    for (std::size_t r = rank[i]; r-- > 0 && key(i) - key(by_x[r]) < kth();) offer(by_x[r]);
    for (const auto& f : found) out[i].push_back(f.second);
  }
  return out;
}

/// 2-opt over a sequence of visits: reversing a stretch covers each of its cells backwards, so
/// the moves inside the stretch keep their lengths and only the two joins change. Moves join a
/// cell to one of its nearest cells; a stretch of one cell may take any orientation.
bool twoOpt(std::vector<Visit>& t, const std::vector<CellEnds>& cells, const TourCost& cost,
            const std::vector<std::vector<std::size_t>>& nearest, const std::function<bool()>& keep_going) {
  const std::size_t n = t.size();
  if (n < 2) return false;
  std::vector<std::size_t> pos(cells.size());
  for (std::size_t k = 0; k < n; ++k) pos[t[k].cell] = k;
  auto reverse = [&](std::size_t i, std::size_t j) {  // t[i..j]
    std::reverse(t.begin() + static_cast<long>(i), t.begin() + static_cast<long>(j) + 1);
    for (std::size_t k = i; k <= j; ++k) {
      t[k] = reversed(cells, t[k]);
      pos[t[k].cell] = k;
    }
  };
  // Reversing t[i..j] replaces the joins (t[i-1], t[i]) and (t[j], t[j+1]) (where they exist).
  auto gain = [&](std::size_t i, std::size_t j) {
    const Visit first = reversed(cells, t[j]), last = reversed(cells, t[i]);
    double before = 0.0, after = 0.0;
    if (i > 0) before += step(cells, cost, t[i - 1], t[i]), after += step(cells, cost, t[i - 1], first);
    else before += head(cells, cost, t[i]), after += head(cells, cost, first);
    if (j + 1 < n) before += step(cells, cost, t[j], t[j + 1]), after += step(cells, cost, last, t[j + 1]);
    else before += tail(cells, cost, t[j]), after += tail(cells, cost, last);
    return before - after;
  };
  auto around = [&](std::size_t k, const Visit& v) {
    double c = 0.0;
    c += k > 0 ? step(cells, cost, t[k - 1], v) : head(cells, cost, v);
    c += k + 1 < n ? step(cells, cost, v, t[k + 1]) : tail(cells, cost, v);
    return c;
  };
  // Don't-look bits: a cell is tried again only after a move changed one of its joins.
  std::vector<char> look(cells.size(), 1);
  auto touch = [&](long i) {
    if (i >= 0 && i < static_cast<long>(n)) look[t[static_cast<std::size_t>(i)].cell] = 1;
  };
  auto touchAround = [&](std::size_t i, std::size_t j) {  // the joins of t[i..j] with the rest changed
    touch(static_cast<long>(i) - 1), touch(static_cast<long>(i)), touch(static_cast<long>(j)), touch(static_cast<long>(j) + 1);
  };
  // With a start (an end), the cells whose entries (exits) are nearest to it: reversing the
  // stretch from the first visit to one of them (from one of them to the last) makes it the first
  // (the last).
  auto nearestTo = [&](const std::optional<Point>& point, bool entries) {
    std::vector<std::pair<double, std::size_t>> by;
    if (!point) return by;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double d = INFINITY;
      for (int o = 0; o < 4; ++o) d = std::min(d, length(*point, entries ? cells[c].entry[o] : cells[c].exit[o]));
      by.emplace_back(d, c);
    }
    const std::size_t keep = std::min(kCandidates, by.size());
    std::partial_sort(by.begin(), by.begin() + static_cast<long>(keep), by.end());
    by.resize(keep);
    return by;
  };
  const auto near_start = nearestTo(cost.start, true), near_end = nearestTo(cost.end, false);
  bool any = false;
  for (int sweep = 0; sweep < kMaxSweeps && keep_going(); ++sweep) {
    bool improved = false;
    for (const auto& [d, c] : near_start) {
      const std::size_t j = pos[c];
      if (j > 0 && gain(0, j) > 1e-9) reverse(0, j), improved = true, touchAround(0, j);
    }
    for (const auto& [d, c] : near_end) {
      const std::size_t j = pos[c];
      if (j + 1 < n && gain(j, n - 1) > 1e-9) reverse(j, n - 1), improved = true, touchAround(j, n - 1);
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (!look[t[k].cell]) continue;
      look[t[k].cell] = 0;
      // The best orientation of t[k] between its neighbours.
      for (int o = 0; o < 4; ++o) {
        const Visit v{t[k].cell, o};
        if (around(k, v) < around(k, t[k]) - 1e-9) t[k] = v, improved = true, touchAround(k, k);
      }
      // Join t[k] to a near cell c: after t[k] (reverse t[k+1..pos c]) or before it (reverse
      // t[pos c..k-1]).
      for (std::size_t c : nearest[t[k].cell]) {
        const std::size_t j = pos[c];
        if (j > k + 1 && gain(k + 1, j) > 1e-9) {
          reverse(k + 1, j), improved = true, touchAround(k + 1, j);
        } else if (j + 1 < k && gain(j, k - 1) > 1e-9) {
          reverse(j, k - 1), improved = true, touchAround(j, k - 1);
        }
      }
    }
    any = any || improved;
    if (!improved) break;
  }
  return any;
}

/// Or-opt for single cells: take a cell out and put it back (in any orientation) between two
/// consecutive cells one of which is among its nearest, where that shortens the sequence.
bool orOpt(std::vector<Visit>& t, const std::vector<CellEnds>& cells, const TourCost& cost,
           const std::vector<std::vector<std::size_t>>& nearest) {
  const std::size_t n = t.size();
  if (n < 3) return false;
  bool improved = false;
  std::vector<std::size_t> pos(cells.size());
  for (std::size_t k = 0; k < n; ++k) pos[t[k].cell] = k;
  for (std::size_t cell = 0; cell < cells.size(); ++cell) {
    const std::size_t k = pos[cell];
    // u is t without t[k]; gap g puts the cell before u[g] (g == n - 1: at the end).
    auto u = [&](std::size_t i) -> const Visit& { return t[i < k ? i : i + 1]; };
    double saved = 0.0;
    saved += k > 0 ? step(cells, cost, t[k - 1], t[k]) : head(cells, cost, t[k]);
    saved += k + 1 < n ? step(cells, cost, t[k], t[k + 1]) : tail(cells, cost, t[k]);
    if (k > 0 && k + 1 < n) saved -= step(cells, cost, t[k - 1], t[k + 1]);
    else saved -= k == 0 ? head(cells, cost, t[1]) : tail(cells, cost, t[n - 2]);
    double best = saved - 1e-9;
    std::size_t best_gap = n;
    int best_orientation = 0;
    for (std::size_t m = 0; m < std::min(kOrOptCandidates, nearest[cell].size()); ++m) {
      const std::size_t near = nearest[cell][m];
      const std::size_t j = pos[near] < k ? pos[near] : pos[near] - 1;
      for (std::size_t g : {j, j + 1}) {
        if (g == k) continue;  // where it already is
        for (int o = 0; o < 4; ++o) {
          const Visit v{cell, o};
          double added = 0.0;
          added += g > 0 ? step(cells, cost, u(g - 1), v) : head(cells, cost, v);
          added += g < n - 1 ? step(cells, cost, v, u(g)) : tail(cells, cost, v);
          if (g > 0 && g < n - 1) added -= step(cells, cost, u(g - 1), u(g));
          else added -= g == 0 ? head(cells, cost, u(0)) : tail(cells, cost, u(n - 2));
          if (added < best) best = added, best_gap = g, best_orientation = o;
        }
      }
    }
    if (best_gap == n) continue;
    t.erase(t.begin() + static_cast<long>(k));
    t.insert(t.begin() + static_cast<long>(best_gap), Visit{cell, best_orientation});
    for (std::size_t q = std::min(k, best_gap); q <= std::max(k, best_gap); ++q) pos[t[q].cell] = q;
    improved = true;
  }
  return improved;
}

void improve(std::vector<Visit>& t, const std::vector<CellEnds>& cells, const TourCost& cost,
             const std::vector<std::vector<std::size_t>>& nearest, const std::function<bool()>& keep_going) {
  for (int round = 0; round < kMaxRounds && keep_going(); ++round) {
    twoOpt(t, cells, cost, nearest, keep_going);
    if (!orOpt(t, cells, cost, nearest)) break;
  }
}

/// Orientations for a sequence: each cell entered at the corner nearest the previous one's exit.
std::vector<Visit> oriented(const std::vector<std::size_t>& sequence, const std::vector<CellEnds>& cells, const TourCost& cost) {
  std::vector<Visit> visits;
  for (std::size_t cell : sequence) {
    Visit v{cell, 0};
    auto enter = [&](const Visit& w) { return visits.empty() ? head(cells, cost, w) : step(cells, cost, visits.back(), w); };
    for (int o = 1; o < 4; ++o)
      if (enter({cell, o}) < enter(v)) v.orientation = o;
    visits.push_back(v);
  }
  return visits;
}

std::vector<std::size_t> cellsOf(const std::vector<Visit>& visits) {
  std::vector<std::size_t> out;
  for (const Visit& v : visits) out.push_back(v.cell);
  return out;
}

Ordering greedyOrder(const std::vector<CellEnds>& cells, const TourCost& cost) {
  // From each exit, the nearest entry of an unvisited cell (also the cheapest: every MoveCost
  // grows with the length). The cells' entries are bucketed in a grid; rings of buckets are
  // searched outward until no nearer entry can remain.
  Ordering out;
  const std::size_t n = cells.size();
  Box extent;
  for (const CellEnds& c : cells)
    for (const Point& p : c.entry) extent.add(p);
  const double size = std::max({extent.width(), extent.height(), 1e-9});
  const double step = std::max(size / 256.0, std::sqrt(std::max(extent.width() * extent.height(), 1e-18) / static_cast<double>(n)));
  const long nx = static_cast<long>(extent.width() / step) + 1, ny = static_cast<long>(extent.height() / step) + 1;
  std::vector<std::vector<std::size_t>> buckets(static_cast<std::size_t>(nx * ny));
  auto column = [&](double x) { return std::clamp(static_cast<long>((x - extent.min_x) / step), 0L, nx - 1); };
  auto row = [&](double y) { return std::clamp(static_cast<long>((y - extent.min_y) / step), 0L, ny - 1); };
  for (std::size_t c = 0; c < n; ++c)
    for (const Point& p : cells[c].entry) {
      auto& bucket = buckets[static_cast<std::size_t>(row(p.y) * nx + column(p.x))];
      if (bucket.empty() || bucket.back() != c) bucket.push_back(c);
    }
  std::vector<bool> done(n, false);
  Visit cur = cost.start ? nearestEntry(cells, *cost.start) : Visit{0, 0};
  done[cur.cell] = true;
  out.visits.push_back(cur);
  out.estimated_cost += head(cells, cost, cur);
  for (std::size_t k = 1; k < n; ++k) {
    const Point here = cells[cur.cell].exit[cur.orientation];
    double best = INFINITY;  // squared
    Visit next{n, 0};
    const long cx = column(here.x), cy = row(here.y);
    for (long ring = 0;; ++ring) {
      // Entries in ring r are at least (r - 1) * step away (here may lie outside the grid box).
      const double reach = std::max(0.0, static_cast<double>(ring - 1)) * step;
      if (next.cell < n && reach * reach > best) break;
      if (cx - ring < 0 && cy - ring < 0 && cx + ring >= nx && cy + ring >= ny) break;
      for (long y = cy - ring; y <= cy + ring; ++y) {
        if (y < 0 || y >= ny) continue;
        const bool edge_row = y == cy - ring || y == cy + ring;
        for (long x = cx - ring; x <= cx + ring; x += edge_row ? 1 : 2 * ring) {
          if (x >= 0 && x < nx)
            for (std::size_t c : buckets[static_cast<std::size_t>(y * nx + x)]) {
              if (done[c]) continue;
              for (int o = 0; o < 4; ++o) {
                const double dx = here.x - cells[c].entry[o].x, dy = here.y - cells[c].entry[o].y;
                const double v = dx * dx + dy * dy;
                if (v < best || (v == best && (c < next.cell || (c == next.cell && o < next.orientation)))) best = v, next = {c, o};
              }
            }
          if (ring == 0) break;
        }
      }
    }
    out.estimated_cost += cost.move(std::sqrt(best));
    done[next.cell] = true;
    out.visits.push_back(next);
    cur = next;
  }
  out.estimated_cost += tail(cells, cost, cur);
  return out;
}

}  // namespace

// Not inlined: the orderings' hot loop (step) calls it only for the objective `time`, and inlined
// it made that loop 2 % dearer for every objective (the cost gate's decomposition cases).
[[gnu::noinline]] double MoveCost::timed(double length) const {
  // A move between two passes: a run between two quarter turns.
  return straightRunTime(length, *clock) + 2.0 * (clock->turn_cost_s + rotationTime(M_PI / 2.0, *clock));
}

CellEnds alternatingEnds(const PassEnds& front, const PassEnds& back, std::size_t count, Point centre) {
  CellEnds ends;
  const std::size_t last = count - 1;
  for (int o = 0; o < 4; ++o) {
    const bool leftward = (o & 1) != 0, first_down = (o & 2) != 0;
    const PassEnds& a = leftward ? back : front;
    const PassEnds& b = leftward ? front : back;
    const bool last_up = (last % 2 == 0) == !first_down;
    ends.entry[o] = first_down ? a.second : a.first;
    ends.exit[o] = last_up ? b.second : b.first;
    // Backwards: from the other end, first pass the last one reversed.
    ends.reverse[o] = (leftward ? 0 : 1) | (last_up ? 2 : 0);
  }
  ends.centre = centre;
  return ends;
}

Ordering orderCells(const std::vector<CellEnds>& cells, const std::vector<CellLink>& links, Order order,
                    const std::function<bool()>& keep_going, const TourCost& cost) {
  if (cells.empty()) return {};
  if (order == Order::Greedy) return greedyOrder(cells, cost);
  const Graph g = cellGraph(cells, links);
  // Depth-first from the cell entered nearest the start (cell 0 without one).
  std::vector<std::size_t> dfs = depthFirstOrder(g, cost.start ? nearestEntry(cells, *cost.start).cell : 0);
  if (order == Order::Dfs) return orient(dfs, cells, cost);
  // Local search from two starts: the MST-preorder tour and the greedy order.
  const auto nearest = nearestCells(cells);
  std::vector<std::vector<Visit>> starts{oriented(approximateTour(g, cells), cells, cost), greedyOrder(cells, cost).visits};
  Ordering best;
  best.estimated_cost = INFINITY;
  for (std::vector<Visit>& visits : starts) {
    improve(visits, cells, cost, nearest, keep_going);
    Ordering o = orient(cellsOf(visits), cells, cost);
    if (o.estimated_cost < best.estimated_cost) best = std::move(o);
  }
  return best;
}

}  // namespace coverbench::decomposition
