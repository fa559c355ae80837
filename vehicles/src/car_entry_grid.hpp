#pragma once
// The rows' ends in a grid, walked nearest first: where a step of the car's sweep (car_row_sweep.cpp)
// looks for the next row. Private to vehicles/src.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "coverbench/car_sweep.hpp"

namespace coverbench::vehicle_detail {

/// A sweep step's candidate: a row entered from one end, with the straight distance to that end
/// (a curve is never shorter).
struct Candidate {
  double bound;
  std::size_t row;
  bool from_a;
};

/// The order candidates are taken in: nearest first, ties by row and then end.
bool farther(const Candidate& p, const Candidate& q) {
  return p.bound > q.bound || (p.bound == q.bound && (p.row > q.row || (p.row == q.row && p.from_a < q.from_a)));
}

/// The rows' ends in a uniform grid, so that a step of the sweep looks at the cells about the car
/// rather than at every row's ends. `NearestFirst` walks it.
class EntryGrid {
 public:
  EntryGrid(const std::vector<CarRow>& rows, double cell) : rows_(rows), cell_(cell) {
    if (rows.empty()) return;
    lo_ = hi_ = rows.front().a;
    for (const CarRow& r : rows)
      for (Point p : {r.a, r.b}) {
        lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
        hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y)};
      }
    nx_ = static_cast<long>((hi_.x - lo_.x) / cell_) + 1;
    ny_ = static_cast<long>((hi_.y - lo_.y) / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_ * ny_));
    row_ends_.assign(static_cast<std::size_t>(ny_), 0);
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (bool from_a : {true, false}) {
        const Point p = from_a ? rows[i].a : rows[i].b;
        cells_[static_cast<std::size_t>(cellY(p) * nx_ + cellX(p))].push_back(2 * i + (from_a ? 0 : 1));
        ++row_ends_[static_cast<std::size_t>(cellY(p))];
      }
    ends_ = 2 * rows.size();
  }
  /// A row painted is taken out of the grid (its ends are never candidates: `keep` admits no
  /// painted row), and put back when a backtrack unpaints it; the sweep then walks past fewer ends.
  void setPainted(std::size_t row, bool painted) {
    for (bool from_a : {true, false}) {
      const Point p = from_a ? rows_[row].a : rows_[row].b;
      std::vector<std::size_t>& ends = cells_[static_cast<std::size_t>(cellY(p) * nx_ + cellX(p))];
      const std::size_t id = 2 * row + (from_a ? 0 : 1);
      std::size_t& in_row = row_ends_[static_cast<std::size_t>(cellY(p))];
      if (!painted) {
        ends.push_back(id);
        ++in_row, ++ends_;
      } else if (const auto at = std::find(ends.begin(), ends.end(), id); at != ends.end()) {
        *at = ends.back();  // the order within a cell is immaterial: candidates come out in `farther`'s order
        ends.pop_back();
        --in_row, --ends_;
      }
    }
  }
  long cellX(Point p) const { return static_cast<long>(std::floor((p.x - lo_.x) / cell_)); }
  long cellY(Point p) const { return static_cast<long>(std::floor((p.y - lo_.y) / cell_)); }

  /// The candidates from `from`, nearest first in `farther`'s order, among the ends `keep(row,
  /// from_a)` admits. Cells are visited in square rings about `from`'s cell: once rings 0..k are
  /// seen, every end not yet seen is at least k cells away, so a seen one nearer than that is next.
  template <class Keep>
  class NearestFirst {
   public:
    NearestFirst(const EntryGrid& grid, Point from, Keep keep)
        : grid_(grid), from_(from), keep_(std::move(keep)), cx_(grid.cellX(from)), cy_(grid.cellY(from)) {
      last_ring_ = std::max({cx_, grid.nx_ - 1 - cx_, cy_, grid.ny_ - 1 - cy_, 0L});
    }
    /// The next candidate, or nothing when every admitted end was returned.
    std::optional<Candidate> next() {
      while (true) {
        const bool all_seen = ring_ > last_ring_ || visited_ == grid_.ends_;
        if (!seen_.empty() && (all_seen || seen_.front().bound < static_cast<double>(ring_ - 1) * grid_.cell_)) {
          std::pop_heap(seen_.begin(), seen_.end(), farther);
          const Candidate c = seen_.back();
          seen_.pop_back();
          return c;
        }
        if (all_seen) return std::nullopt;
        visitRing(ring_++);
      }
    }

   private:
    void visitCell(long x, long y) {
      const std::vector<std::size_t>& ends = grid_.cells_[static_cast<std::size_t>(y * grid_.nx_ + x)];
      visited_ += ends.size();
      for (std::size_t id : ends) {
        const std::size_t row = id / 2;
        const bool from_a = id % 2 == 0;
        if (!keep_(row, from_a)) continue;
        const Point d = (from_a ? grid_.rows_[row].a : grid_.rows_[row].b) - from_;
        seen_.push_back({std::sqrt(d.x * d.x + d.y * d.y), row, from_a});
        std::push_heap(seen_.begin(), seen_.end(), farther);
      }
    }
    /// The cells k cells from `from`'s (in the square metric) that lie in the grid, in grid rows
    /// holding ends.
    void visitRing(long k) {
      const long x0 = std::max(cx_ - k, 0L), x1 = std::min(cx_ + k, grid_.nx_ - 1);
      for (long y = std::max(cy_ - k, 0L), y1 = std::min(cy_ + k, grid_.ny_ - 1); y <= y1; ++y) {
        if (grid_.row_ends_[static_cast<std::size_t>(y)] == 0) continue;
        if (y == cy_ - k || y == cy_ + k) {
          for (long x = x0; x <= x1; ++x) visitCell(x, y);
        } else {
          if (cx_ - k >= 0 && cx_ - k < grid_.nx_) visitCell(cx_ - k, y);
          if (k > 0 && cx_ + k >= 0 && cx_ + k < grid_.nx_) visitCell(cx_ + k, y);
        }
      }
    }
    const EntryGrid& grid_;
    Point from_;
    Keep keep_;
    long cx_, cy_, last_ring_;
    long ring_ = 0;  // rings 0..ring_-1 are seen
    std::size_t visited_ = 0;  // ends in the cells visited, admitted or not
    std::vector<Candidate> seen_;  // a heap in `farther`'s order
  };

 private:
  const std::vector<CarRow>& rows_;
  double cell_;
  Point lo_{}, hi_{};
  long nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::size_t>> cells_;  // 2 * row + (0 for end a, 1 for end b)
  std::vector<std::size_t> row_ends_;  // ends in each row of cells
  std::size_t ends_ = 0;               // ends in the grid
};

}  // namespace coverbench::vehicle_detail
