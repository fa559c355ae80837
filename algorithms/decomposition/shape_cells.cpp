#include "shape_cells.hpp"

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

namespace coverbench::decomposition {
namespace {

/// The rows' frame turned by +90 degrees: rows along x become passes along y, as the cells are cut
/// (the sweep runs along x). A rotation, exact in doubles, so rings keep their orientation.
Point turned(Point p) { return {-p.y, p.x}; }

Region turned(const Region& region) {
  Region out = region;
  for (PolygonWithHoles& poly : out) {
    for (Point& p : poly.outer) p = turned(p);
    for (Ring& hole : poly.holes)
      for (Point& p : hole) p = turned(p);
  }
  return out;
}

/// A piece in the turned frame: a pass at x from y0 to y1 (its low-x end in the rows' frame is its
/// low end here).
struct Pass {
  std::size_t piece = 0;
  double x = 0.0, y0 = 0.0, y1 = 0.0;
};

/// The cell holding a pass: of the cells whose x range holds it, the one whose span at x overlaps
/// it most; cells.size() when none does.
std::size_t holdingCell(const Decomposition& cells, const Pass& pass) {
  constexpr double kSlack = 1e-9;
  std::size_t best = cells.cells.size();
  double best_overlap = -kSlack;
  for (std::size_t c = 0; c < cells.cells.size(); ++c) {
    const Cell& cell = cells.cells[c];
    if (pass.x < cell.minX() - kSlack || pass.x > cell.maxX() + kSlack) continue;
    const Span s = cell.spanAt(std::clamp(pass.x, cell.minX(), cell.maxX()));
    const double overlap = std::min(s.top, pass.y1) - std::max(s.bottom, pass.y0);
    if (overlap > best_overlap) best_overlap = overlap, best = c;
  }
  return best;
}


}  // namespace

ShapeCellOrder orderByCells(const ShapeRowPieces& rows, Kind kind, Order order, const TourCost& cost,
                            const std::function<bool()>& keep_going) {
  ShapeCellOrder out;
  const Decomposition all = decomposeParts(turned(rows.centres), kind, 0.0);
  // Each piece to the cell holding it; the cells holding none are left out of the tour.
  std::map<std::size_t, std::vector<Pass>> held;
  std::vector<RowPiece> outside;
  std::vector<std::size_t> outside_index;
  for (std::size_t k = 0; k < rows.pieces.size(); ++k) {
    const Point a = turned(rows.pieces[k].first), b = turned(rows.pieces[k].second);
    const Pass pass{k, a.x, a.y, b.y};
    const std::size_t c = holdingCell(all, pass);
    if (c == all.cells.size()) {
      outside.push_back(rows.pieces[k]);
      outside_index.push_back(k);
    } else {
      held[c].push_back(pass);
    }
  }
  std::vector<std::size_t> cell_of;  // tour index -> cell
  std::map<std::size_t, std::size_t> index_of;
  std::vector<CellEnds> ends;
  for (auto& [c, passes] : held) {
    std::sort(passes.begin(), passes.end(), [](const Pass& p, const Pass& q) { return std::tie(p.x, p.y0) < std::tie(q.x, q.y0); });
    index_of[c] = cell_of.size();
    cell_of.push_back(c);
    const auto ends_of = [](const Pass& p) { return PassEnds{{p.x, p.y0}, {p.x, p.y1}}; };
    ends.push_back(alternatingEnds(ends_of(passes.front()), ends_of(passes.back()), passes.size(), all.cells[c].centre()));
  }
  std::vector<CellLink> links;
  for (const Contact& contact : all.contacts) {
    const auto l = index_of.find(contact.left), r = index_of.find(contact.right);
    if (l != index_of.end() && r != index_of.end()) links.push_back({l->second, r->second});
  }
  TourCost tour = cost;
  if (tour.start) tour.start = turned(*tour.start);
  if (tour.end) tour.end = turned(*tour.end);
  const Ordering ordering = orderCells(ends, links, order, keep_going, tour);
  for (const Visit& visit : ordering.visits) {
    std::vector<Pass> passes = held[cell_of[visit.cell]];
    if ((visit.orientation & 1) != 0) std::reverse(passes.begin(), passes.end());
    bool down = (visit.orientation & 2) != 0;
    for (const Pass& pass : passes) {
      out.order.push_back({pass.piece, down});  // down in the turned frame: from the high-x end
      down = !down;
    }
  }
  // What no cell holds (none expected: the cells are the centres' region), nearest end first.
  if (!outside.empty()) {
    const Point at = out.order.empty() ? outside.front().first
                                       : (out.order.back().second ? rows.pieces[out.order.back().first].first
                                                                  : rows.pieces[out.order.back().first].second);
    for (const auto& [k, backwards] : nearestEndOrder(outside, at)) out.order.push_back({outside_index[k], backwards});
  }
  out.cells = cell_of.size();
  out.contacts = links.size();
  out.outside = outside.size();
  out.estimated_cost = ordering.estimated_cost;
  return out;
}

}  // namespace coverbench::decomposition
