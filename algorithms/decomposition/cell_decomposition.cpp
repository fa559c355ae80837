#include "cell_decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace coverbench::decomposition {

double Edge::yAt(double x) const {
  if (x <= left.x) return left.y;
  if (x >= right.x) return right.y;
  return left.y + (x - left.x) / (right.x - left.x) * (right.y - left.y);
}

double Slice::area() const {
  const double h0 = ceiling.yAt(x0) - floor.yAt(x0), h1 = ceiling.yAt(x1) - floor.yAt(x1);
  return (x1 - x0) * (h0 + h1) / 2.0;
}

double Cell::area() const {
  double a = 0.0;
  for (const Slice& s : slices) a += s.area();
  return a;
}

Span Cell::spanAt(double x) const {
  // The first slice whose right end is at or past x, and the next one when x is their boundary.
  auto it = std::lower_bound(slices.begin(), slices.end(), x, [](const Slice& s, double v) { return s.x1 < v; });
  if (it == slices.end()) --it;
  Span span{it->floor.yAt(x), it->ceiling.yAt(x)};
  if (std::next(it) != slices.end() && std::next(it)->x0 <= x) {
    span.bottom = std::min(span.bottom, std::next(it)->floor.yAt(x));
    span.top = std::max(span.top, std::next(it)->ceiling.yAt(x));
  }
  return span;
}

std::vector<Point> Cell::boundaryWalk(double a, double b, bool ceiling) const {
  if (a > b) {
    std::vector<Point> walk = boundaryWalk(b, a, ceiling);
    std::reverse(walk.begin(), walk.end());
    return walk;
  }
  auto side = [&](const Slice& s, double x) { return ceiling ? s.ceiling.yAt(x) : s.floor.yAt(x); };
  auto end = [&](double x) {
    const Span span = spanAt(x);
    return Point{x, ceiling ? span.top : span.bottom};
  };
  std::vector<Point> walk{end(a)};
  auto push = [&](Point p) {
    if (!(walk.back() == p)) walk.push_back(p);
  };
  for (std::size_t i = 0; i + 1 < slices.size(); ++i) {
    const double x = slices[i].x1;
    if (x < a || x > b) continue;
    // The same edge on both sides: a slab boundary some other vertex made, not a bend here.
    const Edge& e0 = ceiling ? slices[i].ceiling : slices[i].floor;
    const Edge& e1 = ceiling ? slices[i + 1].ceiling : slices[i + 1].floor;
    if (e0.left == e1.left && e0.right == e1.right) continue;
    // Arrive along the left slice (unless the walk starts here), leave along the right one.
    if (x > a) push({x, side(slices[i], x)});
    if (x < b) push({x, side(slices[i + 1], x)});
  }
  push(end(b));
  return walk;
}

namespace {

/// One interval of one slab: indices of its floor and ceiling edges, and its cell.
struct Interval {
  std::size_t floor = 0, ceiling = 0;
  std::size_t cell = 0;
  std::size_t left_links = 0, right_links = 0;
};

struct Link {
  std::size_t left = 0, right = 0;  ///< interval indices in slab k and slab k + 1
  double y0 = 0.0, y1 = 0.0;
};

/// Whether edge `b` continues edge `a` (a ends where b starts) turning by less than kCornerTurnDeg:
/// a vertex of an arc's chords, not a corner.
bool smoothJoin(const Edge& a, const Edge& b) {
  if (!(a.right == b.left)) return false;
  const Point da = a.right - a.left, db = b.right - b.left;
  return dot(da, db) > std::cos(kCornerTurnDeg * M_PI / 180.0) * norm(da) * norm(db);
}

}  // namespace

Decomposition decompose(const PolygonWithHoles& polygon, Kind kind, double min_contact) {
  std::vector<Edge> edges;
  std::vector<double> xs;
  auto addRing = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point a = ring[i], b = ring[(i + 1) % ring.size()];
      xs.push_back(a.x);
      if (a.x < b.x) edges.push_back({a, b});
      if (b.x < a.x) edges.push_back({b, a});
    }
  };
  addRing(polygon.outer);
  for (const Ring& hole : polygon.holes) addRing(hole);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::vector<std::size_t> by_left(edges.size());
  std::iota(by_left.begin(), by_left.end(), 0);
  std::stable_sort(by_left.begin(), by_left.end(),
                   [&](std::size_t p, std::size_t q) { return edges[p].left.x < edges[q].left.x; });

  Decomposition out;
  out.slabs = xs.size() > 1 ? xs.size() - 1 : 0;
  std::vector<std::size_t> active;
  std::vector<std::pair<double, std::size_t>> order;
  std::vector<Interval> previous, current;
  std::vector<Link> links;
  std::vector<bool> continued;
  std::size_t next_edge = 0;
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const double x0 = xs[k], x1 = xs[k + 1], mid = (x0 + x1) / 2.0;
    // Edges spanning this slab: started at or before x0, ending at or after x1.
    active.erase(std::remove_if(active.begin(), active.end(), [&](std::size_t e) { return edges[e].right.x <= x0; }),
                 active.end());
    while (next_edge < by_left.size() && edges[by_left[next_edge]].left.x <= x0) active.push_back(by_left[next_edge++]);
    order.clear();
    for (std::size_t e : active) order.push_back({edges[e].yAt(mid), e});
    std::sort(order.begin(), order.end());
    current.clear();
    for (std::size_t i = 0; i + 1 < order.size(); i += 2)
      if (order[i + 1].first > order[i].first) current.push_back({order[i].second, order[i + 1].second, 0, 0, 0});

    // Links with the previous slab's intervals across x0 (both lists are sorted bottom to top).
    links.clear();
    if (k > 0) {
      std::size_t i = 0, j = 0;
      while (i < previous.size() && j < current.size()) {
        const double a0 = edges[previous[i].floor].yAt(x0), a1 = edges[previous[i].ceiling].yAt(x0);
        const double b0 = edges[current[j].floor].yAt(x0), b1 = edges[current[j].ceiling].yAt(x0);
        const double y0 = std::max(a0, b0), y1 = std::min(a1, b1);
        if (y1 - y0 > min_contact) {
          links.push_back({i, j, y0, y1});
          ++previous[i].right_links;
          ++current[j].left_links;
        }
        (a1 < b1) ? ++i : ++j;
      }
    }
    continued.assign(current.size(), false);
    for (const Link& link : links) {
      const Interval& p = previous[link.left];
      Interval& c = current[link.right];
      const bool same =
          kind == Kind::Trapezoidal
              ? ((p.floor == c.floor || smoothJoin(edges[p.floor], edges[c.floor])) &&
                 (p.ceiling == c.ceiling || smoothJoin(edges[p.ceiling], edges[c.ceiling])))
              : (p.right_links == 1 && c.left_links == 1);
      if (same) {
        c.cell = p.cell;
        continued[link.right] = true;
      }
    }
    for (std::size_t j = 0; j < current.size(); ++j) {
      if (!continued[j]) {
        current[j].cell = out.cells.size();
        out.cells.emplace_back();
      }
      out.cells[current[j].cell].slices.push_back({x0, x1, edges[current[j].floor], edges[current[j].ceiling]});
    }
    for (const Link& link : links) {
      const std::size_t a = previous[link.left].cell, b = current[link.right].cell;
      if (a != b) out.contacts.push_back({a, b, x0, link.y0, link.y1});
    }
    std::swap(previous, current);
  }
  return out;
}

}  // namespace coverbench::decomposition
