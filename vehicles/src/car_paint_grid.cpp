// The raster of what a path paints, and the fill passes found on it (car_paint_grid.hpp).
#include "car_paint_grid.hpp"

#include <algorithm>
#include <cmath>

#include "car_sweep_parts.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::vehicle_detail {

PaintGrid::PaintGrid(const Workspace& ws, double h) : h_(h), r_(ws.tool().radius()) {
  Box box = boundingBox(ws.free());
  origin_ = {box.min_x - r_ - h, box.min_y - r_ - h};
  nx_ = std::max(1, static_cast<int>(std::ceil((box.max_x - box.min_x + 2.0 * (r_ + h)) / h)));
  ny_ = std::max(1, static_cast<int>(std::ceil((box.max_y - box.min_y + 2.0 * (r_ + h)) / h)));
  cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0);
  std::vector<double> ys(static_cast<std::size_t>(ny_));
  for (int j = 0; j < ny_; ++j) ys[static_cast<std::size_t>(j)] = origin_.y + (j + 0.5) * h;
  const auto crossings = scanlineCrossings(allRings(ws.free()), ys);
  for (int j = 0; j < ny_; ++j) {
    const auto& line = crossings[static_cast<std::size_t>(j)];
    for (std::size_t k = 0; k + 1 < line.size(); k += 2) mark(j, line[k].x, line[k + 1].x, kFree | kReach);
  }
  // The reach: a disk of the tool's radius round each cell of F on its edge.
  const int d = static_cast<int>(std::floor(r_ / h_));
  std::vector<std::pair<int, int>> disk;
  for (int dj = -d; dj <= d; ++dj)
    for (int di = -d; di <= d; ++di)
      if ((di * di + dj * dj) * h_ * h_ <= r_ * r_) disk.emplace_back(di, dj);
  // A cell on F's edge: in F, with a 4-neighbour outside it (a row at a time, without branches).
  std::vector<std::uint8_t> edge(static_cast<std::size_t>(nx_), 0);
  for (int j = 1; j + 1 < ny_; ++j) {
    const std::uint8_t* row = &cells_[index(0, j)];
    const std::uint8_t *below = row - nx_, *above = row + nx_;
    for (int i = 1; i + 1 < nx_; ++i)
      edge[static_cast<std::size_t>(i)] = row[i] & static_cast<std::uint8_t>(~(row[i - 1] & row[i + 1] & below[i] & above[i])) & kFree;
    for (int i = 1; i + 1 < nx_; ++i) {
      if (!edge[static_cast<std::size_t>(i)]) continue;
      for (const auto& [di, dj] : disk)
        if (i + di >= 0 && i + di < nx_ && j + dj >= 0 && j + dj < ny_) cells_[index(i + di, j + dj)] |= kReach;
    }
  }
}

void PaintGrid::paint(const Path& path) {
  for (auto& cell : cells_) cell &= static_cast<std::uint8_t>(~kPainted);
  paintMore(path, 0);
}

void PaintGrid::paintMore(const Path& path, std::size_t first) {
  forEachPaintedChord(path, 0.1 * h_, first, [&](Point p, Point q) { capsule(p, q); });
}

void PaintGrid::paintSegment(const Path& path, std::size_t i) {
  forEachChordOf(path, i, 0.1 * h_, [&](Point p, Point q) { capsule(p, q); });
}

std::pair<std::size_t, std::size_t> PaintGrid::openIn(Point p, Point q) const {
  std::size_t open_cells = 0, reach_cells = 0;
  capsuleRows(p, q, [&](int j, double x0, double x1) {
    const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - origin_.x) / h_ - 0.5)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - origin_.x) / h_ - 0.5)));
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = index(i, j);
      reach_cells += (cells_[c] & kReach) != 0;
      open_cells += open(c);
    }
  });
  return {open_cells, reach_cells};
}

bool PaintGrid::openAlong(const Path& path, std::size_t i, double share) const {
  std::pair<std::size_t, std::size_t> cells{0, 0};
  forEachChordOf(path, i, 0.1 * h_, [&](Point p, Point q) {
    const auto [o, r] = openIn(p, q);
    cells.first += o;
    cells.second += r;
  });
  return enoughOpen(cells, share);
}

double PaintGrid::reach() const {
  std::size_t count = 0;
  for (std::uint8_t cell : cells_) count += (cell & kReach) != 0;
  return static_cast<double>(count) * h_ * h_;
}

double PaintGrid::painted() const {
  std::size_t count = 0;
  for (std::uint8_t cell : cells_) count += (cell & kReach) && (cell & kPainted);
  return static_cast<double>(count) * h_ * h_;
}

std::vector<CarRow> PaintGrid::passes(Workspace& ws, double spacing, double min_area, double rho, bool forward_only, double min_pass) {
  std::vector<CarRow> out;
  std::vector<int> piece(cells_.size(), -1);
  std::vector<std::size_t> stack, members;
  int pieces = 0;
  for (std::size_t seed = 0; seed < cells_.size(); ++seed) {
    if (!open(seed) || piece[seed] >= 0) continue;
    members.clear();
    piece[seed] = pieces;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      members.push_back(c);
      const int i = static_cast<int>(c % static_cast<std::size_t>(nx_)), j = static_cast<int>(c / static_cast<std::size_t>(nx_));
      for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        if (i + di < 0 || i + di >= nx_ || j + dj < 0 || j + dj >= ny_) continue;
        const std::size_t d = index(i + di, j + dj);
        if (open(d) && piece[d] < 0) {
          piece[d] = pieces;
          stack.push_back(d);
        }
      }
    }
    const int id = pieces++;
    if (static_cast<double>(members.size()) * h_ * h_ < min_area) continue;
    // The principal axis of the piece's cells.
    double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
    for (std::size_t c : members) {
      const Point p = centre(c) - origin_;
      sx += p.x, sy += p.y, sxx += p.x * p.x, syy += p.y * p.y, sxy += p.x * p.y;
    }
    const double n = static_cast<double>(members.size()), cx = sx / n, cy = sy / n;
    const double axis = 0.5 * std::atan2(2.0 * (sxy / n - cx * cy), (sxx / n - cx * cx) - (syy / n - cy * cy));
    const std::size_t before = out.size();
    for (int turn = 0; turn < 2 && out.size() == before; ++turn) {
      const double theta = axis + turn * M_PI / 2.0;
      const Point u{std::cos(theta), std::sin(theta)}, v{-u.y, u.x};
      double lo_u = INFINITY, hi_u = -INFINITY, lo_v = INFINITY, hi_v = -INFINITY;
      for (std::size_t c : members) {
        const Point p = centre(c);
        lo_u = std::min(lo_u, dot(p, u)), hi_u = std::max(hi_u, dot(p, u));
        lo_v = std::min(lo_v, dot(p, v)), hi_v = std::max(hi_v, dot(p, v));
      }
      lo_v -= h_ / 2.0, hi_v += h_ / 2.0;
      const int lines = std::max(1, static_cast<int>(std::ceil((hi_v - lo_v) / spacing - 1e-9)));
      const int near = static_cast<int>(std::ceil(0.5 * r_ / h_));
      // A piece one line wide whose middle line gives no pass (it lies beyond F's edge, along a
      // wall or an obstacle): that line moved across by half a tool radius, then a whole one.
      const int tries = lines == 1 ? 5 : lines;
      for (int line = 0; line < tries; ++line) {
        if (lines == 1 && out.size() > before) break;
        const double shift = lines == 1 ? (line == 0 ? 0.0 : (line % 2 ? 1.0 : -1.0) * ((line + 1) / 2) * 0.5 * r_) : 0.0;
        const double at_v = (lo_v + hi_v) / 2.0 + (lines == 1 ? shift : (line - (lines - 1) / 2.0) * spacing);
        // Samples every half cell from a tool radius before the piece to a tool radius after it.
        const double step = h_ / 2.0;
        const int samples = static_cast<int>(std::ceil((hi_u - lo_u + 2.0 * r_) / step)) + 1;
        int first = -1;
        for (int k = 0; k <= samples; ++k) {
          const Point p = u * (lo_u - r_ + k * step) + v * at_v;
          const bool in = k < samples && inFree(p) && nearPiece(p, piece, id, near);
          if (in && first < 0) first = k;
          if (in || first < 0) continue;
          Point a = u * (lo_u - r_ + first * step) + v * at_v, b = u * (lo_u - r_ + (k - 1) * step) + v * at_v;
          first = -1;
          for (int shrink = 0; shrink < 3 && distance(a, b) >= min_pass && !ws.router().isFree(a, b); ++shrink) {
            a = a + u * h_;
            b = b - u * h_;
          }
          if (distance(a, b) < min_pass || dot(b - a, u) <= 0.0 || !ws.router().isFree(a, b)) continue;
          if (forward_only && !leaveRoomToTurn(ws, a, b, rho, rho, rho, min_pass)) continue;
          out.push_back({a, b, 0, false});
        }
      }
    }
  }
  return out;
}

bool PaintGrid::nearPiece(Point p, const std::vector<int>& piece, int id, int near) const {
  int i = 0, j = 0;
  cellOf(p, i, j);
  for (int dj = -near; dj <= near; ++dj)
    for (int di = -near; di <= near; ++di)
      if (i + di >= 0 && i + di < nx_ && j + dj >= 0 && j + dj < ny_ && piece[index(i + di, j + dj)] == id) return true;
  return false;
}

inline void PaintGrid::mark(int j, double x0, double x1, std::uint8_t bit) {
  const int i0 = std::max(0, static_cast<int>(std::ceil((x0 - origin_.x) / h_ - 0.5)));
  const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((x1 - origin_.x) / h_ - 0.5)));
  for (int i = i0; i <= i1; ++i) cells_[index(i, j)] |= bit;
}

void PaintGrid::capsule(Point p, Point q) {
  capsuleRows(p, q, [&](int j, double lo, double hi) { mark(j, lo, hi, kPainted); });
}

template <class Row>
void PaintGrid::capsuleRows(Point p, Point q, Row&& row) const {
  const double len = distance(p, q);
  const Point nrm = len > 0.0 ? Point{-(q.y - p.y) / len, (q.x - p.x) / len} * r_ : Point{0.0, 0.0};
  const Point quad[4] = {p + nrm, q + nrm, q - nrm, p - nrm};
  const int j0 = std::max(0, static_cast<int>(std::ceil((std::min(p.y, q.y) - r_ - origin_.y) / h_ - 0.5)));
  const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((std::max(p.y, q.y) + r_ - origin_.y) / h_ - 0.5)));
  for (int j = j0; j <= j1; ++j) {
    const double y = origin_.y + (j + 0.5) * h_;
    double lo = INFINITY, hi = -INFINITY;
    for (const Point& c : {p, q}) {
      const double dy = y - c.y;
      if (std::fabs(dy) > r_) continue;
      const double half = std::sqrt(r_ * r_ - dy * dy);
      lo = std::min(lo, c.x - half), hi = std::max(hi, c.x + half);
    }
    if (len > 0.0)
      for (int e = 0; e < 4; ++e) {
        const Point a = quad[e], b = quad[(e + 1) % 4];
        if ((a.y - y) * (b.y - y) > 0.0 || a.y == b.y) continue;
        const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
        lo = std::min(lo, x), hi = std::max(hi, x);
      }
    if (lo <= hi) row(j, lo, hi);
  }
}

}  // namespace coverbench::vehicle_detail
