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

Point Cell::centre() const {
  const double mid = (minX() + maxX()) / 2.0;
  const Span s = spanAt(mid);
  return {mid, (s.bottom + s.top) / 2.0};
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

/// Joins every sliver, a cell narrower than `width` along the sweep, to a cell it continues: on
/// its left, a cell that ends where the sliver begins and touches it there (the longest such
/// contact), else on its right, one that begins where the sliver ends. The slices of the two run
/// end to end, so the joined cell is x-monotone and lies in the polygon. The events joined stay
/// within `width` of the one where the cell ended (or began) before: a run of slivers joins one
/// cell only while it is that short. A cell that has grown to `width` is no sliver.
void mergeSlivers(Decomposition& d, double width) {
  const std::size_t n = d.cells.size();
  std::vector<double> first_end(n), first_begin(n);
  for (std::size_t i = 0; i < n; ++i) first_end[i] = d.cells[i].maxX(), first_begin[i] = d.cells[i].minX();
  std::vector<std::size_t> into(n);
  std::iota(into.begin(), into.end(), 0);
  auto root = [&](std::size_t i) {
    while (into[i] != i) i = into[i];
    return i;
  };
  // Contact indices by cell, on the cell's left side and on its right side (a joined cell holds
  // the lists of both parts; the x of a contact tells whether it lies at the cell's current end).
  std::vector<std::vector<std::size_t>> on_left(n), on_right(n);
  for (std::size_t k = 0; k < d.contacts.size(); ++k) {
    on_left[d.contacts[k].right].push_back(k);
    on_right[d.contacts[k].left].push_back(k);
  }
  // The cell across the longest contact at `x` in `list` whose own end (right end when it lies on
  // the left) is at x; n if none.
  auto partner = [&](std::size_t cell, const std::vector<std::size_t>& list, double x, bool partner_left) {
    std::size_t best = n;
    double longest = 0.0;
    for (std::size_t k : list) {
      const Contact& c = d.contacts[k];
      if (c.x != x) continue;
      const std::size_t other = root(partner_left ? c.left : c.right);
      if (other == cell) continue;
      const Cell& o = d.cells[other];
      if ((partner_left ? o.maxX() : o.minX()) != x || c.y1 - c.y0 <= longest) continue;
      best = other;
      longest = c.y1 - c.y0;
    }
    return best;
  };
  bool merged = false;
  for (std::size_t s = 0; s < n; ++s) {
    Cell& sliver = d.cells[s];
    if (sliver.maxX() - sliver.minX() >= width) continue;
    std::size_t target = partner(s, on_left[s], sliver.minX(), true);
    if (target != n && sliver.maxX() - first_end[target] >= width) target = n;
    const bool append = target != n;
    if (!append) target = partner(s, on_right[s], sliver.maxX(), false);
    if (!append && target != n && first_begin[target] - sliver.minX() >= width) target = n;
    if (target == n) continue;
    std::vector<Slice>& to = d.cells[target].slices;
    to.insert(append ? to.end() : to.begin(), sliver.slices.begin(), sliver.slices.end());
    sliver.slices.clear();
    for (auto* lists : {&on_left, &on_right})
      (*lists)[target].insert((*lists)[target].end(), (*lists)[s].begin(), (*lists)[s].end());
    into[s] = target;
    merged = true;
  }
  if (!merged) return;
  // The cells left, in sweep order again (a cell joined on its left begins earlier), and their
  // contacts, without those between the parts of one cell.
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (into[i] == i) kept.push_back(i);
  std::stable_sort(kept.begin(), kept.end(),
                   [&](std::size_t a, std::size_t b) { return d.cells[a].minX() < d.cells[b].minX(); });
  std::vector<std::size_t> index(n);
  std::vector<Cell> cells;
  for (std::size_t i : kept) {
    index[i] = cells.size();
    cells.push_back(std::move(d.cells[i]));
  }
  std::vector<Contact> contacts;
  for (Contact c : d.contacts) {
    c.left = index[root(c.left)], c.right = index[root(c.right)];
    if (c.left != c.right) contacts.push_back(c);
  }
  d.cells = std::move(cells);
  d.contacts = std::move(contacts);
}

}  // namespace

Decomposition decompose(const PolygonWithHoles& polygon, Kind kind, double min_contact, double merge_width) {
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
  if (merge_width > 0.0) mergeSlivers(out, merge_width);
  return out;
}

Decomposition decomposeParts(const Region& region, Kind kind, double merge_width,
                             const std::function<bool(const PolygonWithHoles&)>& keep) {
  Decomposition cells;
  for (const PolygonWithHoles& poly : region) {
    if (keep && !keep(poly)) continue;
    Decomposition d = decompose(poly, kind, 1e-9, merge_width);
    const std::size_t base = cells.cells.size();
    for (Contact& c : d.contacts) c.left += base, c.right += base;
    cells.cells.insert(cells.cells.end(), d.cells.begin(), d.cells.end());
    cells.contacts.insert(cells.contacts.end(), d.contacts.begin(), d.contacts.end());
    cells.slabs += d.slabs;
  }
  return cells;
}

}  // namespace coverbench::decomposition
