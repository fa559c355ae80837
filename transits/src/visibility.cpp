// Shortest collision-free transits on a visibility graph, searched with Boost.Graph.
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <tuple>

#include "coverbench/transit_planners.hpp"
#include "coverbench/transit_router.hpp"

namespace coverbench {
namespace {

/// Nodes sit this far beyond the exact clearance requirement (more than kPlanningMargin, so a
/// node always passes the planners' own checks).
constexpr double kNodeMargin = 5e-6;
/// Largest angle a node chain turns through per step around a corner.
constexpr double kMaxStep = M_PI / 2.0;

/// Straight-line distance with a plain square root (std::hypot is several times slower and its
/// overflow care is not needed at wall scale): the A* inner loop's cost.
inline double length(Point a, Point b) {
  const double dx = a.x - b.x, dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

/// Per-thread storage for the A* search's per-node heaps, kept between searches. Capacity beyond
/// kKeepBytes is given back after a search that needed it, so one huge search does not pin memory.
template <class T>
class SearchScratch {
 public:
  void reset() {
    std::size_t bytes = 0;
    for (const std::vector<T>& h : heaps_) bytes += h.capacity() * sizeof(T);
    if (bytes > kKeepBytes) heaps_.clear();
    for (std::size_t i = 0; i < std::min(used_, heaps_.size()); ++i) heaps_[i].clear();
    used_ = 0;
  }
  /// The heap of closing rank r, empty when first asked for (ranks are asked for in order).
  std::vector<T>& heap(std::size_t r) {
    if (r == used_) {
      if (used_ == heaps_.size()) heaps_.emplace_back();
      ++used_;
    }
    return heaps_[r];
  }

 private:
  static constexpr std::size_t kKeepBytes = std::size_t{16} << 20;
  std::vector<std::vector<T>> heaps_;
  std::size_t used_ = 0;
};

Point unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
double angleOf(Point v) { return std::atan2(v.y, v.x); }

/// Nodes on a polyline circumscribing the arc of `radius` around `v`, from direction `n1` to
/// direction `n2` (unit vectors) the short way. Every segment of the chain is tangent to the arc,
/// so the chain stays at least `radius` from `v`.
void cornerNodes(Point v, Point n1, Point n2, double radius, std::vector<Point>& out) {
  const double sweep = std::atan2(cross(n1, n2), dot(n1, n2));
  const int steps = std::max(1, static_cast<int>(std::ceil(std::fabs(sweep) / kMaxStep)));
  const double step = sweep / steps;
  const double a1 = angleOf(n1);
  out.push_back(v + unit(a1) * radius);
  for (int j = 0; j < steps; ++j)
    out.push_back(v + unit(a1 + (j + 0.5) * step) * (radius / std::cos(step / 2.0)));
  out.push_back(v + unit(a1 + sweep) * radius);
}

Point leftNormal(Point d) {
  const double n = norm(d);
  return {-d.y / n, d.x / n};
}

}  // namespace

struct TransitRouter::Graph {
  using G = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                  boost::property<boost::edge_weight_t, double>>;
  std::vector<Point> nodes;
  std::vector<Point> boundary;  ///< every vertex of F's rings, for the last fallback (filled on first use)
  G graph;
  bool linked = false;  ///< whether `graph` holds the edges between all nodes yet
  /// Each checked move between two nodes, kept across queries (a sweep's routes check the same
  /// moves again and again: on a wall of 293 obstacles, 13.3 M checks were of 1.2 M moves). Bits
  /// for both orders of each pair (row i, column j), for up to kMaxMemoNodes nodes; allocated on
  /// first use.
  std::vector<bool> checked, blocked;
  bool isFreeNodes(const TransitRouter& router, std::size_t i, std::size_t j);
};

namespace {
/// Nodes up to which moves between them are remembered (2 x 8 MB of bits at most).
constexpr std::size_t kMaxMemoNodes = 8192;
}  // namespace

bool TransitRouter::Graph::isFreeNodes(const TransitRouter& router, std::size_t i, std::size_t j) {
  const std::size_t n = nodes.size();
  if (n > kMaxMemoNodes) return router.isFree(nodes[i], nodes[j]);
  if (checked.empty()) checked.assign(n * n, false), blocked.assign(n * n, false);
  if (!checked[i * n + j]) {
    // Checked in one order whichever way it is asked (a segment's check may round differently
    // reversed).
    const bool free = router.isFree(nodes[std::min(i, j)], nodes[std::max(i, j)]);
    checked[i * n + j] = checked[j * n + i] = true;
    blocked[i * n + j] = blocked[j * n + i] = !free;
  }
  return !blocked[i * n + j];
}

TransitRouter::TransitRouter(const ClearanceField& field, const ToolParams& tool) : field_(&field), tool_(tool) {}
TransitRouter::~TransitRouter() = default;

bool TransitRouter::isFree(Point a, Point b) const {
  return field_->segmentFree(a, b, tool_.radius(), tool_.clearance, kPlanningMargin);
}

std::size_t TransitRouter::nodeCount() {
  build();
  return graph_->nodes.size();
}

void TransitRouter::link() {
  build();
  if (graph_->linked) return;
  graph_->linked = true;
  const std::size_t n = graph_->nodes.size();
  graph_->graph = Graph::G(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (isFree(graph_->nodes[i], graph_->nodes[j]))
        boost::add_edge(i, j, distance(graph_->nodes[i], graph_->nodes[j]), graph_->graph);
}

std::optional<std::vector<Point>> TransitRouter::localRoute(Point a, Point b) {
  // Search the nodes in a box around a and b; grow the box until the route found is provably the
  // shortest through all nodes: a route that leaves the box is at least as long as the box's
  // shorter side (the ellipse of shorter routes fits in the box's inscribed disk). A box holding
  // every node is the whole graph.
  Box around;
  around.add(a);
  around.add(b);
  const std::vector<Point>& nodes = graph_->nodes;
  bool with_chains = false;  // F's boundary vertices near the ends added as nodes
  for (double grow = std::fmax(1.0, 0.5 * distance(a, b));; grow *= 2.0) {
    Box box = around;
    box.min_x -= grow, box.min_y -= grow, box.max_x += grow, box.max_y += grow;
    auto inBox = [&](Point p) { return p.x >= box.min_x && p.x <= box.max_x && p.y >= box.min_y && p.y <= box.max_y; };
    std::vector<Point> pos{a, b};
    std::vector<std::size_t> node{kNoNode, kNoNode};  // each point's index among the nodes
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (inBox(nodes[i])) pos.push_back(nodes[i]), node.push_back(i);
    // Once the box holds every node, the search is over the whole graph and needs no bound.
    const bool everything = pos.size() == nodes.size() + 2;
    const double bound = everything ? INFINITY : std::fmin(box.width(), box.height());
    const std::size_t corner_nodes = pos.size();
    auto addChains = [&] {
      for (const std::vector<Point>& chain : boundaryChains(a, b))
        for (const Point& p : chain)
          if (inBox(p)) pos.push_back(p), node.push_back(kNoNode);
    };
    if (with_chains) addChains();
    std::optional<std::vector<Point>> found = lazySearch(pos, node, bound);
    if (!found && !with_chains) {
      // An end that sees no node (a cusp of F, a passage barely wider than the tool) gets F's own
      // boundary vertices near the ends as extra nodes, as in the whole-graph fallback.
      auto seesNode = [&](Point p) {
        for (std::size_t i = 2; i < corner_nodes; ++i)
          if (isFree(p, pos[i])) return true;
        return false;
      };
      if (!seesNode(a) || !seesNode(b)) {
        with_chains = true;
        addChains();
        found = lazySearch(pos, node, bound);
      }
    }
    if (found || everything) return found;
  }
}

std::optional<std::vector<Point>> TransitRouter::lazySearch(const std::vector<Point>& pos, const std::vector<std::size_t>& node,
                                                             double bound) const {
  // Searched within growing bounds first: a route no longer than B passes only points p with
  // |a p| + |p b| <= B (an ellipse), and the search within B tries the same moves in the same
  // order as the search within `bound` until a route is found, so it finds the same route when
  // that is no longer than B. Most routes are a little longer than the straight line; a search
  // over every point in the box spent most of its time on moves it would never try.
  const Point a = pos[0], b = pos[1];
  const double d = length(a, b);
  for (double extra = std::fmax(0.5, 0.25 * d);; extra *= 2.0) {
    const double within = d + extra;
    if (!(within < bound)) break;
    // A hair wider than B: a route's summed lengths may round below the straight |a p|.
    const double keep = within * (1.0 + 1e-12) + 1e-12;
    std::vector<Point> near{a, b};
    std::vector<std::size_t> near_node{node[0], node[1]};
    for (std::size_t i = 2; i < pos.size(); ++i)
      if (length(a, pos[i]) + length(pos[i], b) <= keep) near.push_back(pos[i]), near_node.push_back(node[i]);
    if (near.size() == pos.size()) break;  // every point: the search within `bound` follows
    if (auto found = searchWithin(near, near_node, within)) return found;
  }
  return searchWithin(pos, node, bound);
}

std::optional<std::vector<Point>> TransitRouter::searchWithin(const std::vector<Point>& pos, const std::vector<std::size_t>& node,
                                                               double bound) const {
  // A* from pos[0] to pos[1] with lazy edges: a move is checked only when it is the cheapest way
  // left to reach its end. The Euclidean heuristic is consistent, so the first valid arrival at
  // pos[1] is the shortest. Routes longer than `bound` are not searched.
  // Each closed node's moves wait in a heap of their own, and only its cheapest move left stands
  // in the search's heap: moves are tried cheapest first as if every one were pushed, but the
  // search's heap holds one entry per closed node, not one per pair (on a cluttered wall a search
  // closes about a hundred nodes of a thousand and tries one move in fifteen).
  // Moves into one node at one cost are tried fewest hops first, then from the node closed first:
  // of equal routes (through collinear nodes) the one with the fewest points.
  const std::size_t none = pos.size();
  // A move waiting in the search's heap: its start's closing rank `from`, its end v and the
  // hops to v along it.
  struct Move {
    double f, g;
    std::size_t v, hops, from;
    bool operator>(const Move& o) const {
      return std::tie(f, v, hops, from) > std::tie(o.f, o.v, o.hops, o.from);
    }
  };
  // A move not yet tried from one closed node: only its cost and its end (the start, its g and
  // hops are the node's). Within one node's heap, the order by (f, v) is the search heap's order.
  struct Waiting {
    double f;
    std::uint32_t v;
    bool operator>(const Waiting& o) const { return std::tie(f, v) > std::tie(o.f, o.v); }
  };
  // Every closed node keeps a heap of up to pos.size() moves: one allocation per search, reused
  // by this thread's next search (a fresh vector per closed node cost more in page faults than
  // the search itself on walls with thousands of nodes).
  thread_local SearchScratch<Waiting> scratch;
  scratch.reset();
  const Point b = pos[1];
  std::vector<double> to_b(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) to_b[i] = length(pos[i], b);
  std::vector<bool> closed(pos.size(), false);
  std::vector<std::size_t> pred(pos.size(), none);
  struct Closed {
    std::size_t v, hops;
    double g;
  };
  std::vector<Closed> order;  // closed nodes, in closing order (their rank)
  std::priority_queue<Move, std::vector<Move>, std::greater<>> open;
  // The next move worth trying (into a node still open) from the node of closing rank r.
  auto offerNext = [&](std::size_t r) {
    std::vector<Waiting>& heap = scratch.heap(r);
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), std::greater<>{});
      const Waiting w = heap.back();
      heap.pop_back();
      if (!closed[w.v]) {
        const Closed& u = order[r];
        open.push({w.f, u.g + length(pos[u.v], pos[w.v]), w.v, u.hops + 1, r});
        return;
      }
    }
  };
  auto moveFree = [&](std::size_t u, std::size_t v) {
    return node[u] != kNoNode && node[v] != kNoNode ? graph_->isFreeNodes(*this, node[u], node[v]) : isFree(pos[u], pos[v]);
  };
  open.push({to_b[0], 0.0, 0, 0, none});
  while (!open.empty()) {
    const Move m = open.top();
    open.pop();
    if (m.from != none) offerNext(m.from);
    if (m.f > bound) break;
    if (closed[m.v]) continue;
    if (m.from != none && !moveFree(order[m.from].v, m.v)) continue;
    closed[m.v] = true;
    pred[m.v] = m.from == none ? none : order[m.from].v;
    if (m.v == 1) {
      std::vector<Point> points;
      for (std::size_t v = 1; v != none; v = pred[v]) points.push_back(pos[v]);
      std::reverse(points.begin(), points.end());
      return points;
    }
    const std::size_t rank = order.size();
    order.push_back({m.v, m.hops, m.g});
    std::vector<Waiting>& out = scratch.heap(rank);
    // A move an earlier query found blocked would be tried and fail: it is not offered.
    const std::vector<bool>& blocked = graph_->blocked;
    const bool memo = node[m.v] != kNoNode && !blocked.empty();
    const std::size_t row = memo ? node[m.v] * graph_->nodes.size() : 0;
    for (std::size_t w = 1; w < pos.size(); ++w) {
      if (closed[w] || (memo && node[w] != kNoNode && blocked[row + node[w]])) continue;
      const double f = m.g + length(pos[m.v], pos[w]) + to_b[w];
      if (f <= bound) out.push_back({f, static_cast<std::uint32_t>(w)});
    }
    std::make_heap(out.begin(), out.end(), std::greater<>{});
    offerNext(rank);
  }
  return std::nullopt;
}

void TransitRouter::build() {
  if (graph_) return;
  graph_ = std::make_unique<Graph>();
  const Wall& wall = field_->wall();
  const double r = tool_.radius();
  const double around_obstacle = r + tool_.clearance + kNodeMargin;
  std::vector<Point> candidates;

  // Convex corners of obstacles (counter-clockwise polygons turn left there): F's boundary is an
  // arc around them, on the outward side.
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle) {
      const int n = 12;
      const double rr = (o.radius + around_obstacle) / std::cos(M_PI / n);
      for (int i = 0; i < n; ++i) candidates.push_back(o.center + unit(2.0 * M_PI * (i + 0.5) / n) * rr);
      continue;
    }
    const Ring& p = o.polygon;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point prev = p[(i + n - 1) % n], v = p[i], next = p[(i + 1) % n];
      if (cross(v - prev, next - v) <= 0.0) continue;
      // Outward normals of a counter-clockwise polygon point to the right of its edges.
      cornerNodes(v, leftNormal(v - prev) * -1.0, leftNormal(next - v) * -1.0, around_obstacle, candidates);
    }
  }
  // Reflex corners of the boundary (counter-clockwise, turning right): F's boundary is an arc
  // around them on the inward side.
  {
    const Ring& b = wall.boundary;
    const std::size_t n = b.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point prev = b[(i + n - 1) % n], v = b[i], next = b[(i + 1) % n];
      if (cross(v - prev, next - v) >= 0.0) continue;
      cornerNodes(v, leftNormal(v - prev), leftNormal(next - v), r + kNodeMargin, candidates);
    }
  }
  for (const Point& c : candidates)
    if (isFree(c, c)) graph_->nodes.push_back(c);
}

std::vector<std::vector<Point>> TransitRouter::boundaryChains(Point a, Point b) const {
  std::vector<std::vector<Point>> chains;
  if (!free_) return chains;
  const double window = std::fmax(4.0 * (tool_.radius() + tool_.clearance), 0.25);
  for (const PolygonWithHoles& poly : *free_) {
    std::vector<const Ring*> rings{&poly.outer};
    for (const Ring& h : poly.holes) rings.push_back(&h);
    for (const Ring* ring : rings) {
      std::vector<Point> run;
      for (const Point& p : *ring) {
        if (distance(p, a) <= window || distance(p, b) <= window) {
          run.push_back(p);
        } else if (!run.empty()) {
          chains.push_back(std::move(run));
          run.clear();
        }
      }
      if (!run.empty()) chains.push_back(std::move(run));
    }
  }
  return chains;
}

std::optional<std::vector<Point>> TransitRouter::route(Point a, Point b) {
  if (isFree(a, b)) return std::vector<Point>{a, b};
  build();
  // The local search ends with every node in its box, so the corner nodes alone have no route.
  if (auto local = localRoute(a, b)) return local;
  // Fallback: F's own boundary vertices near a and b, in runs along the rings. Consecutive ones
  // are joined by F's edges, which are free, so a walk along F leaves cusps and thin passages
  // that no corner node can see into.
  const std::vector<std::vector<Point>> chains = boundaryChains(a, b);
  if (!chains.empty()) {
    link();
    if (auto near = search(a, b, chains)) return near;
  }
  // Last: every vertex of F's boundary as a node. F's edges are free, so a and b in one component
  // of F are joined through them; what the corner nodes miss (a passage barely wider than the
  // tool far from both ends, whose nodes fall into a neighbouring obstacle's clearance) is found.
  return wholeBoundaryRoute(a, b);
}

std::optional<std::vector<Point>> TransitRouter::wholeBoundaryRoute(Point a, Point b) {
  if (!free_) return std::nullopt;
  // Only within one component of F: a pair in two (or outside F) has no route, and proving it by
  // searching every vertex of a's component took seconds per query (replanning asks many).
  // An end on F's boundary, outside its conservative polygon by the margin, belongs to the
  // component whose boundary is nearest (within the tool's radius).
  auto component = [&](Point p) {
    long nearest = -1;
    double best = tool_.radius();
    for (std::size_t i = 0; i < free_->size(); ++i) {
      const PolygonWithHoles& poly = (*free_)[i];
      if (pointInPolygon(poly, p)) return static_cast<long>(i);
      double d = distanceSegmentRingEdges(p, p, poly.outer);
      for (const Ring& h : poly.holes) d = std::fmin(d, distanceSegmentRingEdges(p, p, h));
      if (d < best) best = d, nearest = static_cast<long>(i);
    }
    return nearest;
  };
  const long ca = component(a);
  if (ca < 0 || component(b) != ca) return std::nullopt;
  Graph& g = *graph_;
  if (g.boundary.empty())
    for (const PolygonWithHoles& poly : *free_) {
      g.boundary.insert(g.boundary.end(), poly.outer.begin(), poly.outer.end());
      for (const Ring& h : poly.holes) g.boundary.insert(g.boundary.end(), h.begin(), h.end());
    }
  std::vector<Point> pos{a, b};
  pos.reserve(2 + g.nodes.size() + g.boundary.size());
  pos.insert(pos.end(), g.nodes.begin(), g.nodes.end());
  pos.insert(pos.end(), g.boundary.begin(), g.boundary.end());
  std::vector<std::size_t> node(pos.size(), kNoNode);
  for (std::size_t i = 0; i < g.nodes.size(); ++i) node[2 + i] = i;
  return lazySearch(pos, node, INFINITY);
}

std::optional<std::vector<Point>> TransitRouter::search(Point a, Point b, const std::vector<std::vector<Point>>& chains) {
  Graph& g = *graph_;
  const std::size_t n = g.nodes.size();
  // Temporary vertices after the permanent nodes: a, b, then the chain points.
  std::vector<Point> pos = g.nodes;
  pos.push_back(a);
  pos.push_back(b);
  for (const auto& chain : chains) pos.insert(pos.end(), chain.begin(), chain.end());
  const std::size_t va = n, vb = n + 1;
  for (std::size_t v = n; v < pos.size(); ++v) boost::add_vertex(g.graph);
  auto link = [&](std::size_t i, std::size_t j) {
    if (isFree(pos[i], pos[j])) boost::add_edge(i, j, distance(pos[i], pos[j]), g.graph);
  };
  for (std::size_t i = 0; i < n; ++i) link(va, i), link(i, vb);
  std::size_t at = n + 2;
  for (const auto& chain : chains) {
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const std::size_t v = at + k;
      if (k > 0) link(v - 1, v);
      link(va, v);
      link(v, vb);
      for (std::size_t i = 0; i < n; ++i) link(v, i);
    }
    at += chain.size();
  }
  std::optional<std::vector<Point>> result;
  std::vector<std::size_t> pred(pos.size());
  std::vector<double> dist(pos.size());
  boost::dijkstra_shortest_paths(
      g.graph, va,
      boost::predecessor_map(boost::make_iterator_property_map(pred.begin(), boost::get(boost::vertex_index, g.graph)))
          .distance_map(boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, g.graph))));
  if (pred[vb] != vb) {
    std::vector<Point> points{b};
    for (std::size_t v = pred[vb]; v != va; v = pred[v]) points.push_back(pos[v]);
    points.push_back(a);
    std::reverse(points.begin(), points.end());
    result = std::move(points);
  }
  for (std::size_t v = pos.size(); v-- > n;) {  // last added first: indices below stay valid
    boost::clear_vertex(v, g.graph);
    boost::remove_vertex(v, g.graph);
  }
  return result;
}

const std::vector<TransitPlannerInfo>& transitPlanners() {
  static const std::vector<TransitPlannerInfo> planners = {
      {"visibility", "the shortest path on a visibility graph whose nodes circumscribe F's rounded corners (lazy A*)",
       "Lozano-Perez & Wesley, An algorithm for planning collision-free paths among polyhedral obstacles, CACM 1979", false},
      {"rrtstar", "OMPL's RRT*: a tree of random samples, rewired towards shorter paths",
       "Karaman & Frazzoli, Sampling-based algorithms for optimal motion planning, IJRR 2011", true},
      {"prmstar", "OMPL's PRM*: a roadmap of random samples, each joined to its k-nearest (k growing with log n); the shortest path through it",
       "Karaman & Frazzoli, IJRR 2011", true},
      {"bitstar", "OMPL's BIT*: batches of samples searched in order of an informed cost heuristic",
       "Gammell, Srinivasa & Barfoot, Batch Informed Trees, ICRA 2015", true},
      {"informed-rrtstar", "OMPL's Informed RRT*: RRT* sampling the ellipse that can still shorten the path once one is found",
       "Gammell, Srinivasa & Barfoot, Informed RRT*, IROS 2014", true},
  };
  return planners;
}

const TransitPlannerInfo* findTransitPlanner(const std::string& name) {
  for (const TransitPlannerInfo& p : transitPlanners())
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace coverbench
