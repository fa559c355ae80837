// Shortest collision-free transits on a visibility graph, searched with Boost.Graph.
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <cmath>

#include "coverbench/workspace.hpp"

namespace coverbench {
namespace {

/// Nodes sit this far beyond the exact clearance requirement (more than kPlanningMargin, so a
/// node always passes the planners' own checks).
constexpr double kNodeMargin = 5e-6;
/// Largest angle a node chain turns through per step around a corner.
constexpr double kMaxStep = M_PI / 2.0;

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
  G graph;
};

TransitRouter::TransitRouter(const ClearanceField& field, const ToolParams& tool) : field_(&field), tool_(tool) {}
TransitRouter::~TransitRouter() = default;

bool TransitRouter::isFree(Point a, Point b) const {
  return field_->segmentFree(a, b, tool_.radius(), tool_.clearance, kPlanningMargin);
}

std::size_t TransitRouter::nodeCount() {
  build();
  return graph_->nodes.size();
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

  const std::size_t n = graph_->nodes.size();
  graph_->graph = Graph::G(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (isFree(graph_->nodes[i], graph_->nodes[j]))
        boost::add_edge(i, j, distance(graph_->nodes[i], graph_->nodes[j]), graph_->graph);
}

std::optional<std::vector<Point>> TransitRouter::route(Point a, Point b) {
  if (isFree(a, b)) return std::vector<Point>{a, b};
  build();
  std::optional<std::vector<Point>> result = search(a, b, {});
  if (result || !free_) return result;
  // Fallback: F's own boundary vertices near a and b, in runs along the rings. Consecutive ones
  // are joined by F's edges, which are free, so a walk along F leaves cusps and thin passages
  // that no corner node can see into.
  const double window = std::fmax(4.0 * (tool_.radius() + tool_.clearance), 0.25);
  std::vector<std::vector<Point>> chains;
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
  if (chains.empty()) return result;
  return search(a, b, chains);
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

}  // namespace coverbench
